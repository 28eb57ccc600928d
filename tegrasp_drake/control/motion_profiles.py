"""Smooth point-to-point motion: minimum-jerk timing and pose interpolation.

A minimum-jerk segment starts and ends with zero velocity and acceleration, so phase
boundaries put no velocity jumps (and no false RA spikes) into the pad accelerometers.
"""

import numpy as np
from pydrake.math import RigidTransform
from pydrake.common.eigen_geometry import Quaternion


def minimum_jerk(tau):
    """s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 for tau clipped to [0, 1]."""
    tau = np.clip(tau, 0.0, 1.0)
    return tau ** 3 * (10.0 + tau * (-15.0 + 6.0 * tau))


def interpolate_pose(X_start: RigidTransform, X_end: RigidTransform, s: float) -> RigidTransform:
    """The pose a fraction s of the way from X_start to X_end (straight line, slerp)."""
    q0 = X_start.rotation().ToQuaternion()
    q1 = X_end.rotation().ToQuaternion()
    rotation = q0.slerp(s, q1) if s > 0 else q0
    p = (1.0 - s) * X_start.translation() + s * X_end.translation()
    return RigidTransform(Quaternion(rotation.wxyz()), p)
