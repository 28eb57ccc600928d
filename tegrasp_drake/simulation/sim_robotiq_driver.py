"""SimRobotiqDriver: the simulated twin of the Robotiq 2F-85's own controller.

Same command bytes (rPR, rSP, rFR) and status bytes as the real gripper (robotiq/units.py).
Half the pad opening q [m] follows a speed- and acceleration-limited reference, planned at
the command rate (SimRobotiqPlanner); the hand (gripper_hands.py) maps it to its actuated
coordinate a, which the plant's implicit PD tracks. On the linkage hand a compiled drive
(robotiq_drive_step.py) adds, once a plant step, the current limit, the self-locking screw
and the stop (docs/model.md, "The drive: rotor, position loop, current limit, screw"); the
prismatic hand keeps a stiff, backdrivable PD whose set-point stays within 2 F / kp.
"""

import dataclasses
import functools
import math

import numpy as np
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from tegrasp_drake.rig import materials
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import bounded, chosen
from tegrasp_drake.robotiq import drive
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.robotiq.hand_models import GRIPPER_MODELS
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.simulation.robotiq_drive_step import (
    DIRECTION, FORCE, GOAL, HALF_SPEED, HELD, MEMORY, MOTOR, MOVING, OBJECT, PLANNER,
    POSITION_BYTE, REF_A, REF_Q, REF_V, RESTARTS, STUCK, TIME, UPDATES, AddDriveStep,
    effective_phase, object_status_now)
from tegrasp_drake.rig.api_boundary import public_dataclass, register_removed_fields

_PLANNER_SIZE = len(PLANNER)


@public_dataclass
@dataclasses.dataclass
class GripperDriverConfig:
    """The simulated 2F-85: its hand and its controller (a force-limited position loop)."""
    # "linkage" (the 2F-85's five-bar fingers) or "prismatic" (gripper_hands.py)
    model: str = chosen("linkage", names=GRIPPER_MODELS,
                        why="the 2F-85's finger linkage, or prismatic fingers")
    # Low end: the position loop follows no command faster than half the update rate, so the
    # slowest loop the model allows (position_loop_hz, 40 Hz) needs updates at twice that.
    update_rate_hz: float = bounded(200.0, low=2 * drive.POSITION_LOOP_HZ_RANGE[0],
                                    high=1000.0, unit="Hz",
                                    why="the 2F-85 takes commands at up to 200 Hz; at least "
                                        "twice the slowest position loop, 40 Hz")
    # The prismatic hand's PD on half the opening a, which moves both fingers (the right one
    # mimics the left): m = 2 x 0.05 kg (modelgen/robotiq_sdf.py FINGER_MASS).
    # kp: w_n = sqrt(kp / m) = 200 rad/s (32 Hz), a 31 ms period that 1 ms plant steps
    # resolve; the lag behind the reference's acceleration, m a / kp = 12.5 um, is far below
    # one position byte (0.19 mm of a). Robotiq publishes no loop gain (the linkage hand's
    # loop, robotiq/drive.py, is 60 Hz on the rotor). Low end: that lag reaches one position
    # byte at about 270 N/m (at the default 0.5 m/s^2); below it the hand would report a
    # position other than the one it was sent to.
    position_gain: float = bounded(4000.0, low=300.0, high=1e6, unit="N/m",
                                   why="the fingers' lag behind the reference stays under one "
                                       "position byte")
    # kd: damping ratio kd / (2 sqrt(kp m)) = 1, critically damped as the 2F-85, which does
    # not overshoot a requested position (robotiq/drive.py POSITION_LOOP_DAMPING_RATIO)
    damping_gain: float = bounded(40.0, low=0.0, high=1e4, unit="N s/m")
    # the linkage hand's drive; sources and ranges in robotiq/drive.py
    position_loop_hz: float = bounded(
        drive.POSITION_LOOP_HZ, low=drive.POSITION_LOOP_HZ_RANGE[0],
        high=drive.POSITION_LOOP_HZ_RANGE[1], unit="Hz",
        why="the 2F-85 firmware's position loop: slower and the locked drive yields, faster "
            "and a 1 ms plant step cannot follow it")
    screw_efficiency: float = bounded(
        drive.SCREW_EFFICIENCY, low=drive.SCREW_EFFICIENCY_RANGE[0],
        high=drive.SCREW_EFFICIENCY_RANGE[1],
        why="a self-locking screw's forward efficiency is below 0.5")
    # The pads' Coulomb coefficient (static = dynamic) as a geometry's, which Drake combines
    # with the other geometry's as 2 mu_pad mu / (mu_pad + mu): the default 4.42 meets the
    # pad-object pairs' handbook values, 0.81 on the box, 0.69 on the cylinders
    # (rig/materials.py; docs/model.md, "Friction by material pair").
    pad_friction: float = bounded(
        materials.PAD_COVER, low=0.1, high=100.0,
        why="a geometry's coefficient; below 0.1 every pad pair is under 0.2, no gripper pad; "
            "above about 100 the pairs are twice the other geometry's and no longer change")
    # The reference's ramp on half the opening, both hands. Robotiq publishes only the speed
    # (20-150 mm/s pad to pad, 10-75 mm/s a finger): at 0.5 m/s^2 a finger reaches 75 mm/s in
    # 0.15 s over 5.6 mm of its 42.5 mm travel (a full stroke 0.72 s, 0.57 s with no ramp),
    # 10 mm/s in 20 ms. A profile, not a motor limit: at the lowest force cap (20 N) the
    # linkage hand's drive (robotiq/drive.py) gives 2 F (dq/da)^2 / J = 13-22 m/s^2. Below one
    # film converter code (1.23 m/s^2): the fingers' start and stop stay in the RA noise.
    acceleration: float = bounded(0.5, low=0.0, low_open=True, high=10.0, unit="m/s^2")
    # m/s; slower than this before the goal = object detected
    stall_speed: float = bounded(0.002, low=0.0, low_open=True, high=0.15, unit="m/s",
                                 why="below the 2F-85's 150 mm/s top speed, Robotiq 2F-85 manual")


