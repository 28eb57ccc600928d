"""GraspStateMachine: the tactile-event grasping algorithm (Sec. II-B, III-C, Fig. 6b) as a
Drake LeafSystem.

Each tick (config.update_period_s) it summarises its inputs into an Observation, asks the
pure rule (transition_logic.next_mode) for the next mode, and carries out the motion of the
mode it is in: smooth (minimum-jerk) translations of the grasp frame at the side-grasp
orientation, and Robotiq-style gripper requests. Everything it remembers is in one abstract
state value (MachineState), so a Context holds the whole run, timeline included.

Motion of each mode (world frame, grasp frame G; the stroke is world y; the corrective
actions' decisions and moves are in corrective_actions.py):
  Reach     move to the expected object position at grasp height, then close
  Re-Reach  open, shift along the stroke toward the finger that touched first by the offset
            its contact implies, (then Reach closes again); the taxel_aware controller also
            shifts along the approach axis by the contact's offset on the pads (by the
            pad's half length after a first touch beyond the pads, which stops the close:
            taxel_corrections.touched_beyond_pads), goes to the midpoint of the two faces
            when a finger touches alone after the other touched at an earlier close
            (taxel_corrections.bracketed_object), and opens without a shift to re-grasp an
            object it put down because it sat tilted
  Load      keep closing at the grip force (raised by each Lift-Load)
  Lift      rise by lift_height;  Hold: stay;  Avoid: move avoid_distance along the hit
  Place     descend to place_press below the lift-off height (stops at the Place-Unload event)
  Unload    open where it is, then retract along the approach and up
  Done      stay;  Failed: stay, the gripper keeps its last request (the object is not dropped)
"""

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.control.corrective_actions import (
    Counters, avoid_move, hit_baseline_history, is_hit, lift_load_grip_force,
    pad_accelerations_in_world, re_reach_shift, re_reach_target)
from tegrasp_drake.control.finger_strike import (side_moment_nm, strike_force_n, strike_shift,
                                                 struck_finger)
from tegrasp_drake.control.grasp_modes import Mode, Stage, Transition, Trigger
from tegrasp_drake.control.motion_profiles import MotionSegment
from tegrasp_drake.control.taxel_contact import grasp_contact
from tegrasp_drake.control.taxel_corrections import (
    FaceTouch, Shift, beyond_pads_shift, bracketed_object, caged_behind_pads, held_tilted,
    opposite_face, pushed_distance_m, release_topples, remembered_faces, taxel_re_reach_shift,
    touched_beyond_pads, touched_face, touched_faces)
from tegrasp_drake.control.scripted_grasp import gripper_command, grasp_frame_xy
from tegrasp_drake.control.transition_logic import (
    HOLDING_MODES, TAXEL_AWARE, Observation, memorized_corrective_trigger, next_mode)
from tegrasp_drake.events.transitions import (CORRECTIVE_TRANSITIONS, NO_EVENT,
                                              REQUIRED_TRANSITIONS, transition_states)
from tegrasp_drake.rig import robotiq_units as ru
from tegrasp_drake.rig.arm_kinematics import R_WG_SIDE_GRASP
from tegrasp_drake.rig.channels import CHANNEL_NAMES, TAXELS_PER_PAD

OPENING_SPEED_MPS = 0.1  # when opening to re-reach or unload
GRIPPER_STATUS_LAG_S = 0.1  # gOBJ is trusted this long after a new request
# The event each mode checks for (the expected event): the event-triggered transition that
# leaves it.
EXPECTED_TRANSITION = {Mode.from_label(transition_states(name)[0]): name
                       for name in REQUIRED_TRANSITIONS}
# The memorized corrective event each mode checks for (when named in
# controller.memorized_corrective_events): the corrective transition that leaves it.
EXPECTED_CORRECTIVE_TRANSITION = {Mode.from_label(transition_states(name)[0]): name
                                  for name in CORRECTIVE_TRANSITIONS}


