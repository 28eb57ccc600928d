"""SimRobotiqDriver: the simulated twin of the Robotiq 2F-85's own controller.

It takes the same command bytes as the real gripper (rPR, rSP, rFR) and reports the same
status bytes (robotiq/units.py). Inside, half the pad opening q [m] follows a speed- and
acceleration-limited reference toward the requested position (the 2F-85's speed setting is a
finger speed), planned at the 2F-85's command rate; the hand (gripper_hands.py) maps it to
its actuated coordinate a (the left driver's angle on the linkage hand, q itself on the
prismatic one), which the plant's implicit PD (SAP) tracks.

On the linkage hand the plant's PD is the 2F-85 firmware's position loop on the drive's
inertia (the rotor is the actuator's reflected inertia; robotiq/drive.py), and the driver
adds what a PD cannot do, once a plant step (half a step after the plant's, so that it sees
the state the plant steps from): the current limit while the fingers move (the loop's torque
capped at 2 F |dq/da|, both pads on the one motor: the set-point is moved so that the PD's
torque is the cap), the self-locking screw (a load that would drive the rotor back stops it
where it stands: the set-point then holds the rotor under the load it carries), and the stop
(standing at the current limit, the firmware reports an object, gOBJ, and cuts the current,
gCU = 0; the screw holds the force of that instant). A new command restarts the reference
from where the fingers stand. The prismatic hand keeps the idealised drive: no rotor, a
stiff PD whose set-point stays within 2 F / kp of the finger, backdrivable. The position byte
gPO is computed from the measured a through the hand's linkage.

MakeSimRobotiqDriver: SimRobotiqPlanner (Python, command rate) and the per-plant-step drive
compiled from this module's set-point functions (robotiq_drive_step.py).
"""

import dataclasses
import functools
import math

import numpy as np
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.robotiq import drive
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.simulation.gripper_hands import GRIPPER_MODELS, gripper_hand
from tegrasp_drake.simulation.robotiq_drive_step import (
    DIRECTION, FORCE, GOAL, HALF_SPEED, HELD, MEMORY, MOTOR, MOVING, OBJECT, PLANNER,
    POSITION_BYTE, REF_A, REF_Q, REF_V, RESTARTS, STUCK, TIME, UPDATES, AddDriveStep,
    effective_phase, object_status_now)
from tegrasp_drake.rig.api_boundary import public_dataclass

_PLANNER_SIZE = len(PLANNER)  # the planner's state (robotiq_drive_step.PLANNER)


@public_dataclass
@dataclasses.dataclass
class GripperDriverConfig:
    """The simulated 2F-85: which hand, and its controller (a position loop with a force
    limit)."""
    # The hand (gripper_hands.py): "linkage", the 2F-85's five-bar fingers, or "prismatic".
    model: str = "linkage"
    # the 2F-85 accepts commands at up to 200 Hz
    update_rate_hz: float = bounded(200.0, low=0.0, low_open=True, high=1000.0, unit="Hz",
                                    why="the 2F-85 takes commands at up to 200 Hz")
    # The prismatic hand's PD on half the opening.
    position_gain: float = bounded(4000.0, low=0.0, low_open=True, high=1e6, unit="N/m")  # N/m
    damping_gain: float = bounded(40.0, low=0.0, high=1e4, unit="N s/m")  # N s/m
    # The linkage hand's drive (robotiq/drive.py has the sources and ranges): the firmware's
    # position loop bandwidth [Hz], critically damped on the drive's inertia, and the
    # self-locking screw's forward efficiency, which sets how much of the rotor's inertia
    # the fingers feel while the motor drives them.
    position_loop_hz: float = bounded(
        drive.POSITION_LOOP_HZ, low=drive.POSITION_LOOP_HZ_RANGE[0],
        high=drive.POSITION_LOOP_HZ_RANGE[1], unit="Hz",
        why="the 2F-85 firmware's position loop: slower and the locked drive yields, faster "
            "and a 1 ms plant step cannot follow it")
    screw_efficiency: float = bounded(
        drive.SCREW_EFFICIENCY, low=drive.SCREW_EFFICIENCY_RANGE[0],
        high=drive.SCREW_EFFICIENCY_RANGE[1],
        why="a self-locking screw's forward efficiency is below 0.5")
    # m/s^2, finger speed ramps
    acceleration: float = bounded(0.5, low=0.0, low_open=True, high=10.0, unit="m/s^2")
    # m/s; slower than this before the goal = object detected
    stall_speed: float = bounded(0.002, low=0.0, low_open=True, high=0.15, unit="m/s",
                                 why="below the 2F-85's 150 mm/s top speed, Robotiq 2F-85 manual")


