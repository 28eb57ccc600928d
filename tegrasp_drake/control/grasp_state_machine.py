"""GraspStateMachine: the tactile-event grasping algorithm (Sec. II-B, III-C, Fig. 6b) as a
Drake LeafSystem. Each tick it summarises its inputs into an Observation, asks its rule table
(rule_engine.py) for the next mode, and carries out the mode's motion: minimum-jerk moves of
the grasp frame G (world frame, stroke along y) and 2F-85 requests. All memory is one
abstract state (MachineState)."""

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.control import taxel_aware, transition_logic
from tegrasp_drake.control.cartesian_arm_controller import followable_move_s
from tegrasp_drake.control.corrective_actions import (
    approach_retreat_target, avoid_move, hit_baseline_history, is_hit, lift_load_grip_force,
    pad_accelerations_in_world, ra_history, ra_level, re_reach_shift, re_reach_target)
from tegrasp_drake.control.grasp_modes import Mode, Stage, Transition, Trigger
from tegrasp_drake.control.machine_state import GraspPlan, MachineState, ModeTimers
from tegrasp_drake.control.motion_profiles import MotionSegment
from tegrasp_drake.control.rule_actions import Regrasp, ReReach
from tegrasp_drake.control.scripted_grasp import gripper_command
from tegrasp_drake.control.transition_logic import Observation, memorized_corrective_trigger
from tegrasp_drake.events.transitions import (CORRECTIVE_TRANSITIONS, NO_EVENT,
                                              REQUIRED_TRANSITIONS, transition_states)
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.rig.arm_kinematics import R_WG_SIDE_GRASP
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.channels import CHANNEL_NAMES, TAXELS_PER_PAD

__all__ = ["GraspPlan", "GraspStateMachine", "MachineState"]

OPENING_SPEED_MPS = 0.1  # when opening to re-reach or unload
GRIPPER_STATUS_LAG_S = 0.1  # gOBJ is trusted this long after a new request
# The event each mode expects: the event-triggered transition that leaves it.
EXPECTED_TRANSITION = {Mode.from_label(transition_states(name)[0]): name
                       for name in REQUIRED_TRANSITIONS}