@dataclasses.dataclass(frozen=True)
class MachineState:
    """Everything the machine remembers (times in s of simulated time)."""
    mode: Mode
    mode_start: float
    segment: MotionSegment
    gripper: tuple  # (opening [m], speed [m/s], force [N]) requested
    gripper_request_time: float
    grip_force: float
    stage: Stage = Stage.NONE  # the step within a mode
    counters: Counters = Counters()
    closing_since: float = -1.0
    one_sided_since: float = -1.0
    slip_since: float = -1.0
    motion_done_since: float = -1.0
    reentry_offset: float = 0.0  # Re-Reach shift along world y [m]
    reentry_offset_x: float = 0.0  # Re-Reach shift along world x [m] (taxel_aware)
    tilted_since: float = -1.0  # Hold: since when the object sits tilted (taxel_aware) [s]
    regrasp_pending: bool = False  # the Place puts a tilted object down to re-grasp it
    approach_contact_since: float = -1.0  # a pad touched while approaching (taxel_aware) [s]
    # The gripper's opening [m] when a pad first touched in this close (taxel_aware; -1: none).
    first_touch_opening_m: float = -1.0
    # The contact's offset along the approach axis [m, pad +y] at that first touch, kept
    # until the next Re-Reach (read again in Load; 0: no pad has touched).
    first_touch_offset_m: float = 0.0
    # The pad alone at that first touch ("left", "right"; "" both or none).
    first_touch_finger: str = ""
    resume_approach: bool = False  # the Re-Reach stopped the approach: finish it, then close
    # The faces the fingers in contact pressed when the last Re-Reaches began from a close
    # (taxel_aware, taxel_corrections.remembered_faces: the latest of each finger); () after
    # a Re-Reach that began otherwise.
    touched_faces: tuple = ()
    # The finger-strike sense (taxel_aware, finger_strike.py): the wrench on G at the
    # approach's start [N m, N], since when the force beyond it exceeds the threshold [s],
    # the side moment summed over those ticks [N m], and the finger they point to.
    strike_baseline: tuple = ()
    strike_since: float = -1.0
    strike_moment_sum: float = 0.0
    strike_finger: str = ""  # the struck finger those ticks say ("left", "right", "" unknown)
    sa_before: tuple = (0.0, 0.0)  # SA [N] at the last Hold tick (the hit's baseline)
    # The memorized hit trigger's: the last Hold ticks' SA (hit_baseline_history).
    sa_history: tuple = ()
    acceleration_sum: tuple = (0.0, 0.0, 0.0)  # Avoid sensing: pads' world acceleration sum
    sa_gain_sum: tuple = (0.0, 0.0)  # Avoid sensing: SA gains over sa_before, summed
    timeline: tuple[Transition, ...] = ()
    failure: str = ""

    def __deepcopy__(self, memo):
        # Never mutated once stored (each tick stores a new one), so a copy can share it;
        # Drake copies abstract state often, and a deep copy of the timeline is costly.
        return self


@dataclasses.dataclass(frozen=True)
class GraspPlan:
    """Where and how far to move, from the scenario (its `grasp` section) [m, s, N]."""
    start_xyz: tuple
    object_xy: tuple  # the grasp frame's target for the expected object (grasp_frame_xy)
    object_width: float  # along the stroke, for the Re-Reach shift
    grasp_height: float
    object_height: float  # for whether a pushed object stands when let go (taxel_aware)
    lift_height: float
    place_press: float
    settle_s: float
    reach_s: float
    lift_s: float
    hold_s: float
    place_s: float
    unload_s: float
    retract_s: float
    retract_distance: float
    close_speed: float
    grip_force: float

    @staticmethod
    def from_scenario(scenario) -> "GraspPlan":
        g = scenario.grasp
        return GraspPlan(
            start_xyz=tuple(scenario.arm.initial_gripper_xyz),
            object_xy=tuple(grasp_frame_xy(scenario)),
            object_width=scenario.object.width_along_stroke(), grasp_height=g.grasp_height,
            object_height=scenario.object.height(),
            lift_height=g.lift_height, place_press=g.place_press, settle_s=g.settle_s,
            reach_s=g.reach_s, lift_s=g.lift_s, hold_s=g.hold_s, place_s=g.place_s,
            unload_s=g.unload_s, retract_s=g.retract_s, retract_distance=g.retract_distance,
            close_speed=g.close_speed, grip_force=g.grip_force)