def reference_step(q: float, v: float, goal: float, max_speed: float, acceleration: float,
                   dt: float) -> float:
    """The constant acceleration [m/s^2] over the next dt that moves (q, v) toward goal
    without exceeding max_speed and while still able to stop at the goal. Python floats
    (math.sqrt rounds as np.sqrt does), called on every update."""
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
    limit [N]) of a command's (rPR, rSP, rFR) bytes. Cached: the command changes a few
    times a trial and is read on every update."""
    position_byte = float(np.clip(np.round(position), 0, 255))
    return (position_byte, float(ru.opening_from_position_byte(position_byte) / 2),
            float(ru.speed_from_byte(speed) / 2), float(ru.force_from_byte(force)))


def status_position_byte(q: float) -> float:
    """gPO of the finger coordinate q [m]: ru.position_byte_from_opening(2 q) on Python
    floats (round() rounds half to even, as np.rint)."""
    fraction = min(max(2.0 * q / ru.STROKE_M, 0.0), 1.0)
    return float(round(ru.POSITION_CLOSED_BYTE - fraction * ru.POSITION_SPAN_BYTES))


def has_arrived(q: float, v: float, goal: float, acceleration: float, dt: float) -> bool:
    """True when the reference (q, v) is within one step's reach of goal at rest: it is then
    put on the goal. Otherwise the discrete bang-bang of reference_step circles the goal in
    a limit cycle (|q - goal| about acceleration dt^2, |v| about acceleration dt), whose
    velocity the plant's PD damping turns into a grip-force ripple (about 0.1 N peak to peak
    at 30 Hz with the defaults) that a blocked finger never sees on the real gripper."""
    return abs(goal - q) <= acceleration * dt * dt and abs(v) <= acceleration * dt


def force_limited_set_point(q: float, q_ref: float, force: float, position_gain: float,
                            lever: float = 1.0) -> float:
    """The PD set-point for the actuated coordinate: the reference, but no further than
    2 force lever / position_gain from the measured q, so that a blocked finger pushes each
    pad (one actuator drives both) with at most force [N]; lever = |d(half opening)/dq|."""
    band = 2.0 * force * lever / position_gain
    return q + min(max(q_ref - q, -band), band)  # floats: called on every plant step


def drive_set_point(*, a: float, v: float, v_prev: float, set_point: tuple[float, float],
                    phase: float, anchor: float, reference: tuple[float, float], limit: float,
                    direction: float, gain: float, damping: float, inertia: float,
                    time_step: float) -> tuple[float, float, float, float, float]:
    """One step of the 2F-85's drive on the linkage hand (module docstring): the set-point
    (a_d [rad], v_d [rad/s]) of the plant's PD (gain, damping) for the next plant step, the
    phase, the motor's torque [N m] and the anchor (where the screw stopped the rotor
    [rad]), from the driver's state a, v (v_prev one step before), the set-point and phase
    of the last step, the loop's reference (a_ref, v_ref), the torque cap `limit` [N m],
    the direction the command moves the nut in (+1 or -1), the drive's inertia [kg m^2] and
    the plant's time step [s]. Python floats: called once a plant step."""
    set_a, set_v = set_point
    # The load on the drive over the last step: the PD's torque at the step's end (SAP
    # evaluates it there) less what accelerated the inertia.
    load = gain * (set_a - a) + damping * (set_v - v) - inertia * (v - v_prev) / time_step
    demand = gain * (reference[0] - a) + damping * (reference[1] - v)
    motor = min(max(demand, -limit), limit)
    if phase == HELD:
        # The screw holds; the firmware watches the encoder: a finger that closes on by
        # half the squeeze the hold carries has lost its object, and the motor drives on.
        if direction * (a - anchor) <= 0.5 * direction * (set_a - anchor):
            return set_a, 0.0, HELD, 0.0, anchor
        phase = MOVING
    elif phase == STUCK:
        if direction * motor <= direction * load:  # the screw still carries the load
            return set_a, 0.0, HELD if direction * motor >= limit else STUCK, motor, anchor
        phase = MOVING
    elif direction * v <= 0.0 and direction * load > max(direction * motor, 0.0):
        # The load would drive the rotor back: the screw stops it where it stands.
        set_a = a + load / gain
        return set_a, 0.0, HELD if direction * motor >= limit else STUCK, motor, a
    if abs(demand) <= limit:
        return reference[0], reference[1], phase, motor, anchor
    # At the current limit: the set-point that makes the PD's torque the cap, at the
    # velocity the next step reaches if the last step's acceleration holds.
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
    """The simulated 2F-85 controller's command intake, reference and status bytes, at the
    2F-85's command rate; its drive (robotiq_drive_step.py) sets the plant's PD every
    plant step from this system's state. MakeSimRobotiqDriver joins the two.

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
        finger_state: (2) the hand's actuated coordinate a and its rate, as
            MakeSimRobotiqDriver's.
        drive_memory: the drive's memory (robotiq_drive_step.MEMORY).
        planner_state: this system's state (robotiq_drive_step.PLANNER), for the drive.
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
        # Advance the reference to now with the acceleration chosen at the last update.
        h = t - s[TIME]
        s[REF_Q] += s[REF_V] * h + 0.5 * s[REF_A] * h * h
        s[REF_V] += s[REF_A] * h
        s[TIME] = t
        goal, force = s[GOAL], s[FORCE]
        s[POSITION_BYTE], s[GOAL], s[HALF_SPEED], s[FORCE] = command_targets(
            *self._command.Eval(context).tolist())
        if (s[GOAL], s[FORCE]) != (goal, force):
            if phase != MOVING:
                # Fingers the screw holds: the new motion starts where they stand, and the
                # drive moves again (it counts the restarts).
                s[REF_Q], s[REF_V], phase = q, 0.0, MOVING
                s[RESTARTS] += 1.0
            if s[GOAL] != s[REF_Q]:
                # The direction the command moves the nut in, in the actuated coordinate
                # (kept until the next command: the reference may pass its goal by a hair).
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
        # Python floats (round() rounds half to even, as np.round); the same bytes.
        s = context.get_discrete_state(self._state).get_value().tolist()
        memory = self._memory.Eval(context).tolist()
        a = self._finger_state.Eval(context).item(0)
        hand = self._hand
        # The motor's current: the torque it gives while the fingers move, none once they
        # stop (the screw holds) or stand at the requested position.
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
    """The simulated 2F-85 controller (the module docstring) as a Diagram: its planner
    (SimRobotiqPlanner, Python, at the command rate) and its drive (robotiq_drive_step.py,
    compiled, once a plant step).

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
        finger_state: (2) the hand's actuated coordinate a and its rate (the left driver's
            angle [rad] and [rad/s] on the linkage hand; half the opening [m], [m/s] on the
            prismatic one), from gripper_hands.actuated_state_selector.
        desired_state: (2) a and da/dt set-points for the plant's PD on the actuated joint,
            for the plant step that follows (set half a step before it).
        status: (8) status bytes, robotiq.units order.

    time_step is the plant's [s]: the drive runs once a plant step, half a step after it.
    """
    if not time_step > 0.0:
        raise ValueError(f"time_step {time_step} must be the plant's positive step [s]")
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
