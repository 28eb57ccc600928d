"""SimRobotiqDriver: the simulated twin of the Robotiq 2F-85's own controller.

It takes the same command bytes as the real gripper (rPR, rSP, rFR) and reports the same
status bytes (robotiq/units.py). Inside, half the pad opening q [m] follows a speed- and
acceleration-limited reference toward the requested position (the 2F-85's speed setting is a
finger speed); the hand (gripper_hands.py) maps it to its actuated coordinate a (the left
driver's angle on the linkage hand, q itself on the prismatic one), which the plant's
implicit PD (SAP) tracks. The grip force limit is imposed the way a current-limited motor
does it: the PD set-point is kept within 2 F |dq/da| / kp of the measured a, so a blocked
finger pushes each pad with at most F in a parallel grasp (one actuator drives both fingers,
so it carries both pads' share). On the linkage hand the drive is non-backdrivable, as the
2F-85's screw and nut are: the set-point (the nut) moves only in the commanded direction, so
a load pushing the fingers back meets the PD's full stiffness, not the force limit. The
position byte gPO is computed from the measured a through the hand's linkage; a finger that
stops short of its goal reports an object (gOBJ).
"""

import dataclasses
import functools
import math

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.simulation.gripper_hands import GRIPPER_MODELS, gripper_hand

(_REF_Q, _REF_V, _REF_A, _GOAL, _HALF_SPEED, _FORCE, _POSITION_BYTE, _OBJECT, _T, _HELD,
 _DIRECTION) = range(11)


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
    # The linkage hand's PD on the driver angle. The screw drive is stiff: 1000 N m/rad
    # gives 0.16 mm at a pad pushed with 50 N (lever 57 mm), and the damping is critical
    # for both fingers' linkage inertia about the driver axis, about 2.4e-4 kg m^2
    # (2 sqrt(1000 x 2.4e-4) = 0.98).
    # N m/rad
    driver_position_gain: float = bounded(1000.0, low=0.0, low_open=True, high=1e5, unit="N m/rad")
    driver_damping_gain: float = bounded(1.0, low=0.0, high=1e3, unit="N m s/rad")  # N m s/rad
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


def nut_set_point(held: float, limited: float, reference: float, direction: float) -> float:
    """The set-point of a non-backdrivable drive: the nut at `held` moves only in
    `direction` (+1 or -1; 0 when it has not moved yet), toward the force-limited set-point
    `limited` but never past the reference. A load that pushes the finger either way
    leaves it where it is."""
    if direction > 0.0:
        return max(held, min(limited, reference))
    if direction < 0.0:
        return min(held, max(limited, reference))
    return limited


def object_status(q: float, v: float, q_ref: float, goal: float, stall_speed: float) -> int:
    """gOBJ from the finger's measured motion (see ObjectStatus)."""
    if abs(q - goal) < 5e-4:
        return int(ru.ObjectStatus.AT_REQUESTED_POSITION)
    if abs(v) < stall_speed and abs(q_ref - q) > 1e-3:
        closing = goal < q
        return int(ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING if closing
                   else ru.ObjectStatus.STOPPED_ON_CONTACT_OPENING)
    return int(ru.ObjectStatus.MOVING)


