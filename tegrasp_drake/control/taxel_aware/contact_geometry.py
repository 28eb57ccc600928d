"""What the taxel-aware rules know about the object's place, as pure functions of the
contact's geometry: where a Re-Reach moves, the faces the fingers touched, the push of a
close and whether it topples the object, a touch beyond the pads, an object caged behind
them, a tilted hold. The ContactEstimator (estimator.py) calls them each tick; the rules
(table.py) read what it estimated.

Frames: world W; the side grasp approaches along world +x with the stroke along world y,
the left finger on +y (corrective_actions.py). Settings: TaxelAwareConfig
(controller_config.py).
"""

import dataclasses

import numpy as np

from tegrasp_drake.control.taxel_contact import GraspContact
from tegrasp_drake.rig.taxel_layout import PAD_LENGTH


@dataclasses.dataclass(frozen=True)
class Shift:
    """A Re-Reach move of the open gripper [m, world]: dx along the approach axis, dy along
    the stroke."""
    dx_m: float
    dy_m: float


def approach_shift(contact: GraspContact, taxel_config,
                   pad_travel_to_grasp_m: float = 0.0) -> float:
    """The shift along world x [m] that puts the pads' centres on the contact once closed
    on the object: the contact's approach_offset_m (pad +y is world +x at the side grasp)
    less the pads' travel along the approach axis still to come as they close to the
    object's width (pad_travel_to_grasp_m [m]: 0 on the prismatic hand), clipped to
    +-max_approach_shift_m; 0 without contact or within centre_tolerance_m."""
    touching = contact.left.touching or contact.right.touching
    offset = contact.approach_offset_m - pad_travel_to_grasp_m
    if not touching or abs(offset) <= taxel_config.centre_tolerance_m:
        return 0.0
    return float(np.clip(offset, -taxel_config.max_approach_shift_m,
                         taxel_config.max_approach_shift_m))


@dataclasses.dataclass(frozen=True)
class FaceTouch:
    """A finger that touched the object alone while closing, and where: finger "left"
    (on world +y) or "right"; face_y_m [m, world y] the object's face under its pad."""
    finger: str
    face_y_m: float


def touched_face(finger: str, gripper_y_m: float, opening_m: float) -> FaceTouch:
    """The face a finger touching alone presses [m, world y]: the fingers close
    symmetrically about the grasp frame's origin gripper_y_m [m, world y], so the pad of
    a gripper open opening_m [m] sits opening_m / 2 from it, the left one on +y."""
    sign = 1.0 if finger == "left" else -1.0
    return FaceTouch(finger, gripper_y_m + sign * opening_m / 2.0)


def touched_faces(contact: tuple, gripper_y_m: float, opening_m: float) -> tuple:
    """The FaceTouch of each finger in contact ((left, right) booleans) [m, world y]."""
    return tuple(touched_face(finger, gripper_y_m, opening_m)
                 for finger, touching in zip(("left", "right"), contact) if touching)


def remembered_faces(kept: tuple, touched: tuple) -> tuple:
    """The faces to remember when a Re-Reach begins from a close: the ones touched now
    replace those of the same finger (the object may have moved since); none touched (the
    gripper closed on nothing: the object is not where they were) forgets them all."""
    if not touched:
        return ()
    fingers = {face.finger for face in touched}
    return tuple(face for face in kept if face.finger not in fingers) + tuple(touched)


def opposite_face(faces: tuple, finger: str) -> FaceTouch | None:
    """The remembered face of the finger other than `finger`, or None."""
    return next((face for face in faces if face.finger != finger), None)