class GraspStateMachine(LeafSystem):
    """The grasping state machine.

    .. pydrake_system::

        name: GraspStateMachine
        input_ports:
        - match
        - scores
        - channels
        - gripper.status
        - pad_acceleration (optional)
        - slip_vibration
        - device_fault (optional)
        - taxel_forces (optional)
        - corrective_match (optional)
        - grasp_wrench (optional)
        output_ports:
        - X_WG_desired
        - gripper_command
        - expected_event
        - mode
        - corrective_expected_event

    Ports:
        match: [1] when the detector matches the expected event, else [0].
        scores: the detector's four channel scores (logged with each transition).
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2), Eq. 1-2.
        gripper.status: the 2F-85 status bytes (robotiq_units order).
        pad_acceleration: [left xyz, right xyz] (m/s^2, pad frames), for the Avoid
            direction; unconnected: Avoid moves straight up.
        slip_vibration: [left, right] the pads' vibration in the slip band (m/s^2,
            tactile.slip_vibration_band), for Lift-Load.
        device_fault: an abstract str, "" when all devices are alive, else the watchdog's
            message; unconnected: no faults.
        taxel_forces: [left 12, right 12] taxel forces (N, taxel_layout order); read by
            the taxel_aware controller only, which needs it connected.
        corrective_match: [1] when the corrective EventMatcher matches the mode's
            memorized corrective event, else [0]; read with memorized corrective triggers
            only (controller.memorized_corrective_events), which need it connected.
        grasp_wrench: [Mx, My, Mz, Fx, Fy, Fz] (N m, N; world) on the arm at the grasp
            frame, from the arm's joint torques (GraspWrenchEstimator); read by the
            taxel_aware controller's finger-strike sense; unconnected: no such sense.
        X_WG_desired: RigidTransform, the grasp frame's desired pose in world.
        gripper_command: [rPR, rSP, rFR] bytes.
        expected_event: [index] of the event the detector should check, -1 for none. It
            depends only on the state (the detector's `match` feeds back to this system).
        mode: [Mode value].
        corrective_expected_event: [index] of the corrective event the corrective matcher
            should check (slip in Lift, a hit in Hold), -1 for none or without memorized
            corrective triggers; depends only on the state.
    """

    def __init__(self, *, plan: GraspPlan, config, event_indices: dict,
                 event_trigger: Trigger, corrective_event_indices: dict | None = None):
        super().__init__()
        self._plan = plan
        self._config = config
        self._event_indices = dict(event_indices)
        self._event_trigger = event_trigger
        missing = [t for t in EXPECTED_TRANSITION.values() if t not in self._event_indices]
        if missing:
            raise ValueError(f"the event detector has no event for {missing}")
        self._corrective_event_indices = dict(corrective_event_indices or {})
        self._memorized_corrective = tuple(
            t for t in CORRECTIVE_TRANSITIONS if memorized_corrective_trigger(config, t))
        missing = [t for t in self._memorized_corrective
                   if t not in self._corrective_event_indices]
        if missing:
            raise ValueError(f"memorized corrective triggers need the corrective events "
                             f"{missing}")
        self._match = self.DeclareVectorInputPort("match", 1)
        self._scores = self.DeclareVectorInputPort("scores", len(CHANNEL_NAMES))
        self._channels = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._status = self.DeclareVectorInputPort("gripper.status", ru.STATUS_SIZE)
        self._pad_acceleration = self.DeclareVectorInputPort("pad_acceleration", 6)
        self._slip_vibration = self.DeclareVectorInputPort("slip_vibration", 2)
        self._device_fault = self.DeclareAbstractInputPort("device_fault", AbstractValue.Make(""))
        self._taxel_forces = self.DeclareVectorInputPort("taxel_forces", 2 * TAXELS_PER_PAD)
        self._corrective_match = self.DeclareVectorInputPort("corrective_match", 1)
        self._grasp_wrench = self.DeclareVectorInputPort("grasp_wrench", 6)
        self._taxel_aware = getattr(config, "name", "") == TAXEL_AWARE
        self._state = self.DeclareAbstractState(AbstractValue.Make(self.initial_state()))
        self.DeclarePeriodicUnrestrictedUpdateEvent(config.update_period_s, 0.0, self._update)
        state_only = {self.abstract_state_ticket(self._state)}
        self.DeclareAbstractOutputPort(
            "X_WG_desired", lambda: AbstractValue.Make(RigidTransform()), self._calc_pose,
            prerequisites_of_calc=state_only | {self.time_ticket()})
        self.DeclareVectorOutputPort("gripper_command", ru.COMMAND_SIZE, self._calc_gripper,
                                     prerequisites_of_calc=state_only)
        self.DeclareVectorOutputPort("expected_event", 1, self._calc_expected_event,
                                     prerequisites_of_calc=state_only)
        self.DeclareVectorOutputPort("mode", 1, self._calc_mode,
                                     prerequisites_of_calc=state_only)
        self.DeclareVectorOutputPort("corrective_expected_event", 1,
                                     self._calc_corrective_expected_event,
                                     prerequisites_of_calc=state_only)

    # ---- construction helpers -------------------------------------------------------

    def initial_state(self) -> MachineState:
        p = self._plan
        grasp = (*p.object_xy, p.grasp_height)
        return MachineState(
            mode=Mode.REACH, mode_start=0.0,
            segment=MotionSegment(p.settle_s, p.reach_s, p.start_xyz, grasp),
            gripper=(ru.STROKE_M, p.close_speed, p.grip_force), gripper_request_time=0.0,
            grip_force=p.grip_force, stage=Stage.MOVING)

    def state(self, context) -> MachineState:
        return context.get_abstract_state(self._state).get_value()

    def transitions(self, context) -> tuple[Transition, ...]:
        """The transitions so far, in order."""
        return self.state(context).timeline

    def timeline(self, context) -> list[dict]:
        """The transitions so far in their JSON form (Transition.as_dict): dicts with t,
        from, to, trigger, reason, scores."""
        return [transition.as_dict() for transition in self.transitions(context)]

    # ---- outputs -----------------------------------------------------------------------

    def _calc_pose(self, context, output):
        position = self.state(context).segment.position(context.get_time())
        output.set_value(RigidTransform(R_WG_SIDE_GRASP, position))

    def _calc_gripper(self, context, output):
        output.SetFromVector(gripper_command(*self.state(context).gripper))

    def _calc_expected_event(self, context, output):
        transition = EXPECTED_TRANSITION.get(self.state(context).mode)
        output.SetAtIndex(0, self._event_indices[transition] if transition else NO_EVENT)

    def _calc_corrective_expected_event(self, context, output):
        transition = EXPECTED_CORRECTIVE_TRANSITION.get(self.state(context).mode)
        output.SetAtIndex(0, self._corrective_event_indices[transition]
                          if transition in self._memorized_corrective else NO_EVENT)

    def _calc_mode(self, context, output):
        output.SetAtIndex(0, float(self.state(context).mode))

    # ---- the tick ----------------------------------------------------------------------

    def _update(self, context, state):
        t = context.get_time()
        s = self._advance_stage(self.state(context), t, context)
        observation, s = self._observe(s, t, context)
        decision = next_mode(s.mode, observation, s.counters, self._config,
                             event_trigger=self._event_trigger, hold_s=self._plan.hold_s)
        if decision is not None:
            s = self._enter(s, decision, t, context)
        state.get_mutable_abstract_state(self._state).set_value(s)

    def _opening(self, context) -> float:
        return float(ru.opening_from_position_byte(self._status.Eval(context)[ru.STATUS_PO]))

    def _gripper_settled(self, s: MachineState, t: float) -> bool:
        return t - s.gripper_request_time >= GRIPPER_STATUS_LAG_S

    def _advance_stage(self, s: MachineState, t: float, context) -> MachineState:
        """Steps within a mode: close after the reach, shift after opening, retract after
        releasing."""
        p = self._plan
        if s.mode == Mode.REACH and s.stage == Stage.MOVING and s.segment.done(t):
            return dataclasses.replace(
                s, stage=Stage.CLOSING, closing_since=t, gripper_request_time=t,
                gripper=(0.0, p.close_speed, s.grip_force))
        if s.mode == Mode.AVOID and s.stage == Stage.SENSING:
            return self._sense_hit(s, t, context)
        if s.mode in (Mode.RE_REACH, Mode.UNLOAD) and s.stage == Stage.OPENING:
            opened = self._opening(context) >= self._config.opened_m
            if opened and self._gripper_settled(s, t):
                here = s.segment.position(t)
                if s.mode == Mode.RE_REACH:
                    target = re_reach_target(here, s.reentry_offset) + np.array(
                        [s.reentry_offset_x, 0.0, 0.0])
                    duration = self._config.re_reach_move_s
                else:
                    # Back to the start pose's distance (nearer, the wrist nears its singularity).
                    target = np.array([max(here[0] - p.retract_distance, p.start_xyz[0]),
                                       here[1], p.start_xyz[2]])
                    duration = p.retract_s
                return dataclasses.replace(s, stage=Stage.MOVING,
                                           segment=MotionSegment(t, duration, tuple(here),
                                                                 tuple(target)))
        return s

    def _sense_hit(self, s: MachineState, t: float, context) -> MachineState:
        """Avoid: gather which way the hit pushed, then start moving away from it."""
        config = self._config
        total = np.asarray(s.acceleration_sum)
        if self._pad_acceleration.HasValue(context):
            total = total + pad_accelerations_in_world(
                self._pad_acceleration.Eval(context)).sum(axis=0)
        # The push shows in SA for a few samples and then rings: sum it over the sensing.
        gain = np.asarray(s.sa_gain_sum) + (self._channels.Eval(context)[:2]
                                            - np.asarray(s.sa_before))
        if t - s.mode_start < config.avoid_sense_s:
            return dataclasses.replace(s, acceleration_sum=tuple(total), sa_gain_sum=tuple(gain))
        here = s.segment.position(t)
        move = avoid_move(here, gain, total, config)
        entry = dataclasses.replace(
            s.timeline[-1], direction=tuple(round(float(x), 3) for x in move.direction_W),
            delta_sa_n=tuple(round(float(x), 3) for x in move.delta_sa_n))
        return dataclasses.replace(
            s, stage=Stage.MOVING, timeline=s.timeline[:-1] + (entry,),
            segment=MotionSegment(t, config.avoid_s, tuple(here), tuple(move.p_end_W)))

    def _observe(self, s: MachineState, t: float, context):
        """The tick's Observation, and the state with its running timers updated."""
        config = self._config
        channels = self._channels.Eval(context)
        contact = self._sa_contact(channels)
        one_sided = contact[0] != contact[1]
        one_sided_since = (s.one_sided_since if s.one_sided_since >= 0 else t) if one_sided \
            else -1.0
        ra = float(max(channels[2], channels[3]))
        slip_vibration = float(max(self._slip_vibration.Eval(context)))
        slipping = s.mode == Mode.LIFT and slip_vibration > config.slip_vibration_mps2
        slip_since = (s.slip_since if s.slip_since >= 0 else t) if slipping else -1.0
        moving_stage = s.stage in (Stage.MOVING, Stage.NONE)
        motion_done = moving_stage and s.segment.done(t)
        motion_done_since = ((s.motion_done_since if s.motion_done_since >= 0 else t)
                             if motion_done else -1.0)
        status = self._status.Eval(context)
        closing = s.mode == Mode.REACH and s.stage == Stage.CLOSING
        # Only a status that echoes the close request (gPR = rPR) says where the fingers
        # stopped: a late status from the open request also reads "at requested position".
        closed_on_nothing = (
            closing and self._gripper_settled(s, t) and not any(contact)
            and status[ru.STATUS_PR] == gripper_command(*s.gripper)[ru.COMMAND_POSITION]
            and int(status[ru.STATUS_OBJ]) == ru.ObjectStatus.AT_REQUESTED_POSITION)
        fault_code = int(status[ru.STATUS_FLT])
        device_fault = self._device_fault.Eval(context) if self._device_fault.HasValue(
            context) else ""
        time_in_mode = t - s.mode_start
        taxel_fields, tilted_since = {}, -1.0
        if self._taxel_aware:
            shape = grasp_contact(self._taxel_forces.Eval(context))
            tilted = s.mode == Mode.HOLD and held_tilted(shape, config.taxel_aware)
            tilted_since = (s.tilted_since if s.tilted_since >= 0 else t) if tilted else -1.0
            approaching = s.mode == Mode.REACH and s.stage == Stage.MOVING and any(contact)
            approach_since = ((s.approach_contact_since if s.approach_contact_since >= 0
                               else t) if approaching else -1.0)
            s = dataclasses.replace(s, approach_contact_since=approach_since)
            s, strike_fields = self._sense_strike(s, t, context, contact)
            taxel_fields.update(strike_fields)
            opening = self._opening(context)
            # The close goes on in the first Load: a Reach-Load event can match the impact of
            # the first touch a taxel sample (9.3 ms) before the taxels show it.
            first_load = s.mode == Mode.LOAD and s.counters.lift_loads == 0
            first_close = closing or first_load
            s, topples = self._pushed_past_tipping(s, shape, closing, opening,
                                                   first_load=first_load)
            located = self._bracket(s, t, contact, opening)
            taxel_fields.update(bracketed_width_m=located[1] if located else 0.0)
            taxel_fields.update(approach_contact_s=t - approach_since if approaching else 0.0,
                                topples_if_released=topples,
                                touched_beyond_pads=self._touched_beyond_pads(s, first_close),
                                first_touch_finger=s.first_touch_finger,
                                caged_behind_pads=self._caged(s, shape, status, opening),
                                opening_m=opening,
                                object_width_m=self._plan.object_width, contact_shape=shape,
                                tilted_s=t - tilted_since if tilted else 0.0,
                                regrasp_pending=s.regrasp_pending)
        observation = Observation(**taxel_fields,
            time_in_mode=time_in_mode, event_matched=bool(self._match.Eval(context)[0] > 0.5),
            motion_done=motion_done,
            time_since_motion_done=t - motion_done_since if motion_done else 0.0,
            closing_s=t - s.closing_since if closing else -1.0, contact=contact,
            one_sided_s=t - one_sided_since if one_sided and closing else 0.0,
            closed_on_nothing=closed_on_nothing,
            grip_reached=bool(min(channels[0], channels[1])
                              >= config.grip_fraction * s.grip_force),
            slip_s=t - slip_since if slipping else 0.0,
            slip_quiet=slip_vibration <= config.slip_vibration_mps2,
            hit=s.mode == Mode.HOLD and is_hit(ra, time_in_mode, config),
            corrective_event_matched=bool(self._memorized_corrective) and bool(
                self._corrective_match.Eval(context)[0] > 0.5),
            gripper_fault=ru.fault_name(fault_code) if fault_code else "",
            device_fault=device_fault)
        sa_before, sa_history = s.sa_before, s.sa_history
        if "hold_avoid" in self._memorized_corrective:
            # The match comes after the hit: the baseline is the SA before it.
            if s.mode == Mode.HOLD and not observation.corrective_event_matched:
                sa_history = hit_baseline_history(s.sa_history, channels,
                                                  config.memorized_hit_baseline_s,
                                                  config.update_period_s)
                sa_before = sa_history[0]
        elif s.mode == Mode.HOLD and not observation.hit:
            # The baseline is the last Hold tick before the hit (not the hit's own tick).
            sa_before = tuple(channels[:2])
        return observation, dataclasses.replace(
            s, one_sided_since=one_sided_since, slip_since=slip_since, tilted_since=tilted_since,
            motion_done_since=motion_done_since, sa_before=sa_before, sa_history=sa_history)

    def _sense_strike(self, s: MachineState, t: float, context, contact: tuple):
        """The finger-strike sense during the approach (taxel_aware): the state with its
        baseline, timer and moment sum updated, and the Observation's strike fields."""
        config = self._config.taxel_aware.finger_strike
        approaching = s.mode == Mode.REACH and s.stage == Stage.MOVING
        if not (config.enabled and approaching and self._grasp_wrench.HasValue(context)):
            return s, {}
        wrench = self._grasp_wrench.Eval(context)
        baseline = s.strike_baseline or tuple(float(x) for x in wrench)
        force = strike_force_n(wrench, baseline)
        striking = force > config.force_n
        since = (s.strike_since if s.strike_since >= 0 else t) if striking else -1.0
        moment_sum = (s.strike_moment_sum + side_moment_nm(wrench, baseline)) if striking \
            else 0.0
        finger = struck_finger(moment_sum, contact, config) or ""
        s = dataclasses.replace(s, strike_baseline=baseline, strike_since=since,
                                strike_moment_sum=moment_sum, strike_finger=finger)
        return s, dict(strike_s=t - since if striking else 0.0, strike_force_n=force,
                       strike_finger=finger)

    def _strike_sustained(self, s: MachineState, t: float) -> bool:
        return (s.strike_since >= 0 and t - s.strike_since
                >= self._config.taxel_aware.finger_strike.sustain_s)

    def _pushed_past_tipping(self, s: MachineState, shape, closing: bool,
                             opening_m: float, *, first_load: bool = False
                             ) -> tuple[MachineState, bool]:
        """taxel_aware, while Reach closes: remember the opening, the contact's offset and
        the pad alone (if one) at the first pad's first touch (any taxel above
        TAXEL_CONTACT_N: a light object slides under a push below contact_force_n) and say
        whether the push since then would topple the object if the gripper let go
        (taxel_corrections.release_topples). In the first Load (first_load), where the
        close goes on after a Reach-Load event that matched the first touch's impact
        before the taxels showed it, a first touch is remembered only on the fingertip
        side (offset >= 0), for touched_beyond_pads: caged_behind_pads reads a palm-side
        first touch, and sees in Load only the Reach's, as before."""
        first, offset, finger = s.first_touch_opening_m, s.first_touch_offset_m, \
            s.first_touch_finger
        recording = closing or (first_load and shape.approach_offset_m >= 0.0)
        if recording and first < 0.0 and (shape.left.touching or shape.right.touching):
            first, offset = opening_m, shape.approach_offset_m
            finger = ("" if shape.left.touching == shape.right.touching
                      else "left" if shape.left.touching else "right")
        p = self._plan
        pushed = pushed_distance_m(first, p.object_width)
        topples = closing and release_topples(pushed, grasp_height_m=p.grasp_height,
                                              object_width_m=p.object_width,
                                              object_height_m=p.object_height)
        return dataclasses.replace(s, first_touch_opening_m=first, first_touch_offset_m=offset,
                                   first_touch_finger=finger), topples

    def _touched_beyond_pads(self, s: MachineState, closing: bool) -> bool:
        """taxel_aware, while the close goes on (Reach closing, the first Load): the first
        touch says the object stands beyond the pads and the close would push it over
        (taxel_corrections.touched_beyond_pads)."""
        p = self._plan
        return closing and touched_beyond_pads(
            first_touch_offset_m=s.first_touch_offset_m, one_pad=bool(s.first_touch_finger),
            pushed_m=pushed_distance_m(s.first_touch_opening_m, p.object_width),
            grasp_height_m=p.grasp_height, object_width_m=p.object_width,
            object_height_m=p.object_height, taxel_config=self._config.taxel_aware)

    def _sa_contact(self, channels) -> tuple[bool, bool]:
        """(left, right): each pad's SA sum (Eq. 1) above contact_force_n."""
        threshold = self._config.contact_force_n
        return bool(channels[0] > threshold), bool(channels[1] > threshold)

    def _one_sided_touch(self, s: MachineState, t: float, contact: tuple,
                         opening_m: float) -> FaceTouch | None:
        """taxel_aware, while Reach closes with one finger alone in contact (SA above
        contact_force_n): the face it presses (taxel_corrections.touched_face), from the
        grasp frame's commanded y (the arm tracks it) and the opening; None otherwise."""
        if not (s.mode == Mode.REACH and s.stage == Stage.CLOSING and contact[0] != contact[1]):
            return None
        return touched_face("left" if contact[0] else "right", s.segment.position(t)[1],
                            opening_m)

    def _bracket(self, s: MachineState, t: float, contact: tuple,
                 opening_m: float) -> tuple[float, float] | None:
        """taxel_aware: (centre [m, world y], extent [m]) of the object between the face a
        finger touching alone presses now and the other finger's remembered face
        (taxel_corrections.bracketed_object); None without such a pair."""
        touch = self._one_sided_touch(s, t, contact, opening_m)
        if touch is None:
            return None
        return bracketed_object(opposite_face(s.touched_faces, touch.finger), touch,
                                self._plan.object_width)

    def _caged(self, s: MachineState, shape, status, opening_m: float) -> bool:
        """taxel_aware, while Reach closes, in Load and while holding: the fingers hold
        the object behind the pads (taxel_corrections.caged_behind_pads)."""
        closed = ((s.mode == Mode.REACH and s.stage == Stage.CLOSING)
                  or s.mode in (Mode.LOAD, *HOLDING_MODES))
        at_request = int(status[ru.STATUS_OBJ]) == ru.ObjectStatus.AT_REQUESTED_POSITION
        return closed and caged_behind_pads(
            first_touch_offset_m=s.first_touch_offset_m, opening_m=opening_m,
            object_width_m=self._plan.object_width,
            pads_touch=shape.left.touching or shape.right.touching, closed_to_request=at_request,
            taxel_config=self._config.taxel_aware)

    def _enter(self, s: MachineState, decision, t: float, context) -> MachineState:
        """Log the transition and start the new mode's motion."""
        p, config = self._plan, self._config
        entry = Transition(t=round(t, 6), from_mode=s.mode, to_mode=decision.mode,
                           trigger=decision.trigger, reason=decision.reason,
                           scores=tuple(round(float(x), 4) for x in self._scores.Eval(context)))
        here = s.segment.position(t)
        hold_here = MotionSegment.hold(t, here)
        common = dict(mode=decision.mode, mode_start=t, segment=hold_here, stage=Stage.NONE,
                      closing_since=-1.0, one_sided_since=-1.0, slip_since=-1.0,
                      motion_done_since=-1.0, tilted_since=-1.0, approach_contact_since=-1.0,
                      first_touch_opening_m=-1.0, first_touch_finger="", sa_history=(),
                      strike_baseline=(),
                      strike_since=-1.0, strike_moment_sum=0.0, strike_finger="")

        def new(logged: Transition = entry, **changes) -> MachineState:
            return dataclasses.replace(s, **{**common, "timeline": s.timeline + (logged,),
                                             **changes})

        counters, mode = s.counters, decision.mode
        if mode == Mode.REACH and s.resume_approach:  # finish the interrupted approach
            target = (p.object_xy[0], here[1], p.grasp_height)
            start_to_grasp = np.linalg.norm(np.subtract((*p.object_xy, p.grasp_height),
                                                        p.start_xyz))
            remaining = np.linalg.norm(np.subtract(target, here))
            duration = max(config.re_reach_move_s, p.reach_s * remaining / start_to_grasp)
            return new(stage=Stage.MOVING, resume_approach=False,
                       segment=MotionSegment(t, duration, tuple(here), target))
        if mode == Mode.REACH:  # back from Re-Reach: close again where we are
            return new(stage=Stage.CLOSING, closing_since=t, gripper_request_time=t,
                       gripper=(0.0, p.close_speed, s.grip_force))
        if mode == Mode.RE_REACH:
            approaching = s.mode == Mode.REACH and s.stage == Stage.MOVING
            first_close = ((s.mode == Mode.REACH and s.stage == Stage.CLOSING)
                           or (s.mode == Mode.LOAD and counters.lift_loads == 0))
            faces = ()
            if s.mode == Mode.PLACE:  # a re-grasp: open where it stands, close again
                shift, re_reaches = Shift(0.0, 0.0), counters.re_reaches
            elif self._taxel_aware:
                channels, opening = self._channels.Eval(context), self._opening(context)
                contact = self._sa_contact(channels)
                shift = taxel_re_reach_shift(grasp_contact(self._taxel_forces.Eval(context)),
                                             channels, opening, p.object_width, config)
                if approaching and self._strike_sustained(s, t):  # a finger struck it
                    shift = Shift(-config.taxel_aware.approach_retreat_m,
                                  strike_shift(s.strike_finger or None, opening,
                                               p.object_width))
                elif approaching:  # back off, shift along the stroke, approach again
                    shift = Shift(-config.taxel_aware.approach_retreat_m, shift.dy_m)
                beyond = not approaching and self._touched_beyond_pads(s, first_close)
                if beyond:  # forward and centre
                    shift = beyond_pads_shift(
                        finger=s.first_touch_finger,
                        first_touch_opening_m=s.first_touch_opening_m,
                        object_width_m=p.object_width, taxel_config=config.taxel_aware)
                located = self._bracket(s, t, contact, opening)
                # Both fingers have touched in turn: go between them; not after a touch
                # beyond the pads, whose shift reads the object (a cylinder: its width at
                # any yaw) from this touch alone, while a face of an earlier close may
                # have been pushed since.
                if located is not None and not beyond:
                    shift = Shift(shift.dx_m, located[0] - here[1])
                if s.mode == Mode.REACH and s.stage == Stage.CLOSING:
                    faces = remembered_faces(s.touched_faces,
                                             touched_faces(contact, here[1], opening))
                re_reaches = counters.re_reaches + 1
            else:
                shift = Shift(0.0, re_reach_shift(self._channels.Eval(context),
                                                  self._opening(context), p.object_width,
                                                  config.contact_force_n))
                re_reaches = counters.re_reaches + 1
            logged = dataclasses.replace(entry, offset_m=round(shift.dy_m, 5))
            if self._taxel_aware:
                logged = dataclasses.replace(logged, approach_offset_m=round(shift.dx_m, 5))
            return new(logged, stage=Stage.OPENING, reentry_offset=shift.dy_m,
                       first_touch_offset_m=0.0,
                       reentry_offset_x=shift.dx_m, gripper_request_time=t,
                       regrasp_pending=False, resume_approach=approaching,
                       touched_faces=faces,
                       counters=dataclasses.replace(counters, re_reaches=re_reaches),
                       gripper=(ru.STROKE_M, OPENING_SPEED_MPS, s.grip_force))
        if mode == Mode.LOAD:
            if s.mode != Mode.LIFT:  # the close goes on: so does its first touch's record
                return new(gripper_request_time=t, gripper=(0.0, p.close_speed, s.grip_force),
                           first_touch_opening_m=s.first_touch_opening_m,
                           first_touch_finger=s.first_touch_finger)
            force = lift_load_grip_force(s.grip_force, config)  # Lift-Load: squeeze harder
            return new(dataclasses.replace(entry, grip_force_n=force),
                       counters=dataclasses.replace(counters, lift_loads=counters.lift_loads + 1),
                       grip_force=force, gripper_request_time=t,
                       gripper=(0.0, p.close_speed, force))
        if mode == Mode.LIFT:
            target = (here[0], here[1], p.grasp_height + p.lift_height)
            remaining = max(target[2] - here[2], 0.0) / p.lift_height
            return new(segment=MotionSegment(t, p.lift_s * max(remaining, 0.2), tuple(here),
                                             target))
        if mode == Mode.AVOID:  # stop, sense the hit's direction, then move (_sense_hit)
            return new(stage=Stage.SENSING, acceleration_sum=(0.0, 0.0, 0.0),
                       sa_gain_sum=(0.0, 0.0))
        if mode == Mode.PLACE:
            target = (here[0], here[1], p.grasp_height - p.place_press)
            regrasp = decision.trigger == Trigger.CORRECTIVE  # put down a tilted object
            return new(segment=MotionSegment(t, p.place_s, tuple(here), target),
                       regrasp_pending=regrasp,
                       counters=dataclasses.replace(
                           counters, regrasps=counters.regrasps + int(regrasp)))
        if mode == Mode.UNLOAD:
            return new(stage=Stage.OPENING, gripper_request_time=t,
                       gripper=(ru.STROKE_M, OPENING_SPEED_MPS, s.grip_force))
        if mode == Mode.FAILED:
            return new(failure=decision.reason)
        return new()  # Hold, Done