# Fields a version removed, each with what took its place. The linkage hand's PD on the
# driver angle (driver_position_gain 1000 N m/rad, driver_damping_gain 1 N m s/rad) became
# the 2F-85 drive's model (robotiq/drive.py): its gains follow from the firmware's position
# loop (position_loop_hz) on the drive's inertia (screw_efficiency), so no value carries
# over. scenario/moved_keys.py refuses them in a scenario given and reads a stored scenario
# that holds them (written before the drive's model) without them; GripperDriverConfig(...)
# and an assignment refuse them with the same words.
REMOVED_FIELDS = {
    name: "the linkage hand's PD gains now follow from gripper.position_loop_hz (the 2F-85 "
          "firmware's position loop on the drive's inertia, robotiq/drive.py)"
    for name in ("driver_position_gain", "driver_damping_gain")}
register_removed_fields(GripperDriverConfig, REMOVED_FIELDS)


def reference_step(q: float, v: float, goal: float, max_speed: float, acceleration: float,
                   dt: float) -> float:
    """The constant acceleration [m/s^2] over the next dt that moves (q, v) toward goal
    within max_speed, still able to stop there (Python floats: called every update)."""
    distance = goal - q
    if abs(distance) < 1e-6:
        target_v = 0.0
    else:
        speed = min(max_speed, math.sqrt(2.0 * acceleration * abs(distance)))
        target_v = speed if distance > 0.0 else -speed
    return float(min(max((target_v - v) / dt, -acceleration), acceleration))


