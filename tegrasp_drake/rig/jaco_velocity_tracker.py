"""Turns a desired joint state into the joint velocities a velocity-mode JACO2 executes.

The JACO2 in joint-velocity mode executes joint velocities, nothing else, so following a
desired path needs a position-error term:

    v_cmd = clip(v_des + kp * wrap(q_des - q_measured), -v_max, v_max)

where wrap() maps the error of continuous joints into [-pi, pi); a joint whose desired
state is not finite gets zero velocity. Both stations use it: the
hardware one in front of the Kinova LCM driver (hardware/jaco/jaco_lcm_interface.py), the
simulated one in front of its model of the arm's velocity servo
(simulation/jaco_velocity_drive.py). When `stop` is set (the device watchdog tripped),
the command is to hold still: zero velocity at the measured position.

The settings (JacoVelocityTrackerConfig) and their sources:
- kp = 5 1/s: a 0.2 s time constant for a position error. The loop is an integrator
  (the arm turns velocity into position) behind the command's sample-and-hold and
  latency, about 15 ms together at 100 Hz and 10 ms (T/2 + L); with an ideal servo its
  phase margin is 90 deg - kp (T/2 + L) rad: 86 deg at 5 1/s, 73 deg at 20, 60 deg at 35,
  none at about 100. Plausible 1-20 1/s: below 1 a drift takes seconds to correct.
- max_joint_speed: Kinova's JACO2 6-DOF specification, 36 deg/s for joints 1-3 (the large
  actuators) and 48 deg/s for joints 4-6 (Kinova, "JACO2 6 DOF" specifications / KINOVA
  Gen2 user guide, technical specifications: maximum joint speed).
- continuous_joints: joints 1, 4, 5 and 6 turn without limit, 2 and 3 are limited
  (modelgen/jaco2_dh.py).
"""

import dataclasses

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.rig.station_interface import ARM_JOINTS

_DEG = np.pi / 180.0
# [rad/s] the fastest any JACO2 joint turns (joints 4-6; the specification above): the
# tracker's limits stay under it, and the arm's message check (hardware/jaco/jaco_lcm.py)
# refuses a command beyond it.
JACO2_MAX_JOINT_SPEED = 48 * _DEG


@dataclasses.dataclass
class JacoVelocityTrackerConfig:
    """Gain and limits of the tracker (the module docstring gives their sources)."""
    kp: float = bounded(5.0, low=0.0, low_open=True, high=100.0, unit="1/s",
                        why="plausible 1-20; the loop's phase margin is gone at about 100",
                        below="must be positive [1/s] (plausible 1-20)")
    max_joint_speed: list[float] = bounded(
        default_factory=lambda: [36 * _DEG] * 3 + [48 * _DEG] * 3, low=0.0, low_open=True,
        high=JACO2_MAX_JOINT_SPEED, unit="rad/s", length=6,
        why="the JACO2's joint speed limits, 36-48 deg/s, Kinova JACO2 specifications")
    continuous_joints: list[bool] = dataclasses.field(
        default_factory=lambda: [True, False, False, True, True, True])


def wrap_to_pi(angle):
    """Angle(s) [rad] mapped into [-pi, pi)."""
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi


def velocity_command(q_desired, v_desired, q_measured, config: JacoVelocityTrackerConfig):
    """Commanded joint velocities [rad/s] for a velocity-mode arm (see module docstring)."""
    error = np.asarray(q_desired, dtype=float) - np.asarray(q_measured, dtype=float)
    error = np.where(config.continuous_joints, wrap_to_pi(error), error)
    v_max = np.asarray(config.max_joint_speed)
    command = np.clip(np.asarray(v_desired) + config.kp * error, -v_max, v_max)
    # A joint whose desired state is not finite holds still: NaN never reaches the arm.
    return np.where(np.isfinite(command), command, 0.0)


class JacoVelocityTracker(LeafSystem):
    """Adds the position-error term to a desired joint state (see module docstring).

    .. pydrake_system::

        name: JacoVelocityTracker
        input_ports:
        - desired_state
        - position_measured
        - stop (optional)
        output_ports:
        - commanded_state

    Ports:
        desired_state: (12) joint positions [rad] then velocities [rad/s].
        position_measured: (6) measured joint positions [rad].
        stop: (1) nonzero holds the arm still; unconnected: never stops.
        commanded_state: (12) desired positions [rad] then commanded velocities [rad/s]
            (measured positions and zeros while stopped).
    """

    def __init__(self, config: JacoVelocityTrackerConfig | None = None):
        super().__init__()
        self._config = dataclasses.replace(config or JacoVelocityTrackerConfig())
        n = ARM_JOINTS
        self._desired_state_port = self.DeclareVectorInputPort("desired_state", 2 * n)
        self._position_port = self.DeclareVectorInputPort("position_measured", n)
        self._stop_port = self.DeclareVectorInputPort("stop", 1)
        self.DeclareVectorOutputPort("commanded_state", 2 * n, self._calc_commanded_state)

    def _calc_commanded_state(self, context, output):
        n = ARM_JOINTS
        q_measured = self._position_port.Eval(context)
        if self._stop_port.HasValue(context) and self._stop_port.Eval(context)[0] != 0:
            output.SetFromVector(np.concatenate([q_measured, np.zeros(n)]))
            return
        desired = self._desired_state_port.Eval(context)
        output.SetFromVector(np.concatenate([desired[:n], velocity_command(
            desired[:n], desired[n:], q_measured, self._config)]))
