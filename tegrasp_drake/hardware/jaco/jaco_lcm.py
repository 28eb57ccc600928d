"""Kinova JACO2 LCM messages (`lcmt_jaco_command`, `lcmt_jaco_status`) to and from
vectors, in Drake's driver pattern, and the arm's message-boundary checks. The driver runs
the arm in joint-velocity mode at 100 Hz and ignores `joint_position` (kept for logs), so
JacoVelocityTracker turns position error into velocity first. Units: rad, rad/s, N m, `utime`
in us; num_fingers = 0 (the 2F-85 is on its own bus)."""

import math

import numpy as np
from drake import lcmt_jaco_command, lcmt_jaco_status
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import BasicVector, LeafSystem

from tegrasp_drake.hardware.lcm_boundary import decode_lcm
from tegrasp_drake.hardware.lcm_time import utime_from_time
from tegrasp_drake.hardware.message_boundary import MessageBoundary, RejectedMessage
from tegrasp_drake.modelgen.jaco2_dh import JOINTS as JACO2_JOINTS
from tegrasp_drake.rig.jaco_velocity_tracker import JACO2_MAX_JOINT_SPEED

JACO_NUM_JOINTS = 6
JACO_COMMAND_CHANNEL = "KINOVA_JACO_COMMAND"
JACO_STATUS_CHANNEL = "KINOVA_JACO_STATUS"
JACO_LCM_PERIOD = 0.01  # [s], the driver's 100 Hz
# [rad/s] the fastest JACO2 joint, 48 deg/s (Kinova's specification): no faster command is sane.
JACO_MAX_JOINT_SPEED = JACO2_MAX_JOINT_SPEED

WRONG_JOINT_COUNT = "wrong joint count"
NOT_FINITE = "not finite"
TOO_FAST = "beyond the joint speed limit"
NEGATIVE_UTIME = "negative utime"
OUT_OF_RANGE = "beyond the JACO2's range"

# What a JACO2 can report, per joint, from its published limits (modelgen/jaco2_dh.py:
# Kinova's joint limits, speeds and torques). Stated bounds, not from a specification:
# [rad] past a limited joint's stop (joints 2, 3): the firmware stops the joint at its
# limit; overshoot within a 10 ms period at 36 deg/s is 0.36 deg and compliance under load a
# degree or two, so 5 deg past the stop is no reading of this arm.
_STOP_MARGIN = math.radians(5.0)
# [rad] a continuous joint's angle: the actuator may count whole turns; a thousand turns
# take over two hours of turning one way at 48 deg/s, beyond any session.
_CONTINUOUS_RANGE = 1000 * 2 * math.pi
# Measured speed and torque may pass the actuator's own maximum when the arm is pushed or
# overshoots; twice that is beyond either (the emulated arm's runs read at most 20 deg/s
# and 1.2 N m).
_MEASURED_MARGIN = 2.0


def _position_range(joint) -> tuple[float, float]:
    if joint.lower is None:
        return -_CONTINUOUS_RANGE, _CONTINUOUS_RANGE
    return joint.lower - _STOP_MARGIN, joint.upper + _STOP_MARGIN


# field -> ([(low, high)] per joint, unit), the ranges check_jaco_status enforces.
JACO_STATUS_RANGES = {
    "joint_position": ([_position_range(j) for j in JACO2_JOINTS], "rad"),
    "joint_velocity": ([(-_MEASURED_MARGIN * j.max_speed, _MEASURED_MARGIN * j.max_speed)
                        for j in JACO2_JOINTS], "rad/s"),
    "joint_torque": ([(-_MEASURED_MARGIN * j.max_torque, _MEASURED_MARGIN * j.max_torque)
                      for j in JACO2_JOINTS], "N m"),
}