class SimRobotiqDriver(LeafSystem):
    """The simulated 2F-85 controller.

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
        desired_state: (2) a and da/dt set-points for the plant's PD on the actuated joint.
        status: (8) status bytes, robotiq.units order.
    """

    def __init__(self, *, config: GripperDriverConfig, initial_opening: float = ru.STROKE_M):
        super().__init__()
        if config.model not in GRIPPER_MODELS:
            raise ValueError(f"gripper.model '{config.model}' is not one of "
                             f"{', '.join(GRIPPER_MODELS)}")
        self._config = config
        self._hand = gripper_hand(config.model)
        self._gain, _ = self._hand.pd_gains(config)
        self._dt = 1.0 / config.update_rate_hz
        self._command = self.DeclareVectorInputPort("command", ru.COMMAND_SIZE)
        self._finger_state = self.DeclareVectorInputPort("finger_state", 2)
        q0 = initial_opening / 2
        initial = np.zeros(11)
        initial[[_REF_Q, _GOAL]] = q0
        initial[_HELD] = self._hand.actuated(q0)
        initial[_HALF_SPEED] = ru.SPEED_MIN_MPS / 2
        initial[_FORCE] = ru.FORCE_MIN_N
        initial[_POSITION_BYTE] = ru.position_byte_from_opening(initial_opening)
        initial[_OBJECT] = int(ru.ObjectStatus.AT_REQUESTED_POSITION)
        self._state = self.DeclareDiscreteState(initial)
        self.DeclarePeriodicDiscreteUpdateEvent(self._dt, 0.0, self._update)
        state_ticket = {self.discrete_state_ticket(self._state), self.time_ticket(),
                        self._finger_state.ticket()}
        self.DeclareVectorOutputPort("desired_state", 2, self._calc_desired_state,
                                     prerequisites_of_calc=state_ticket)
        self.DeclareVectorOutputPort(
            "status", ru.STATUS_SIZE, self._calc_status,
            prerequisites_of_calc={self.discrete_state_ticket(self._state),
                                   self._finger_state.ticket()})

    def _update(self, context, discrete_state):
        s = context.get_discrete_state(self._state).value().copy()
        t = context.get_time()
        hand = self._hand
        if hand.non_backdrivable:  # the nut stays where the last plant step put it
            s[_HELD] = self._set_point(context, s,
                                       hand.actuated(self._reference(context, s)[0]))
        # Advance the reference to now with the acceleration chosen at the last update.
        h = t - s[_T]
        s[_REF_Q] += s[_REF_V] * h + 0.5 * s[_REF_A] * h * h
        s[_REF_V] += s[_REF_A] * h
        s[_T] = t
        s[_POSITION_BYTE], s[_GOAL], s[_HALF_SPEED], s[_FORCE] = command_targets(
            *self._command.Eval(context).tolist())
        if has_arrived(s[_REF_Q], s[_REF_V], s[_GOAL], self._config.acceleration, self._dt):
            s[_REF_Q], s[_REF_V] = s[_GOAL], 0.0
        s[_REF_A] = reference_step(s[_REF_Q], s[_REF_V], s[_GOAL], s[_HALF_SPEED],
                                   self._config.acceleration, self._dt)
        if hand.non_backdrivable and s[_GOAL] != s[_REF_Q]:
            # The direction the nut moves in, in the actuated coordinate.
            rate = hand.half_opening_rate(hand.actuated(s[_REF_Q]))
            s[_DIRECTION] = 1.0 if (s[_GOAL] - s[_REF_Q]) * rate > 0.0 else -1.0
        a, v = self._finger_state.Eval(context).tolist()
        q = hand.half_opening(a)
        s[_OBJECT] = object_status(q, v * hand.half_opening_rate(a), s[_REF_Q], s[_GOAL],
                                   self._config.stall_speed)
        discrete_state.set_value(self._state, s)

    def _reference(self, context, s) -> tuple[float, float]:
        """(q_ref [m], v_ref [m/s]): the reference of half the opening now, from state s."""
        h = context.get_time() - s[_T]
        return (s[_REF_Q] + s[_REF_V] * h + 0.5 * s[_REF_A] * h * h,
                s[_REF_V] + s[_REF_A] * h)

    def _set_point(self, context, s, reference: float) -> float:
        """The PD set-point of the actuated coordinate now, from state s (a list or array)
        and the reference in the actuated coordinate."""
        a = self._finger_state.Eval(context).item(0)
        hand = self._hand
        limited = force_limited_set_point(a, reference, s[_FORCE], self._gain,
                                          abs(hand.half_opening_rate(a)))
        if hand.non_backdrivable:
            return nut_set_point(s[_HELD], limited, reference, s[_DIRECTION])
        return limited

    def _calc_desired_state(self, context, output):
        # Evaluated on every plant step: Python floats, not numpy scalars (a tenth of the
        # overhead, the same IEEE arithmetic).
        s = context.get_discrete_state(self._state).value().tolist()
        q_ref, v_ref = self._reference(context, s)
        reference = self._hand.actuated(q_ref)
        v_ref = v_ref / self._hand.half_opening_rate(reference)
        set_point = self._set_point(context, s, reference)
        if self._hand.non_backdrivable and set_point != reference:
            # The nut is held back by the force limit or stands: it does not move with the
            # reference, and a PD damping term on the reference's speed would add
            # kd v_ref to the grip (4 N at 25 mm/s with the linkage's gains).
            v_ref = 0.0
        output.SetFromVector([set_point, v_ref])

    def _calc_status(self, context, output):
        # Python floats (round() rounds half to even, as np.round); the same bytes.
        s = context.get_discrete_state(self._state).get_value().tolist()
        a = self._finger_state.Eval(context).item(0)
        hand = self._hand
        lever = abs(hand.half_opening_rate(a))
        band = 2.0 * s[_FORCE] * lever / self._gain
        # The motor's current is capped at the force limit; a held load beyond it is taken
        # by the screw, not the motor.
        force = self._gain * min(abs(hand.actuated(s[_REF_Q]) - a), band) / (2.0 * lever)
        status = [0.0] * ru.STATUS_SIZE
        status[ru.STATUS_ACT] = 1.0
        status[ru.STATUS_GTO] = 1.0
        status[ru.STATUS_STA] = float(ru.ActivationStatus.ACTIVE)
        status[ru.STATUS_OBJ] = s[_OBJECT]
        status[ru.STATUS_PR] = s[_POSITION_BYTE]
        status[ru.STATUS_PO] = status_position_byte(hand.half_opening(a))
        status[ru.STATUS_CU] = ru.current_byte(
            force, moving=s[_OBJECT] == int(ru.ObjectStatus.MOVING))
        output.SetFromVector(status)