@functools.lru_cache(maxsize=256)
def command_targets(position: float, speed: float, force: float) -> tuple[float, ...]:
    """(position byte, goal finger coordinate q [m], half the closing speed [m/s], force
    limit [N]) of a command's (rPR, rSP, rFR) bytes; cached (read every update)."""
    position_byte = float(np.clip(np.round(position), 0, 255))
    return (position_byte, float(ru.opening_from_position_byte(position_byte) / 2),
            float(ru.speed_from_byte(speed) / 2), float(ru.force_from_byte(force)))


def status_position_byte(q: float) -> float:
    """gPO of the finger coordinate q [m]: ru.position_byte_from_opening(2 q) on floats."""
    fraction = min(max(2.0 * q / ru.STROKE_M, 0.0), 1.0)
    return float(round(ru.POSITION_CLOSED_BYTE - fraction * ru.POSITION_SPAN_BYTES))


def has_arrived(q: float, v: float, goal: float, acceleration: float, dt: float) -> bool:
    """True when the reference (q, v) is a step from goal at rest: it is then put on the goal
    (docs/model.md, "The driver's reference")."""
    return abs(goal - q) <= acceleration * dt * dt and abs(v) <= acceleration * dt


def force_limited_set_point(q: float, q_ref: float, force: float, position_gain: float,
                            lever: float = 1.0) -> float:
    """The PD set-point: the reference within 2 force lever / position_gain of q, so that a
    blocked finger pushes each pad with at most force [N]; lever = |d(half opening)/dq|."""
    band = 2.0 * force * lever / position_gain
    return q + min(max(q_ref - q, -band), band)


def drive_set_point(*, a: float, v: float, v_prev: float, set_point: tuple[float, float],
                    phase: float, anchor: float, reference: tuple[float, float], limit: float,
                    direction: float, gain: float, damping: float, inertia: float,
                    time_step: float) -> tuple[float, float, float, float, float]:
    """One plant step of the linkage hand's drive: (a_d [rad], v_d [rad/s], phase, motor
    torque [N m], anchor [rad] where the screw stopped the rotor) from the driver's a, v
    (v_prev a step before), the last set-point and phase, the reference, the torque cap
    `limit` [N m], the nut's direction (+1/-1), the inertia [kg m^2] and the step [s]."""
    set_a, set_v = set_point
    # the load: the PD's torque at the step's end (SAP's) less what accelerated the inertia
    load = gain * (set_a - a) + damping * (set_v - v) - inertia * (v - v_prev) / time_step
    demand = gain * (reference[0] - a) + damping * (reference[1] - v)
    motor = min(max(demand, -limit), limit)
    if phase == HELD:
        # a finger closing on by half the held squeeze has lost its object: drive on
        if direction * (a - anchor) <= 0.5 * direction * (set_a - anchor):
            return set_a, 0.0, HELD, 0.0, anchor
        phase = MOVING
    elif phase == STUCK:
        if direction * motor <= direction * load:  # the screw still carries the load
            return set_a, 0.0, HELD if direction * motor >= limit else STUCK, motor, anchor
        phase = MOVING
    elif direction * v <= 0.0 and direction * load > max(direction * motor, 0.0):
        # the load would drive the rotor back: the screw stops it
        set_a = a + load / gain
        return set_a, 0.0, HELD if direction * motor >= limit else STUCK, motor, a
    if abs(demand) <= limit:
        return reference[0], reference[1], phase, motor, anchor
    # at the limit: the PD's torque is the cap, at the velocity the last acceleration gives
    v_next = 2.0 * v - v_prev
    return a + time_step * v_next + motor / gain, v_next, phase, motor, anchor


def held_object_status(q: float, goal: float) -> int:
    """gOBJ of fingers the screw holds on an object at q [m] short of goal [m]."""
    return int(ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING if goal < q
               else ru.ObjectStatus.STOPPED_ON_CONTACT_OPENING)


