"""The taxel_aware finger-strike sense as pure functions: a finger's front striking the object in
the approach, which the taxels barely see, read from the arm's joint torques mapped onto the grasp
frame G, and the shift after it (docs/controller.md, "Finger strike"). Wrenches are [Mx, My, Mz,
Fx, Fy, Fz] [N m, N] on the arm at G, in world W (approach +x, stroke y, left finger on +y)."""

import numpy as np

FINGERS = ("left", "right")


def grasp_wrench_from_torques(J_WG: np.ndarray, torques_nm) -> np.ndarray:
    """The wrench on the arm at G [N m, N; W] that joint torques `torques_nm` [N m] hold
    statically: w = -J_WG^-T tau (least squares near a singularity)."""
    solution, *_ = np.linalg.lstsq(np.asarray(J_WG, dtype=float).T,
                                   -np.asarray(torques_nm, dtype=float), rcond=None)
    return solution


def strike_force_n(wrench, baseline) -> float:
    """The size of the force on G [N] beyond the baseline wrench (the approach's start)."""
    return float(np.linalg.norm(np.subtract(wrench, baseline)[3:6]))


def side_moment_nm(wrench, baseline) -> float:
    """The moment that says which finger struck [N m]: about world x (the approach axis)
    plus about world z, beyond the baseline; positive for the left finger (on +y)."""
    delta = np.subtract(wrench, baseline)
    return float(delta[0] + delta[2])


def struck_finger(moment_sum_nm: float, contact: tuple, config) -> str | None:
    """Which finger struck: the one pad touching, else the sign of side_moment_nm summed over
    the strike, when at least min_moment_nm; None when neither tells."""
    if contact[0] != contact[1]:
        return FINGERS[0] if contact[0] else FINGERS[1]
    if abs(moment_sum_nm) < config.min_moment_nm:
        return None
    return FINGERS[0] if moment_sum_nm > 0 else FINGERS[1]


def strike_shift(finger: str | None, opening_m: float, object_width_m: float) -> float:
    """The shift [m, world y] after a strike: toward the struck finger (whose front overlaps
    the object) by (opening - width) / 2, never negative; 0 for an unknown finger."""
    if finger is None:
        return 0.0
    sign = 1.0 if finger == FINGERS[0] else -1.0
    return sign * max((opening_m - object_width_m) / 2.0, 0.0)
