"""The taxel_aware controller's finger-strike sense, as pure functions: a finger's front
striking the object while the open gripper approaches it, seen in the arm's joint torques,
and where the gripper moves after it (stop, back off, shift along the stroke, approach
again: the rule taxel_aware/finger_strike.py).

The taxels cannot see it: a 45 mm box 25 mm along the 85 mm stroke lies in the path of the
finger's front, not its pad, and the moving finger knocks it over. The joints feel it: the
arm's measured joint torques, mapped onto the grasp frame G (J_G^-T), give the force on the
gripper (grasp_wrench_from_torques); a force above force_n for sustain_s is a strike
(FingerStrikeConfig, controller_config.py: the measured numbers and the reasoning).

Frames: world W; the side grasp approaches along world +x with the stroke along world y,
the left finger on +y (corrective_actions.py). Wrenches are [Mx, My, Mz, Fx, Fy, Fz]
[N m, N], on the arm at G's origin, expressed in W.
"""

import numpy as np

FINGERS = ("left", "right")


def grasp_wrench_from_torques(J_WG: np.ndarray, torques_nm) -> np.ndarray:
    """The wrench on the arm at G [N m, N; W] that the joint torques `torques_nm` [N m]
    hold statically: the actuators' torques balance it, tau = -J^T w, so w = -J^-T tau.
    J_WG: G's spatial velocity Jacobian (6 x 6, [w; v] in W) with respect to the joint
    velocities; the least-squares solution near a singularity."""
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
    """Which finger struck: the one pad touching (the taxels see it directly), else the
    sign of side_moment_nm summed over the strike's ticks, when at least min_moment_nm in
    size; None when neither tells. config: FingerStrikeConfig."""
    if contact[0] != contact[1]:
        return FINGERS[0] if contact[0] else FINGERS[1]
    if abs(moment_sum_nm) < config.min_moment_nm:
        return None
    return FINGERS[0] if moment_sum_nm > 0 else FINGERS[1]


def strike_shift(finger: str | None, opening_m: float, object_width_m: float) -> float:
    """The shift along the stroke [m, world y] after a strike: toward the struck finger by
    (opening - width) / 2, never negative; 0 for an unknown finger.

    The struck finger's front overlaps the object, so the object's centre lies at least
    opening/2 - width/2 toward that finger; moving the gripper that far puts the object
    between the fingers (a shift away from the finger would leave its front in the
    object's path)."""
    if finger is None:
        return 0.0
    sign = 1.0 if finger == FINGERS[0] else -1.0
    return sign * max((opening_m - object_width_m) / 2.0, 0.0)