def object_status(q: float, v: float, q_ref: float, goal: float, stall_speed: float) -> int:
    """gOBJ from the finger's measured motion (see ObjectStatus)."""
    if abs(q - goal) < 5e-4:
        return int(ru.ObjectStatus.AT_REQUESTED_POSITION)
    if abs(v) < stall_speed and abs(q_ref - q) > 1e-3:
        closing = goal < q
        return int(ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING if closing
                   else ru.ObjectStatus.STOPPED_ON_CONTACT_OPENING)
    return int(ru.ObjectStatus.MOVING)


class SimRobotiqPlanner(LeafSystem):
    """The simulated 2F-85's command intake, reference and status bytes at the command
    rate; the drive (robotiq_drive_step.py) reads its state every plant step.

    .. pydrake_system::

        name: SimRobotiqPlanner
        input_ports:
        - command
        - finger_state
        - drive_memory
        output_ports:
        - planner_state
        - status

    Ports:
        command: (3) rPR, rSP, rFR bytes.
        finger_state: (2) a and its rate, as MakeSimRobotiqDriver's.
        drive_memory, planner_state: robotiq_drive_step's MEMORY and PLANNER vectors.
        status: (8) status bytes, robotiq.units order.
    """

    def __init__(self, *, config: GripperDriverConfig, initial_opening: float = ru.STROKE_M):
        super().__init__()
        if config.model not in GRIPPER_MODELS:
            raise ValueError(f"gripper.model '{config.model}' is not one of "
                             f"{', '.join(GRIPPER_MODELS)}")
        self._config = config
        self._hand = gripper_hand(config.model)
        self._dt = 1.0 / config.update_rate_hz
        self._command = self.DeclareVectorInputPort("command", ru.COMMAND_SIZE)
        self._finger_state = self.DeclareVectorInputPort("finger_state", 2)
        self._memory = self.DeclareVectorInputPort("drive_memory", len(MEMORY))
        q0 = initial_opening / 2
        initial = np.zeros(_PLANNER_SIZE)
        initial[[REF_Q, GOAL]] = q0
        initial[HALF_SPEED] = ru.SPEED_MIN_MPS / 2
        initial[FORCE] = ru.FORCE_MIN_N
        initial[POSITION_BYTE] = ru.position_byte_from_opening(initial_opening)
        initial[OBJECT] = int(ru.ObjectStatus.AT_REQUESTED_POSITION)
        self._state = self.DeclareDiscreteState(initial)
        self.DeclarePeriodicDiscreteUpdateEvent(self._dt, 0.0, self._update)
        self.DeclareStateOutputPort("planner_state", self._state)
        self.DeclareVectorOutputPort(
            "status", ru.STATUS_SIZE, self._calc_status,
            prerequisites_of_calc={self.discrete_state_ticket(self._state),
                                   self._finger_state.ticket(), self._memory.ticket()})

    def _update(self, context, discrete_state):
        """The command intake and the reference, at the 2F-85's command rate."""
        s = context.get_discrete_state(self._state).value().copy()
        t = context.get_time()
        hand = self._hand
        a, v = self._finger_state.Eval(context).tolist()
        phase = effective_phase(s, self._memory.Eval(context))
        q = hand.half_opening(a)
        h = t - s[TIME]
        s[REF_Q] += s[REF_V] * h + 0.5 * s[REF_A] * h * h
        s[REF_V] += s[REF_A] * h
        s[TIME] = t
        goal, force = s[GOAL], s[FORCE]
        s[POSITION_BYTE], s[GOAL], s[HALF_SPEED], s[FORCE] = command_targets(
            *self._command.Eval(context).tolist())
        if (s[GOAL], s[FORCE]) != (goal, force):
            if phase != MOVING:
                # held fingers: the new motion starts where they stand
                s[REF_Q], s[REF_V], phase = q, 0.0, MOVING
                s[RESTARTS] += 1.0
            if s[GOAL] != s[REF_Q]:
                # the nut's direction, kept to the next command
                rate = hand.half_opening_rate(hand.actuated(s[REF_Q]))
                s[DIRECTION] = 1.0 if (s[GOAL] - s[REF_Q]) * rate > 0.0 else -1.0
        if has_arrived(s[REF_Q], s[REF_V], s[GOAL], self._config.acceleration, self._dt):
            s[REF_Q], s[REF_V] = s[GOAL], 0.0
        s[REF_A] = reference_step(s[REF_Q], s[REF_V], s[GOAL], s[HALF_SPEED],
                                  self._config.acceleration, self._dt)
        if phase == HELD:
            s[OBJECT] = held_object_status(q, s[GOAL])
        else:
            s[OBJECT] = object_status(q, v * hand.half_opening_rate(a), s[REF_Q], s[GOAL],
                                      self._config.stall_speed)
        s[UPDATES] += 1.0
        discrete_state.set_value(self._state, s)

    def _calc_status(self, context, output):
        s = context.get_discrete_state(self._state).get_value().tolist()
        memory = self._memory.Eval(context).tolist()
        a = self._finger_state.Eval(context).item(0)
        hand = self._hand
        # current only while the fingers move (none held or at the request)
        gripper_object = object_status_now(s, memory)
        moving = (gripper_object == int(ru.ObjectStatus.MOVING)
                  and effective_phase(s, memory) != HELD)
        force = abs(memory[MOTOR]) / (2.0 * abs(hand.half_opening_rate(a)))
        status = [0.0] * ru.STATUS_SIZE
        status[ru.STATUS_ACT] = 1.0
        status[ru.STATUS_GTO] = 1.0
        status[ru.STATUS_STA] = float(ru.ActivationStatus.ACTIVE)
        status[ru.STATUS_OBJ] = gripper_object
        status[ru.STATUS_PR] = s[POSITION_BYTE]
        status[ru.STATUS_PO] = status_position_byte(hand.half_opening(a))
        status[ru.STATUS_CU] = ru.current_byte(force, moving=moving)
        output.SetFromVector(status)