def bracketed_object(previous: FaceTouch | None, current: FaceTouch,
                     object_width_m: float) -> tuple[float, float] | None:
    """Where the object lies along the stroke once both fingers have touched it in turn:
    (centre [m, world y], extent [m]); None unless previous (the other finger's face
    remembered from an earlier close, remembered_faces) and current (the finger touching
    alone now) are different fingers.

    Why (the one-sided ping-pong, where the fingers take turns): the paper's shift,
    (opening - width) / 2 toward the touching finger, puts the gripper on the object only
    when the object's extent along the stroke is its nominal width. A box yawed by a
    pushing pad is wider: w (cos yaw + |sin yaw|), 62 mm for the 45 mm box at 32 deg
    (measured: a box 15 mm beyond and 25 mm along the stroke, yawed from 0.7 to 32 deg by
    the approach's push);
    the shift then overshoots by (62 - 45) / 2 = 8.5 mm, the other finger touches alone
    next, and four Re-Reaches alternate (+-18, +6.3, -9.1 mm) to Failed. Two faces touched
    from opposite sides bound the object whatever its yaw or width: it lies between them,
    its centre is their midpoint (that trial: right face -60.5 mm, left face -9.1 mm from
    the expected position, midpoint -34.8 mm; the box's measured centre -34.8 mm).
    The current touch is the fresh one (the previous may be stale by the current push, a
    few mm in 0.1 s of one-sided contact): the centre is read from it, half the extent
    away, with the extent never below object_width_m (faces read less than the object's
    width apart are inconsistent: the object moved between the touches; then this is the
    paper's shift)."""
    if previous is None or previous.finger == current.finger:
        return None
    left, right = (current, previous) if current.finger == "left" else (previous, current)
    extent = max(left.face_y_m - right.face_y_m, object_width_m)
    toward_previous = -1.0 if current.finger == "left" else 1.0
    return current.face_y_m + toward_previous * extent / 2.0, extent


def pushed_distance_m(first_touch_opening_m: float, object_width_m: float) -> float:
    """How far [m, along the stroke] the first pad to touch pushed the object across the
    table before the other pad met it: the fingers close symmetrically, so the first one
    travels half of what the opening closes from its first touch to the object's width
    (the paper's Re-Reach shift, read at the first touch). 0 when no pad has touched
    (first_touch_opening_m < 0) or the first touch came at the object's width."""
    if first_touch_opening_m < 0.0:
        return 0.0
    return max(first_touch_opening_m - object_width_m, 0.0) / 2.0


def release_topples(pushed_m: float, *, grasp_height_m: float, object_width_m: float,
                    object_height_m: float) -> bool:
    """Whether opening the gripper would let a pushed object fall over.

    A pad pushing an upright object pushed_m [m] along the stroke at the grasp height
    grasp_height_m [m] tips it about its base edge by up to atan(pushed / grasp_height)
    (the worst case: the base sticks on the table instead of sliding); the pads hold it
    there. Released, it stands up again only while its centre of mass, half its height
    up, stays over its base, i.e. tilt < atan(width / height) (width along the stroke,
    height object_height_m). So it topples when pushed_m * object_height_m >
    grasp_height_m * object_width_m. Measured on the faithful world's sweep: a thin
    cylinder (25 mm x 120 mm, limit 11.8 deg, 11.5 mm of push at 55 mm) misplaced 15 mm
    along the stroke was held 13-16 deg tilted at the Reach-Load event, and fell or leaned
    onto a finger when the gripper opened."""
    return pushed_m * object_height_m > grasp_height_m * object_width_m


def touched_beyond_pads(*, first_touch_offset_m: float, one_pad: bool, pushed_m: float,
                        grasp_height_m: float, object_width_m: float, object_height_m: float,
                        taxel_config) -> bool:
    """Whether the close must stop at its first touch: one pad alone touched, on its
    distal row alone (first_touch_offset_m [m, approach axis, pad +y toward the
    fingertips] at least beyond_pads_centroid_m), and closing on would push the object
    pushed_m [m] (pushed_distance_m), past its tipping limit (release_topples).

    Why (measured on the thin cylinder, 25 mm x 120 mm, 1.5 cm beyond the nominal grasp
    and 2.5 cm along the stroke): its axis
    stands about 2 mm beyond the pads' distal edge, so the near pad meets it with that
    edge (its distal row alone, 0.15 N, at an opening of 72 mm: 23.5 mm of push to come
    against a tipping limit of 11.5 mm at the 55 mm grasp height). The edge touches the
    rod off its axis and pushes it outward as well as across; tipping it needs
    m g (W / 2) / h = 0.06 kg x 9.81 m/s^2 x 12.5 mm / 55 mm = 0.13 N at the grasp
    height, less than the mu m g = 0.374 x 0.59 N = 0.22 N that slides it, so it tips from the
    first touch on (its pose moves from that tick), leaves the pad's edge and falls past
    the fingertips; the four Re-Reaches that follow close on nothing. Stopping at the
    first touch costs one taxel sample (9.3 ms) and one tick (5 ms), plus the gripper's
    reversal: at the 50 mm/s close a finger moves 25 mm/s, about 0.4 mm in those 14 ms,
    1 mm at most with the reversal, a tilt of atan(1/55) = 1 deg against the 11.8 deg
    the rod stands up from (measured on both markers of both seeds: the opening closed 1.1-1.5 mm
    more after the first touch, 0.55-0.75 mm of push; the rod tilted 1.0 deg at most
    and stood again). A contact with some force on the third row lies on the pad's
    face. The box and the thick cylinder never meet the rule: their tipping limits
    (22.5 mm, 25 mm of push) exceed what the 85 mm stroke can push them
    ((85 - 45) / 2 = 20 mm, 17.5 mm). The rows cannot tell the edge from the distal
    row's face: the rod 1 cm beyond and 1.5 cm along the stroke (axis 8-11 mm ahead,
    15 mm of push to come) stops and centres too, where the paper's rule loaded it
    pushed over (release_topples)."""
    return (one_pad and first_touch_offset_m >= taxel_config.beyond_pads_centroid_m
            and release_topples(pushed_m, grasp_height_m=grasp_height_m,
                                object_width_m=object_width_m,
                                object_height_m=object_height_m))


