"""The taxel_aware finger-strike sense as pure functions: a finger's front striking the object in
the approach, which the taxels barely see, read from the arm's joint torques mapped onto the grasp
frame G, and the shift after it (docs/controller.md, "Finger strike"). Wrenches are [Mx, My, Mz,
Fx, Fy, Fz] [N m, N] on the arm at G, in world W (approach +x, stroke y, left finger on +y)."""

import numpy as np

from tegrasp_drake.modelgen.robotiq_sdf import FINGER_LINK_THICKNESS
from tegrasp_drake.rig.tactile_fingertip import PAD_THICKNESS

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


# [m] how far along the stroke a finger's front reaches out from its pad face: the pad (4 mm)
# and its backing (10 mm) behind it, the colliding parts of both hand models (modelgen)
FINGER_FRONT_M = PAD_THICKNESS + FINGER_LINK_THICKNESS


def toward_finger(finger: str | None, distance_m: float) -> float:
    """distance_m [m, >= 0] along world y toward `finger` (left on +y); 0 for None."""
    if finger is None:
        return 0.0
    return (1.0 if finger == FINGERS[0] else -1.0) * max(distance_m, 0.0)


def strike_shift(finger: str | None, opening_m: float, object_width_m: float,
                 front_m: float = FINGER_FRONT_M) -> float:
    """The shift [m, world y] after a strike: toward the struck finger by
    (opening - width + front) / 2, never negative; 0 for an unknown finger.

    The front met the object's near face, so the object's face on that side, e, lies between
    the struck pad's face (opening / 2 from the grasp axis) and the front's back, front_m
    further out; nothing in the strike says where. After a shift d the struck pad clears the
    object by opening / 2 + d - e and the other pad by e - width + opening / 2 - d; the d
    that leaves the worst e of that range the most clearance on both sides is the middle one,
    (opening - width + front) / 2, leaving (opening - width - front) / 2 at each pad (5.5 mm
    for a 60 mm object on the 85 mm stroke, 13 mm for 45 mm) where the face's old shift,
    (opening - width) / 2, left none to the struck pad when the object's face lay at the
    front's back. The close adds no sideways need: on the linkage the pad's face only moves
    inward over the driver's travel (robotiq/linkage.py: d(half_opening)/d(theta) < 0) while
    it travels out along the approach (docs/controller.md, "Finger strike")."""
    return toward_finger(finger, (opening_m - object_width_m + front_m) / 2.0)


def pad_touch_shift(finger: str | None, opening_m: float, object_width_m: float) -> float:
    """The shift [m, world y] after one pad's face touched the object at opening_m [m]:
    toward that finger by (opening - width) / 2, the object's centre then on the grasp axis;
    0 for an unknown finger."""
    return toward_finger(finger, (opening_m - object_width_m) / 2.0)