def make_jaco_command(utime, position, velocity) -> lcmt_jaco_command:
    """An `lcmt_jaco_command` for 6 joint positions [rad] and velocities [rad/s]."""
    message = lcmt_jaco_command()
    message.utime = int(utime)
    message.num_joints = JACO_NUM_JOINTS
    message.joint_position = [float(x) for x in position]
    message.joint_velocity = [float(x) for x in velocity]
    message.num_fingers = 0
    message.finger_position = []
    message.finger_velocity = []
    return message


def make_jaco_status(utime, position, velocity, torque) -> lcmt_jaco_status:
    """An `lcmt_jaco_status` for measured positions, velocities and torques."""
    message = lcmt_jaco_status()
    message.utime = int(utime)
    message.num_joints = JACO_NUM_JOINTS
    message.joint_position = [float(x) for x in position]
    message.joint_velocity = [float(x) for x in velocity]
    message.joint_torque = [float(x) for x in torque]
    message.joint_torque_external = [0.0] * JACO_NUM_JOINTS
    message.joint_current = [0.0] * JACO_NUM_JOINTS
    message.num_fingers = 0
    for name in ("finger_position", "finger_velocity", "finger_torque",
                 "finger_torque_external", "finger_current"):
        setattr(message, name, [])
    return message


def _check_joints(message, fields) -> None:
    """RejectedMessage unless `message` holds JACO_NUM_JOINTS finite values in each of `fields`."""
    name = type(message).__name__
    if message.num_joints != JACO_NUM_JOINTS:
        raise RejectedMessage(WRONG_JOINT_COUNT, f"{name} with num_joints = "
                              f"{message.num_joints}; the JACO2 has {JACO_NUM_JOINTS}")
    for field in fields:
        values = getattr(message, field)
        bad = [k for k, value in enumerate(values) if not math.isfinite(value)]
        if bad:
            raise RejectedMessage(NOT_FINITE, f"{name} {field}[{bad[0]}] is "
                                  f"{values[bad[0]]}")


def check_jaco_status(data: bytes) -> lcmt_jaco_status:
    """A KINOVA_JACO_STATUS message decoded and checked (check_jaco_status_message); else
    RejectedMessage."""
    return check_jaco_status_message(decode_lcm(lcmt_jaco_status, data))


def check_jaco_status_message(message: lcmt_jaco_status) -> lcmt_jaco_status:
    """`message`, a decoded status, checked as the live run checks each one it receives (6
    joints, finite, within JACO_STATUS_RANGES, utime >= 0: the arm's clock starts at or after
    0); else RejectedMessage. A run log's reader checks the statuses it has decoded with it."""
    _check_joints(message, tuple(JACO_STATUS_RANGES))
    for field, (ranges, unit) in JACO_STATUS_RANGES.items():
        for k, (value, (low, high)) in enumerate(zip(getattr(message, field), ranges)):
            if not low <= value <= high:
                raise RejectedMessage(OUT_OF_RANGE, f"lcmt_jaco_status {field}[{k}] = "
                                      f"{value:.6g} {unit}; the JACO2's joint {k + 1} reads "
                                      f"within [{low:.6g}, {high:.6g}] {unit}")
    if message.utime < 0:
        raise RejectedMessage(NEGATIVE_UTIME, f"lcmt_jaco_status utime = {message.utime} us")
    return message


def jaco_status_boundary(source: str = f"arm: {JACO_STATUS_CHANNEL}") -> MessageBoundary:
    """The boundary of one run's KINOVA_JACO_STATUS stream: check_jaco_status.

    The order of `utime` is not checked. Drake's LCM subscriber hands on only the newest
    status each time it is read, from a queue that fills while the run waits for its
    devices, and a simulated arm behind real time catches up in bursts: a genuine stream's
    utime steps by up to a second between two reads on a loaded host (measured with the
    emulated arm beside a CPU hog on both cores). A rule that each utime follow the last
    lets one forged far-future status refuse every genuine one after it (the arm then looks
    silent), and a bound on the step refuses the genuine bursts. A status that is out of
    order is one sample; the watchdog counts any change of utime as new data."""
    return MessageBoundary(source, check_jaco_status)