def MakeSimRobotiqDriver(*, config: GripperDriverConfig, time_step: float,
                         initial_opening: float = ru.STROKE_M):
    """The simulated 2F-85 controller (module docstring): SimRobotiqPlanner at the command
    rate and the compiled drive (robotiq_drive_step.py) once a plant step.

    .. pydrake_system::

        name: SimRobotiqDriver
        input_ports:
        - command
        - finger_state
        output_ports:
        - desired_state
        - status

    Ports:
        command: (3) rPR, rSP, rFR bytes.
        finger_state: (2) a and its rate ([rad], [rad/s] linkage; [m], [m/s] prismatic).
        desired_state: (2) a and da/dt set-points of the plant's PD for the next step.
        status: (8) status bytes, robotiq.units order.
    time_step: the plant's [s].
    """
    if not time_step > 0.0:
        raise ValueError(f"time_step {number_text(time_step)} must be the plant's positive "
                         "step [s]")
    builder = DiagramBuilder()
    planner = builder.AddNamedSystem("planner", SimRobotiqPlanner(
        config=config, initial_opening=initial_opening))
    hand = gripper_hand(config.model)
    gain, damping = hand.pd_gains(config)
    builder.ExportInput(planner.GetInputPort("command"), "command")
    finger_state = builder.ExportInput(planner.GetInputPort("finger_state"), "finger_state")
    drive_finger_state, memory, set_point = AddDriveStep(
        builder, hand=hand, gain=gain, damping=damping, inertia=hand.drive_inertia(config),
        time_step=time_step, initial_actuated=hand.actuated(initial_opening / 2),
        planner_state=planner.GetOutputPort("planner_state"))
    builder.ConnectInput(finger_state, drive_finger_state)
    builder.Connect(memory, planner.GetInputPort("drive_memory"))
    builder.ExportOutput(set_point, "desired_state")
    builder.ExportOutput(planner.GetOutputPort("status"), "status")
    diagram = builder.Build()
    diagram.set_name("sim_robotiq_driver")
    return diagram
