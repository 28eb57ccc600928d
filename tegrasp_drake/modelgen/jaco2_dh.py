"""Kinematics of the Kinova JACO2 6-DOF arm (j2n6s300) from Kinova, "DH parameters of
Kinova robots" (curved wrist, 60 degree wrist angle; D1 0.2755, D2 0.410, D3 0.2073, D4 D5
0.0741, D6 0.160, e2 0.0098 m). Angles are Kinova's physical q, theta_i = s_i q_i + o_i, so a
command means the same to the real arm."""

import dataclasses
import math

import numpy as np

D1, D2, D3, D4, D5, D6, E2 = 0.2755, 0.410, 0.2073, 0.0741, 0.0741, 0.160, 0.0098
WRIST_HALF_ANGLE = math.pi / 6  # aa: half of the 60 degree wrist angle.
_SA, _S2A = math.sin(WRIST_HALF_ANGLE), math.sin(2 * WRIST_HALF_ANGLE)
D4B = D3 + _SA / _S2A * D4
D5B = _SA / _S2A * D4 + _SA / _S2A * D5
D6B = _SA / _S2A * D5 + D6


@dataclasses.dataclass(frozen=True)
class DhJoint:
    """One row of the classic DH table and the joint's published limits."""
    alpha: float  # rad
    a: float  # m
    d: float  # m
    sign: float  # theta = sign * q + offset
    offset: float  # rad
    lower: float | None  # rad, physical angle; None for a continuous joint
    upper: float | None
    max_speed: float  # rad/s
    max_torque: float  # N m
    mass: float  # kg, from the j2n6s300 description


_DEG = math.pi / 180.0
JOINTS = (
    DhJoint(math.pi / 2, 0.0, D1, -1.0, 0.0, None, None, 36 * _DEG, 40.0, 0.748),
    DhJoint(math.pi, D2, 0.0, 1.0, -math.pi / 2, 47 * _DEG, 313 * _DEG, 36 * _DEG, 80.0, 0.990),
    DhJoint(math.pi / 2, 0.0, -E2, 1.0, math.pi / 2, 19 * _DEG, 341 * _DEG, 36 * _DEG, 40.0,
            0.676),
    DhJoint(2 * WRIST_HALF_ANGLE, 0.0, -D4B, 1.0, 0.0, None, None, 48 * _DEG, 20.0, 0.426),
    DhJoint(2 * WRIST_HALF_ANGLE, 0.0, -D5B, 1.0, -math.pi, None, None, 48 * _DEG, 20.0, 0.426),
    DhJoint(math.pi, 0.0, -D6B, 1.0, math.pi / 2, None, None, 48 * _DEG, 20.0, 0.200),
)


def continuous_joints_problem(continuous) -> tuple[str, str, object] | None:
    """(field, words, value) for a list of per-joint flags (JacoVelocityTrackerConfig's
    `continuous_joints`: the joints whose position error is wrapped into [-pi, pi)) that marks
    a joint with limits continuous, or None. Wrapped, such a joint's error past half a turn
    drives it the short way round, through its stop, where it has to go the long way."""
    for k, (flag, joint) in enumerate(zip(continuous, JOINTS)):
        if flag and joint.lower is not None:
            return ("continuous_joints", f"marks joint {k + 1} continuous, but the JACO2's "
                    f"joint {k + 1} turns only from {joint.lower / _DEG:g} to "
                    f"{joint.upper / _DEG:g} deg (its error must not be wrapped): give false "
                    "for it", list(continuous))
    return None


def dh_transform(alpha: float, a: float, d: float, theta: float) -> np.ndarray:
    """4x4 classic DH transform Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct],
                     [st, ct * ca, -ct * sa, a * st],
                     [0.0, sa, ca, d],
                     [0.0, 0.0, 0.0, 1.0]])


def forward_kinematics(q) -> np.ndarray:
    """X_BaseFlange as a 4x4 matrix for physical joint angles q (6,) [rad]."""
    X = np.eye(4)
    for joint, qi in zip(JOINTS, q):
        X = X @ dh_transform(joint.alpha, joint.a, joint.d, joint.sign * qi + joint.offset)
    return X
