"""The joint velocities a velocity-mode JACO2 executes for a desired joint state,
v = clip(v_des + kp wrap(q_des - q), +-v_max), zero for a non-finite desired state and
while `stop`; both stations use it (docs/hardware.md, "The devices")."""

import dataclasses

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.ranges import bounded, sized
from tegrasp_drake.rig.station_interface import ARM_JOINTS
from tegrasp_drake.rig.api_boundary import public_dataclass

_DEG = np.pi / 180.0
# [rad/s] the fastest JACO2 joints (4-6), Kinova's JACO2 6-DOF specification.
JACO2_MAX_JOINT_SPEED = 48 * _DEG
# [m] the JACO2's reach, Kinova's JACO2 6-DOF specification.
JACO2_REACH_M = 0.9
# [m/s] the fastest the hand can move: each of the 6 joints turning at the fastest joint speed
# moves it at most that speed times its distance from the joint, at most the reach.
HAND_SPEED_BOUND_MPS = 6 * JACO2_MAX_JOINT_SPEED * JACO2_REACH_M


@public_dataclass
@dataclasses.dataclass
class JacoVelocityTrackerConfig:
    """Gain and limits of the tracker."""
    # a 0.2 s time constant; phase margin 90 deg - kp (T/2 + L), 86 deg with 15 ms at 100 Hz.
    # Low end: a 10 s time constant, most of a grasp's 12 s; a slower tracker takes back no
    # position error within a trial.
    kp: float = bounded(5.0, low=0.1, high=100.0, unit="1/s",
                        why="plausible 1-20; below 0.1 an error outlasts the grasp; the loop's "
                            "phase margin is gone at about 100")
    max_joint_speed: list[float] = bounded(
        default_factory=lambda: [36 * _DEG] * 3 + [48 * _DEG] * 3, low=0.0, low_open=True,
        high=JACO2_MAX_JOINT_SPEED, unit="rad/s", length=6,
        why="the JACO2's joint speed limits, 36-48 deg/s, Kinova JACO2 specifications")
    # joints 2 and 3 have limits (modelgen/jaco2_dh.py)
    continuous_joints: list[bool] = sized(
        length=ARM_JOINTS, items="true/false values, one per joint",
        default_factory=lambda: [True, False, False, True, True, True])


def wrap_to_pi(angle):
    """Angle(s) [rad] mapped into [-pi, pi)."""
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi


def velocity_command(q_desired, v_desired, q_measured, config: JacoVelocityTrackerConfig):
    """Commanded joint velocities [rad/s] for a velocity-mode arm (module docstring)."""
    error = np.asarray(q_desired, dtype=float) - np.asarray(q_measured, dtype=float)
    error = np.where(config.continuous_joints, wrap_to_pi(error), error)
    v_max = np.asarray(config.max_joint_speed)
    command = np.clip(np.asarray(v_desired) + config.kp * error, -v_max, v_max)
    # NaN never reaches the arm.
    return np.where(np.isfinite(command), command, 0.0)


class JacoVelocityTracker(LeafSystem):
    """Adds the position-error term to a desired joint state: desired_state and
    commanded_state (12: q [rad], then v [rad/s]); position_measured (6) [rad]; stop: nonzero
    holds the arm still, unconnected never stops.

    .. pydrake_system::

        name: JacoVelocityTracker
        input_ports:
        - desired_state
        - position_measured
        - stop (optional)
        output_ports:
        - commanded_state
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