def check_jaco_command(data: bytes) -> lcmt_jaco_command:
    """A KINOVA_JACO_COMMAND message decoded and checked (6 joints, finite, no joint faster
    than JACO_MAX_JOINT_SPEED: check_jaco_command_message); else RejectedMessage naming the
    defect."""
    return check_jaco_command_message(decode_lcm(lcmt_jaco_command, data))


def check_jaco_command_message(message: lcmt_jaco_command) -> lcmt_jaco_command:
    """`message`, a decoded command, checked as the arm's boundary checks each one it receives
    (check_jaco_command); else RejectedMessage. A run log's reader checks the commands it has
    decoded with it."""
    _check_joints(message, ("joint_position", "joint_velocity"))
    fast = [k for k, v in enumerate(message.joint_velocity) if abs(v) > JACO_MAX_JOINT_SPEED]
    if fast:
        raise RejectedMessage(TOO_FAST, f"joint_velocity[{fast[0]}] = "
                              f"{message.joint_velocity[fast[0]]:.6g} rad/s; the JACO2 turns "
                              f"at most {JACO_MAX_JOINT_SPEED:.3f} rad/s")
    return message


def has_joints(message) -> bool:
    """False for the default (never received) message; a checked message has 6 joints."""
    return message.num_joints == JACO_NUM_JOINTS


class JacoCommandSender(LeafSystem):
    """desired_state (12: q [rad], then v [rad/s]) as an `lcmt_jaco_command`, utime = Context time;
    the arm executes v, so v holds the position-error term (JacoVelocityTracker's commanded_state).

    .. pydrake_system::

        name: JacoCommandSender
        input_ports:
        - desired_state
        output_ports:
        - lcmt_jaco_command
    """

    def __init__(self):
        super().__init__()
        self._desired_state_port = self.DeclareVectorInputPort(
            "desired_state", 2 * JACO_NUM_JOINTS)
        self.DeclareAbstractOutputPort(
            "lcmt_jaco_command", lambda: AbstractValue.Make(lcmt_jaco_command()),
            self._calc_command)

    def _calc_command(self, context, output):
        state = self._desired_state_port.Eval(context)
        output.set_value(make_jaco_command(
            utime_from_time(context.get_time()), state[:JACO_NUM_JOINTS],
            state[JACO_NUM_JOINTS:]))


class JacoCommandReceiver(LeafSystem):
    """`lcmt_jaco_command` as desired_state (12: q [rad], then v [rad/s]), on the emulator side.
    With no new `utime` for `command_timeout` [s] (or none yet) the arm stops, as with the real
    driver: the last sampled position_measured [rad] at zero velocity.

    .. pydrake_system::

        name: JacoCommandReceiver
        input_ports:
        - lcmt_jaco_command
        - position_measured
        output_ports:
        - desired_state
    """

    def __init__(self, *, command_timeout: float = 0.05, period: float = JACO_LCM_PERIOD / 2):
        super().__init__()
        self._command_timeout = command_timeout
        self._message_port = self.DeclareAbstractInputPort(
            "lcmt_jaco_command", AbstractValue.Make(lcmt_jaco_command()))
        self._position_port = self.DeclareVectorInputPort(
            "position_measured", JACO_NUM_JOINTS)
        # [last utime seen, Context time first seen, hold position (6)]
        self._state_index = self.DeclareDiscreteState(
            np.concatenate([[-1.0, -np.inf], np.zeros(JACO_NUM_JOINTS)]))
        self.DeclareInitializationDiscreteUpdateEvent(self._update)
        self.DeclarePeriodicDiscreteUpdateEvent(period, 0.0, self._update)
        self.DeclareVectorOutputPort(
            "desired_state", 2 * JACO_NUM_JOINTS, self._calc_desired_state,
            prerequisites_of_calc={self.xd_ticket(), self.time_ticket(),
                                   self._message_port.ticket()})

    def _update(self, context, discrete_state):
        old = context.get_discrete_state(self._state_index).get_value()
        new = old.copy()
        message = self._message_port.Eval(context)
        if has_joints(message) and message.utime != old[0]:
            new[0], new[1] = message.utime, context.get_time()
        if not self._is_fresh(new, context.get_time()):
            new[2:] = self._position_port.Eval(context)
        discrete_state.get_mutable_vector(self._state_index).SetFromVector(new)

    def _is_fresh(self, state, time) -> bool:
        return time - state[1] <= self._command_timeout

    def _calc_desired_state(self, context, output):
        state = context.get_discrete_state(self._state_index).get_value()
        message = self._message_port.Eval(context)
        # A utime not yet in the state arrived after the last update: fresh by definition.
        if has_joints(message) and (message.utime != state[0] or self._is_fresh(
                state, context.get_time())):
            output.SetFromVector(np.concatenate(
                [message.joint_position, message.joint_velocity]))
        else:
            output.SetFromVector(np.concatenate([state[2:], np.zeros(JACO_NUM_JOINTS)]))