# The memorized corrective event each mode expects (if memorized_corrective.events names it).
EXPECTED_CORRECTIVE_TRANSITION = {Mode.from_label(transition_states(name)[0]): name
                                  for name in CORRECTIVE_TRANSITIONS}


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
        - ra_peak (optional)
        output_ports:
        - X_WG_desired
        - gripper_command
        - expected_event
        - mode
        - corrective_expected_event

    match, corrective_match: [1] when the (corrective) matcher matches; scores: its four
    Eq. 3 scores; channels: [sa_l, sa_r, ra_l, ra_r] [N, N, m/s^2, m/s^2]; gripper.status:
    2F-85 bytes; pad_acceleration: [left xyz, right xyz] [m/s^2, pad frames] (unconnected:
    Avoid moves up); slip_vibration: [left, right] slip band [m/s^2]; device_fault: "" or
    the watchdog's message; taxel_forces: [left 12, right 12] [N] (taxel_aware);
    grasp_wrench: [M, F] at G [N m, N, world] (finger strike); ra_peak: each film's peak |RA|
    over the tick [m/s^2] (tactile/ra_tick_peak.py; unconnected: the tick's RA). Outputs:
    X_WG_desired; gripper_command [rPR, rSP, rFR]; expected_event and
    corrective_expected_event (index, -1 none; state only, since the matchers feed back);
    mode. rules: the RuleTable, run as kept to the plan's hand
    (RuleTable.for_hand(plan.gripper_model), rule_table());
    estimator: a taxel_aware ContactEstimator or None (both from the registry entry).
    """

    def __init__(self, *, plan: GraspPlan, config, event_indices: dict,
                 event_trigger: Trigger, corrective_event_indices: dict | None = None,
                 rules=transition_logic.PAPER_TABLE, estimator=None):
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
        self._status = self.DeclareVectorInputPort(ports.GRIPPER_STATUS, ru.STATUS_SIZE)
        self._pad_acceleration = self.DeclareVectorInputPort("pad_acceleration", 6)
        self._slip_vibration = self.DeclareVectorInputPort("slip_vibration", 2)
        self._device_fault = self.DeclareAbstractInputPort(ports.DEVICE_FAULT,
                                                             AbstractValue.Make(""))
        self._taxel_forces = self.DeclareVectorInputPort("taxel_forces", 2 * TAXELS_PER_PAD)
        self._corrective_match = self.DeclareVectorInputPort("corrective_match", 1)
        self._grasp_wrench = self.DeclareVectorInputPort("grasp_wrench", 6)
        self._ra_peak = self.DeclareVectorInputPort("ra_peak", 2)
        self._estimator = estimator
        self._rules = rules.for_hand(plan.gripper_model)
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

    def initial_state(self) -> MachineState:
        p = self._plan
        grasp = (*p.object_xy, p.grasp_height)
        return MachineState(
            mode=Mode.REACH, mode_start=0.0,
            segment=MotionSegment(p.settle_s, p.reach_s, p.start_xyz, grasp),
            gripper=(ru.STROKE_M, p.close_speed, p.grip_force), gripper_request_time=0.0,
            grip_force=p.grip_force, stage=Stage.MOVING)

    def rule_table(self):
        """The RuleTable it runs: its rules kept to the plan's hand."""
        return self._rules

    def state(self, context) -> MachineState:
        return context.get_abstract_state(self._state).get_value()

    def transitions(self, context) -> tuple[Transition, ...]:
        """The transitions so far, in order."""
        return self.state(context).timeline

    def timeline(self, context) -> list[dict]:
        """The transitions so far in their JSON form (Transition.as_dict)."""
        return [transition.as_dict() for transition in self.transitions(context)]

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

    def _update(self, context, state):
        t = context.get_time()
        s = self._advance_stage(self.state(context), t, context)
        observation, s = self._observe(s, t, context)
        decision = self._rules.next_mode(s.mode, observation, s.counters, self._config,
                                         event_trigger=self._event_trigger,
                                         hold_s=self._plan.hold_s)
        if decision is not None:
            s = self._enter(s, decision, observation, t, context)
        state.get_mutable_abstract_state(self._state).set_value(s)

    def _opening(self, context) -> float:
        return float(ru.opening_from_position_byte(self._status.Eval(context)[ru.STATUS_PO]))

    def _gripper_settled(self, s: MachineState, t: float) -> bool:
        return t - s.gripper_request_time >= GRIPPER_STATUS_LAG_S

    def _advance_stage(self, s: MachineState, t: float, context) -> MachineState:
        """Steps within a mode: close after reaching, shift after opening, retract after release."""
        p = self._plan
        if s.mode == Mode.REACH and s.stage == Stage.MOVING and s.segment.done(t):
            return dataclasses.replace(
                s, stage=Stage.CLOSING, timers=dataclasses.replace(s.timers, closing_since=t),
                gripper_request_time=t, gripper=(0.0, p.close_speed, s.grip_force))
        if s.mode == Mode.AVOID and s.stage == Stage.SENSING:
            return self._sense_hit(s, t, context)
        if s.mode in (Mode.RE_REACH, Mode.UNLOAD) and s.stage == Stage.OPENING:
            opened = self._opening(context) >= self._config.re_reach.opened_m
            if opened and self._gripper_settled(s, t):
                here = s.segment.position(t)
                if s.mode == Mode.RE_REACH:
                    dx, dy = s.reentry_shift
                    target = re_reach_target(here, dy)
                    if s.resume_approach and dx < 0.0:  # a back-off in the approach
                        target = approach_retreat_target(
                            target, -dx, start_xyz=p.start_xyz,
                            grasp_xyz=(p.object_xy[0], p.object_xy[1], p.grasp_height))
                    else:
                        target = target + np.array([dx, 0.0, 0.0])
                    # the shift is known only now: as long as the arm needs along it
                    return self._start_corrective_move(s, t, here, target,
                                                       self._config.re_reach.move_s)
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
        config, timers = self._config, s.timers
        total = np.asarray(timers.acceleration_sum)
        if self._pad_acceleration.HasValue(context):
            total = total + pad_accelerations_in_world(
                self._pad_acceleration.Eval(context)).sum(axis=0)
        # The push shows in SA for a few samples and then rings: sum it over the sensing.
        gain = np.asarray(timers.sa_gain_sum) + (self._channels.Eval(context)[:2]
                                                 - np.asarray(s.sa_before))
        if t - s.mode_start < config.avoid.sense_s:
            return dataclasses.replace(s, timers=dataclasses.replace(
                timers, acceleration_sum=tuple(total), sa_gain_sum=tuple(gain)))
        here = s.segment.position(t)
        move = avoid_move(here, gain, total, config)
        entry = dataclasses.replace(
            s.timeline[-1], direction=tuple(round(float(x), 3) for x in move.direction_W),
            delta_sa_n=tuple(round(float(x), 3) for x in move.delta_sa_n))
        return self._start_corrective_move(
            dataclasses.replace(s, timeline=s.timeline[:-1] + (entry,)), t, here,
            move.p_end_W, config.avoid.move_s)

    @staticmethod
    def _start_corrective_move(s: MachineState, t: float, here, target,
                               move_s: float) -> MachineState:
        """Start the move from here to target [m, world] a corrective action decided at run
        time (Avoid's away from a hit, a Re-Reach's shift), in move_s [s] or as long as the
        arm needs along it (followable_move_s); its duration, and why when stretched, on the
        action's transition (the timeline's last)."""
        duration, note = followable_move_s(here, target, move_s)
        entry = s.timeline[-1]
        entry = dataclasses.replace(entry, move_s=round(duration, 6),
                                    reason=f"{entry.reason}; {note}" if note else entry.reason)
        return dataclasses.replace(s, stage=Stage.MOVING, timeline=s.timeline[:-1] + (entry,),
                                   segment=MotionSegment(t, duration, tuple(here),
                                                         tuple(target)))

    def _observe(self, s: MachineState, t: float, context):
        """The tick's Observation, and the state with its running timers updated."""
        config, timers = self._config, s.timers
        channels = self._channels.Eval(context)
        contact = self._sa_contact(channels)
        one_sided = contact[0] != contact[1]
        one_sided_since = _since(timers.one_sided_since, t, one_sided)
        films_ra = (float(channels[2]), float(channels[3]))
        in_hold = s.mode == Mode.HOLD
        # Hold's RA ticks before this one (the hit's level), then this one
        held_ra = (ra_history(timers.ra_history, films_ra, config.avoid.hit_level_s,
                              config.update_period_s) if in_hold else timers.ra_history)
        slip_vibration = float(max(self._slip_vibration.Eval(context)))
        slipping = s.mode == Mode.LIFT and slip_vibration > config.lift_load.slip_vibration_mps2
        slip_since = _since(timers.slip_since, t, slipping)
        moving_stage = s.stage in (Stage.MOVING, Stage.NONE)
        motion_done = moving_stage and s.segment.done(t)
        motion_done_since = _since(timers.motion_done_since, t, motion_done)
        status = self._status.Eval(context)
        closing = s.mode == Mode.REACH and s.stage == Stage.CLOSING
        # only a status echoing the close request (gPR = rPR): a late one of the open reads
        # "at requested position" too
        at_request = int(status[ru.STATUS_OBJ]) == ru.ObjectStatus.AT_REQUESTED_POSITION
        echoes_request = (status[ru.STATUS_PR]
                          == gripper_command(*s.gripper)[ru.COMMAND_POSITION])
        closed_on_nothing = (
            closing and self._gripper_settled(s, t) and not any(contact) and echoes_request
            and at_request)
        fault_code = int(status[ru.STATUS_FLT])
        device_fault = self._device_fault.Eval(context) if self._device_fault.HasValue(
            context) else ""
        time_in_mode = t - s.mode_start
        event_matched = bool(self._match.Eval(context)[0] > 0.5)
        estimate = None
        if self._estimator is not None:
            memory, estimate = self._estimator.update(s.contact, taxel_aware.ContactReading(
                t=t, mode=s.mode, stage=s.stage, lift_loads=s.counters.lift_loads,
                taxel_forces=self._taxel_forces.Eval(context), sa_n=tuple(channels[:2]),
                contact=contact, opening_m=self._opening(context),
                at_requested_position=at_request,
                stopped_on_object=echoes_request and int(status[ru.STATUS_OBJ])
                == ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING,
                wrench=self._approach_wrench(s, context),
                gripper_y_m=s.segment.position(t)[1], event_matched=event_matched,
                ra_mps2=tuple(channels[2:4]),
                ra_peak_mps2=(tuple(self._ra_peak.Eval(context))
                              if self._ra_peak.HasValue(context) else None)))
            s = dataclasses.replace(s, contact=memory)
        observation = Observation(
            time_in_mode=time_in_mode, event_matched=event_matched,
            motion_done=motion_done,
            time_since_motion_done=t - motion_done_since if motion_done else 0.0,
            closing_s=t - timers.closing_since if closing else -1.0, contact=contact,
            one_sided_s=t - one_sided_since if one_sided and closing else 0.0,
            closed_on_nothing=closed_on_nothing,
            grip_reached=bool(min(channels[0], channels[1])
                              >= config.lift_load.grip_fraction * s.grip_force),
            slip_s=t - slip_since if slipping else 0.0,
            slip_quiet=slip_vibration <= config.lift_load.slip_vibration_mps2,
            hit=in_hold and is_hit(films_ra, time_in_mode, config,
                                   ra_level(timers.ra_history)),
            corrective_event_matched=bool(self._memorized_corrective) and bool(
                self._corrective_match.Eval(context)[0] > 0.5),
            gripper_fault=ru.fault_name(fault_code) if fault_code else "",
            device_fault=device_fault, regrasp_pending=s.regrasp_pending, estimate=estimate)
        sa_before, sa_history = s.sa_before, timers.sa_history
        if "hold_avoid" in self._memorized_corrective:
            # The match comes after the hit: the baseline is the SA before it.
            if s.mode == Mode.HOLD and not observation.corrective_event_matched:
                sa_history = hit_baseline_history(timers.sa_history, channels,
                                                  config.memorized_corrective.hit_baseline_s,
                                                  config.update_period_s)
                sa_before = sa_history[0]
        elif s.mode == Mode.HOLD and not observation.hit:
            # The baseline is the last Hold tick before the hit (not the hit's own tick).
            sa_before = tuple(channels[:2])
        if not (one_sided_since == timers.one_sided_since and slip_since == timers.slip_since
                and motion_done_since == timers.motion_done_since
                and sa_history is timers.sa_history and held_ra is timers.ra_history):
            timers = dataclasses.replace(
                timers, one_sided_since=one_sided_since, slip_since=slip_since,
                motion_done_since=motion_done_since, sa_history=sa_history,
                ra_history=held_ra)
        return observation, (s if timers is s.timers and sa_before is s.sa_before else
                             dataclasses.replace(s, sa_before=sa_before, timers=timers))

    def _approach_wrench(self, s: MachineState, context):
        """The wrench on G [N m, N] during the approach's move (finger strike), else None."""
        approaching = s.mode == Mode.REACH and s.stage == Stage.MOVING
        return (self._grasp_wrench.Eval(context)
                if approaching and self._grasp_wrench.HasValue(context) else None)

    def _sa_contact(self, channels) -> tuple[bool, bool]:
        """(left, right): each pad's SA sum (Eq. 1) above contact_force_n."""
        threshold = self._config.contact_force_n
        return bool(channels[0] > threshold), bool(channels[1] > threshold)

    def _enter(self, s: MachineState, decision, observation: Observation, t: float,
               context) -> MachineState:
        """Log the transition and carry out the decision: start the new mode's motion."""
        p = self._plan
        entry = Transition(t=round(t, 6), from_mode=s.mode, to_mode=decision.mode,
                           trigger=decision.trigger, reason=decision.reason,
                           scores=tuple(round(float(x), 4) for x in self._scores.Eval(context)),
                           code=decision.code)
        here = s.segment.position(t)
        estimate = observation.estimate
        entered = dataclasses.replace(
            s, mode=decision.mode, mode_start=t, segment=MotionSegment.hold(t, here),
            stage=Stage.NONE, timers=ModeTimers(), timeline=s.timeline + (entry,),
            contact=s.contact.after_transition(s.mode, decision.mode,
                                               estimate.touched_now if estimate else ()))

        def new(logged: Transition = entry, **changes) -> MachineState:
            return dataclasses.replace(entered, timeline=s.timeline + (logged,), **changes)

        counters, mode = s.counters, decision.mode
        if mode == Mode.REACH and s.resume_approach:  # finish the interrupted approach
            target = (p.object_xy[0], here[1], p.grasp_height)
            start_to_grasp = np.linalg.norm(np.subtract((*p.object_xy, p.grasp_height),
                                                        p.start_xyz))
            remaining = np.linalg.norm(np.subtract(target, here))
            duration = max(self._config.re_reach.move_s,
                           p.reach_s * remaining / start_to_grasp)
            return new(stage=Stage.MOVING, resume_approach=False,
                       segment=MotionSegment(t, duration, tuple(here), target))
        if mode == Mode.REACH:  # back from Re-Reach: close again where we are
            return new(stage=Stage.CLOSING, timers=ModeTimers(closing_since=t),
                       gripper_request_time=t, gripper=(0.0, p.close_speed, s.grip_force))
        if mode == Mode.RE_REACH:
            action = decision.action if isinstance(decision.action, ReReach) else ReReach()
            counted = action.counted
            if action.shift is not None:  # the rule's own move
                dx, dy = action.shift.dx_m, action.shift.dy_m
                logged = dataclasses.replace(entry, offset_m=round(dy, 5),
                                             approach_offset_m=round(dx, 5))
            else:  # the paper's shift along the stroke
                dx = 0.0
                dy = re_reach_shift(self._channels.Eval(context), self._opening(context),
                                    p.object_width, self._config.contact_force_n)
                logged = dataclasses.replace(entry, offset_m=round(dy, 5))
            return new(logged, stage=Stage.OPENING, reentry_shift=(dx, dy),
                       gripper_request_time=t, regrasp_pending=False,
                       resume_approach=s.mode == Mode.REACH and s.stage == Stage.MOVING,
                       counters=dataclasses.replace(
                           counters, re_reaches=counters.re_reaches + int(counted)),
                       gripper=(ru.STROKE_M, OPENING_SPEED_MPS, s.grip_force))
        if mode == Mode.LOAD:
            if s.mode != Mode.LIFT:  # the close goes on
                return new(gripper_request_time=t, gripper=(0.0, p.close_speed, s.grip_force))
            force = lift_load_grip_force(s.grip_force, self._config)  # Lift-Load: squeeze harder
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
            return new(stage=Stage.SENSING,
                       counters=dataclasses.replace(counters, avoids=counters.avoids + 1))
        if mode == Mode.PLACE:
            target = (here[0], here[1], p.grasp_height - p.place_press)
            regrasp = isinstance(decision.action, Regrasp)  # a tilted object
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


def _since(since: float, t: float, on: bool) -> float:
    """A timer's start: kept while `on` (started now if it was not running), else -1."""
    return (since if since >= 0 else t) if on else -1.0
