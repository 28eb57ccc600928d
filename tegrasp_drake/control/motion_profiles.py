"""Minimum-jerk timing, pose interpolation and the state machine's straight moves: zero
velocity and acceleration at both ends, so phase boundaries ring no false RA spikes."""

import dataclasses

import numpy as np
from pydrake.math import RigidTransform
from pydrake.common.eigen_geometry import Quaternion


def minimum_jerk(tau):
    """s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5, tau clipped to [0, 1] (float or array)."""
    tau = min(max(tau, 0.0), 1.0) if isinstance(tau, float) else np.clip(tau, 0.0, 1.0)
    return tau ** 3 * (10.0 + tau * (-15.0 + 6.0 * tau))


# minimum_jerk's peak slope, ds/dtau = 15/8 at tau = 1/2: a move of d metres over T seconds
# asks at most 15/8 d / T of the hand.
MINIMUM_JERK_PEAK_SPEED = 15.0 / 8.0


def minimum_jerk_slope(tau):
    """ds/dtau = 30 tau^2 (1 - tau)^2 of minimum_jerk, 0 outside [0, 1]: a move of d metres
    over T seconds asks d / T times this of the hand at tau."""
    tau = min(max(tau, 0.0), 1.0) if isinstance(tau, float) else np.clip(tau, 0.0, 1.0)
    return 30.0 * tau ** 2 * (1.0 - tau) ** 2


def interpolate_pose(X_start: RigidTransform, X_end: RigidTransform, s: float) -> RigidTransform:
    """The pose a fraction s of the way from X_start to X_end (straight line, slerp)."""
    q0 = X_start.rotation().ToQuaternion()
    q1 = X_end.rotation().ToQuaternion()
    rotation = q0.slerp(s, q1) if s > 0 else q0
    p = (1.0 - s) * X_start.translation() + s * X_end.translation()
    return RigidTransform(Quaternion(rotation.wxyz()), p)


@dataclasses.dataclass(frozen=True)
class MotionSegment:
    """A minimum-jerk straight move of G's origin from p_start to p_end [m, world]; times [s]."""
    t_start: float
    duration: float
    p_start: tuple
    p_end: tuple

    def position(self, t: float) -> np.ndarray:
        tau = 1.0 if self.duration <= 0 else (t - self.t_start) / self.duration
        s = minimum_jerk(min(max(tau, 0.0), 1.0))
        return np.asarray(self.p_start) + s * (np.asarray(self.p_end) - np.asarray(self.p_start))

    def done(self, t: float) -> bool:
        return t >= self.t_start + self.duration

    @staticmethod
    def hold(t: float, p) -> "MotionSegment":
        """Standing still at p [m, world] from t [s] on."""
        return MotionSegment(t, 0.0, tuple(p), tuple(p))