class JacoStatusSender(LeafSystem):
    """The measured joint state ([rad], [rad/s], [N m]) as an `lcmt_jaco_status` (emulator side).

    .. pydrake_system::

        name: JacoStatusSender
        input_ports:
        - position_measured
        - velocity_measured
        - torque_measured
        output_ports:
        - lcmt_jaco_status
    """

    def __init__(self):
        super().__init__()
        self._position_port = self.DeclareVectorInputPort("position_measured", JACO_NUM_JOINTS)
        self._velocity_port = self.DeclareVectorInputPort("velocity_measured", JACO_NUM_JOINTS)
        self._torque_port = self.DeclareVectorInputPort("torque_measured", JACO_NUM_JOINTS)
        self.DeclareAbstractOutputPort(
            "lcmt_jaco_status", lambda: AbstractValue.Make(lcmt_jaco_status()),
            self._calc_status)

    def _calc_status(self, context, output):
        output.set_value(make_jaco_status(
            utime_from_time(context.get_time()), self._position_port.Eval(context),
            self._velocity_port.Eval(context), self._torque_port.Eval(context)))


class JacoStatusReceiver(LeafSystem):
    """`lcmt_jaco_status` as joint vectors [rad, rad/s, N m] and time_measured (utime [s]).
    Before the first message every output is zero, which the watchdog reads as "not heard".

    .. pydrake_system::

        name: JacoStatusReceiver
        input_ports:
        - lcmt_jaco_status
        output_ports:
        - position_measured
        - velocity_measured
        - torque_measured
        - time_measured
    """

    def __init__(self):
        super().__init__()
        self._message_port = self.DeclareAbstractInputPort(
            "lcmt_jaco_status", AbstractValue.Make(lcmt_jaco_status()))
        for name, field in (("position_measured", "joint_position"),
                            ("velocity_measured", "joint_velocity"),
                            ("torque_measured", "joint_torque")):
            self.DeclareVectorOutputPort(
                name, JACO_NUM_JOINTS, self._make_calc(field),
                prerequisites_of_calc={self._message_port.ticket()})
        self.DeclareVectorOutputPort(
            "time_measured", 1, self._calc_time_measured,
            prerequisites_of_calc={self._message_port.ticket()})

    def _make_calc(self, field):
        def calc(context, output: BasicVector):
            message = self._message_port.Eval(context)
            output.SetFromVector(getattr(message, field) if has_joints(message)
                                 else np.zeros(JACO_NUM_JOINTS))
        return calc

    def _calc_time_measured(self, context, output):
        message = self._message_port.Eval(context)
        output.SetAtIndex(0, message.utime * 1e-6 if has_joints(message) else 0.0)