def beyond_pads_shift(*, finger: str, first_touch_opening_m: float, object_width_m: float,
                      taxel_config) -> Shift:
    """The Re-Reach after touched_beyond_pads [m, world]: forward along the approach axis
    by the pad's half length (12 mm: the pads' centres onto their distal edge; the
    contact on the distal row alone puts the object's axis from that row's inner
    boundary, 6 mm, to some mm beyond the edge, and the measured edge touches had it about
    2 mm beyond: 14 mm ahead, left 2 mm off the centres, within centre_tolerance_m,
    while a rod on the distal row's face, 8-11 mm ahead, is left 1-4 mm behind them;
    max_approach_shift_m, 15 mm, would leave that one 4-7 mm behind, for a second
    Re-Reach), at most max_approach_shift_m; and along the stroke toward the touching
    finger (`finger`, "left" on +y) by the push the close would have made,
    pushed_distance_m at the first touch: the object has barely moved, so that centres
    it."""
    dy = pushed_distance_m(first_touch_opening_m, object_width_m)
    dx = min(PAD_LENGTH / 2, taxel_config.max_approach_shift_m)
    return Shift(dx, dy if finger == "left" else -dy)


def caged_behind_pads(*, first_touch_offset_m: float, opening_m: float,
                      object_width_m: float, pads_touch: bool, closed_to_request: bool,
                      taxel_config) -> bool:
    """Whether the closed fingers hold the object between them and the palm, off the pads.

    The first pad to touch in this close read the contact on its palm side
    (first_touch_offset_m [m, approach axis, pad +y toward the fingertips] below
    -centre_tolerance_m; 0 when no pad touched); the fingers then stopped short of the
    close request (not closed_to_request, gOBJ 3: something between them stops them; read
    at the Reach and Load timeouts, 2 s, by which the 85 mm close at the default speed,
    about 1.5 s, has ended) at an opening narrower than the object (opening_m <
    object_width_m) with neither pad touching it. The pads have closed past the object on
    its fingertip side, so it stands behind them, between the fingers' inner links and the
    palm, and stops the fingers there: it cannot leave through the fingertips' gap
    (narrower than it) and the fingers bound it along the stroke. Lifting carries it (the
    open loop's grasp of a thin cylinder 15 mm toward the palm and 25 mm along the stroke;
    the simulated 2F-85 there reported gOBJ 0, moving, not 2, with its fingers stopped at
    16.9 mm for 0.5 s of a fully closed request, so no stall byte is required). A Re-Reach
    here learns nothing: no taxel sees the object, so its shift is zero and it closes the
    same way again (the 4 identical Re-Reaches that ended in Failed)."""
    return (not closed_to_request and not pads_touch and opening_m < object_width_m
            and first_touch_offset_m < -taxel_config.centre_tolerance_m)


def held_tilted(contact: GraspContact, taxel_config) -> bool:
    """The object sits tilted in the grasp: a pad's contact line turned more than
    tilt_limit_deg, or the two pads' contacts more than height_mismatch_m apart in
    height."""
    tilted_line = contact.tilt_deg is not None and abs(contact.tilt_deg) > \
        taxel_config.tilt_limit_deg
    return tilted_line or abs(contact.height_mismatch_m) > taxel_config.height_mismatch_m

