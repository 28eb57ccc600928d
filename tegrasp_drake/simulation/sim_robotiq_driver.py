"""SimRobotiqDriver: the simulated twin of the Robotiq 2F-85's own controller.

It takes the same command bytes as the real gripper (rPR, rSP, rFR) and reports the same
status bytes (robotiq_units.py). Inside, the finger coordinate q (half the opening, m) follows
a speed- and acceleration-limited reference toward the requested position; the plant's
implicit PD (SAP) tracks it. The grip force limit is imposed the way a current-limited motor
does it: the PD set-point is kept within 2 F / kp of the measured finger position, so a
blocked finger pushes with at most F on each pad (the right finger mimics the left one, so
the single actuator carries 2 F). A finger that stops short of its goal reports an object.
"""

import dataclasses
import functools
import math

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig import robotiq_units as ru

_REF_Q, _REF_V, _REF_A, _GOAL, _HALF_SPEED, _FORCE, _POSITION_BYTE, _OBJECT, _T = range(9)


@dataclasses.dataclass
class GripperDriverConfig:
    """The simulated 2F-85 controller (position loop with a force limit)."""
    update_rate_hz: float = 200.0  # the 2F-85 accepts commands at up to 200 Hz
    position_gain: float = 4000.0  # N/m on the finger coordinate
    damping_gain: float = 40.0  # N s/m
    acceleration: float = 0.5  # m/s^2, finger speed ramps
    stall_speed: float = 0.002  # m/s; slower than this before the goal = object detected


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


def force_limited_set_point(q: float, q_ref: float, force: float, position_gain: float) -> float:
    """The PD set-point [m] for the actuated finger: the reference, but no further than
    2 force / position_gain from the measured q, so that a blocked finger pushes each pad
    (the right finger mimics the left, so the actuator carries both) with at most force [N]."""
    band = 2.0 * force / position_gain
    return q + min(max(q_ref - q, -band), band)  # floats: called on every plant step


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
    """Input ports: command (3: rPR, rSP, rFR bytes), finger_state (4: q_left, q_right,
    v_left, v_right from the plant's gripper instance). Output ports: desired_state (2: q, v
    of the actuated left finger, to the plant), status (8 bytes, robotiq_units order)."""

    def __init__(self, *, config: GripperDriverConfig, initial_opening: float = ru.STROKE_M):
        super().__init__()
        self._config = config
        self._dt = 1.0 / config.update_rate_hz
        self._command = self.DeclareVectorInputPort("command", ru.COMMAND_SIZE)
        self._finger_state = self.DeclareVectorInputPort("finger_state", 4)
        q0 = initial_opening / 2
        initial = np.zeros(9)
        initial[[_REF_Q, _GOAL]] = q0
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
        q, _, v, _ = self._finger_state.Eval(context)
        s[_OBJECT] = object_status(q, v, s[_REF_Q], s[_GOAL], self._config.stall_speed)
        discrete_state.set_value(self._state, s)

    def _calc_desired_state(self, context, output):
        # Evaluated on every plant step: Python floats, not numpy scalars (a tenth of the
        # overhead, the same IEEE arithmetic).
        ref_q, ref_v, ref_a, force, updated_at = context.get_discrete_state(
            self._state).value()[[_REF_Q, _REF_V, _REF_A, _FORCE, _T]].tolist()
        h = context.get_time() - updated_at
        q_ref = ref_q + ref_v * h + 0.5 * ref_a * h * h
        v_ref = ref_v + ref_a * h
        q = self._finger_state.Eval(context).item(0)
        output.SetFromVector([force_limited_set_point(q, q_ref, force,
                                                      self._config.position_gain), v_ref])

    def _calc_status(self, context, output):
        # Python floats (round() rounds half to even, as np.round); the same bytes.
        s = context.get_discrete_state(self._state).get_value().tolist()
        q = self._finger_state.Eval(context).item(0)
        band = 2.0 * s[_FORCE] / self._config.position_gain
        force = self._config.position_gain * min(abs(s[_REF_Q] - q), band) / 2.0
        status = [0.0] * ru.STATUS_SIZE
        status[ru.STATUS_ACT] = 1.0
        status[ru.STATUS_GTO] = 1.0
        status[ru.STATUS_STA] = float(ru.ActivationStatus.ACTIVE)
        status[ru.STATUS_OBJ] = s[_OBJECT]
        status[ru.STATUS_PR] = s[_POSITION_BYTE]
        status[ru.STATUS_PO] = status_position_byte(q)
        status[ru.STATUS_CU] = float(min(max(round(force / ru.FORCE_MAX_N * 255.0), 0), 255))
        output.SetFromVector(status)
