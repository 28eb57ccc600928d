"""The taxel-aware rules' geometry as pure functions: where a Re-Reach moves, the faces the
fingers touched, the push of a close and whether it topples the object, a touch beyond the
pads, a cage behind them, a tilted hold; called each tick by the ContactEstimator
(estimator.py). Frames: world W, approach along +x, stroke along y, left finger on +y.
Why each rule: docs/controller.md, "The taxel-aware controller"."""

import dataclasses

import numpy as np

from tegrasp_drake.control.taxel_contact import GraspContact
from tegrasp_drake.rig.tactile_fingertip import PAD_THICKNESS
from tegrasp_drake.rig.taxel_layout import PAD_LENGTH


@dataclasses.dataclass(frozen=True)
class Shift:
    """A Re-Reach move of the open gripper [m, world]: dx along the approach, dy the stroke; a
    negative dx during the Reach's move backs off that far along the Reach's path."""
    dx_m: float
    dy_m: float


def approach_shift(contact: GraspContact, taxel_config,
                   pad_travel_to_grasp_m: float = 0.0) -> float:
    """The shift along world x [m] that puts the pads' centres on the contact once closed:
    its approach_offset_m less the pads' travel still to come (pad_travel_to_grasp_m),
    clipped to max_approach_shift_m; 0 without contact or within centre_tolerance_m."""
    touching = contact.left.touching or contact.right.touching
    offset = contact.approach_offset_m - pad_travel_to_grasp_m
    if not touching or abs(offset) <= taxel_config.centre_tolerance_m:
        return 0.0
    return float(np.clip(offset, -taxel_config.max_approach_shift_m,
                         taxel_config.max_approach_shift_m))


@dataclasses.dataclass(frozen=True)
class FaceTouch:
    """A finger ("left", on +y, or "right") that touched alone, at face_y_m [m, world y]."""
    finger: str
    face_y_m: float


def touched_face(finger: str, gripper_y_m: float, opening_m: float) -> FaceTouch:
    """The face a finger touching alone presses [m, world y]: opening_m / 2 from gripper_y_m."""
    sign = 1.0 if finger == "left" else -1.0
    return FaceTouch(finger, gripper_y_m + sign * opening_m / 2.0)


def touched_faces(contact: tuple, gripper_y_m: float, opening_m: float) -> tuple:
    """The FaceTouch of each finger in contact ((left, right) booleans) [m, world y]."""
    return tuple(touched_face(finger, gripper_y_m, opening_m)
                 for finger, touching in zip(("left", "right"), contact) if touching)


def remembered_faces(kept: tuple, touched: tuple) -> tuple:
    """The faces kept at a Re-Reach: `touched` replaces the same finger's; none forgets all."""
    if not touched:
        return ()
    fingers = {face.finger for face in touched}
    return tuple(face for face in kept if face.finger not in fingers) + tuple(touched)


def opposite_face(faces: tuple, finger: str) -> FaceTouch | None:
    """The remembered face of the finger other than `finger`, or None."""
    return next((face for face in faces if face.finger != finger), None)


def bracketed_object(previous: FaceTouch | None, current: FaceTouch,
                     object_width_m: float) -> tuple[float, float] | None:
    """(centre [m, world y], extent [m]) of an object touched by both fingers in turn
    (`previous` remembered, `current` touching alone now); None unless different fingers. The
    centre lies half the extent from the fresh face, the extent at least object_width_m
    (docs/controller.md, "Fingers touching alone in turn bracket the object")."""
    if previous is None or previous.finger == current.finger:
        return None
    left, right = (current, previous) if current.finger == "left" else (previous, current)
    extent = max(left.face_y_m - right.face_y_m, object_width_m)
    toward_previous = -1.0 if current.finger == "left" else 1.0
    return current.face_y_m + toward_previous * extent / 2.0, extent


def pushed_distance_m(first_touch_opening_m: float, object_width_m: float) -> float:
    """How far [m, along the stroke] the first pad pushes the object before the other meets
    it: half the closing from the first touch to the object's width; 0 without a touch."""
    if first_touch_opening_m < 0.0:
        return 0.0
    return max(first_touch_opening_m - object_width_m, 0.0) / 2.0


def release_topples(pushed_m: float, *, grasp_height_m: float, object_width_m: float,
                    object_height_m: float) -> bool:
    """Whether opening would let an object pushed pushed_m [m] at grasp_height_m fall over:
    pushed_m * object_height_m > grasp_height_m * object_width_m (docs/controller.md, "Not after
    a push past the tipping limit")."""
    return pushed_m * object_height_m > grasp_height_m * object_width_m


@dataclasses.dataclass(frozen=True)
class OnePadPush:
    """The largest force [N] one pad alone presses an upright free-standing object with,
    quasi-statically, before it gives way: `tips_n` about its far bottom edge, `slides_n` on
    the table (docs/controller.md, "Which rules one finger can fire")."""
    tips_n: float
    slides_n: float

    @property
    def limit_n(self) -> float:
        return min(self.tips_n, self.slides_n)


def one_pad_push(*, weight_n: float, object_width_m: float, contact_height_m: float,
                 table_friction: float) -> OnePadPush:
    """OnePadPush of an object of weight_n [N] and object_width_m [m, along the push] pushed
    sideways at contact_height_m [m above the table]: tipping balances the push's moment
    about the far bottom edge against the weight's, F h = W w/2; sliding at the table pair's
    Coulomb coefficient table_friction, F = mu W. Quasi-static: an impact's transient is not
    bounded by it, and the pad's own friction on the object is left out."""
    return OnePadPush(tips_n=weight_n * (object_width_m / 2.0) / contact_height_m,
                      slides_n=table_friction * weight_n)


def touched_beyond_pads(*, first_touch_offset_m: float, one_pad: bool, pushed_m: float,
                        grasp_height_m: float, object_width_m: float, object_height_m: float,
                        taxel_config) -> bool:
    """Whether the close must stop at its first touch: one pad alone touched, on its distal
    row alone (first_touch_offset_m [m, toward the fingertips] >= beyond_pads_centroid_m), and
    closing on would topple the object (release_topples). docs/controller.md, "A first touch
    beyond the pads stops the close"."""
    return (one_pad and first_touch_offset_m >= taxel_config.beyond_pads_centroid_m
            and release_topples(pushed_m, grasp_height_m=grasp_height_m,
                                object_width_m=object_width_m,
                                object_height_m=object_height_m))


def beyond_pads_shift(*, finger: str, first_touch_opening_m: float, object_width_m: float,
                      taxel_config) -> Shift:
    """The Re-Reach after touched_beyond_pads [m, world]: forward by half the pad's length (at most
    max_approach_shift_m), sideways toward `finger` by the push the close would have made."""
    dy = pushed_distance_m(first_touch_opening_m, object_width_m)
    dx = min(PAD_LENGTH / 2, taxel_config.max_approach_shift_m)
    return Shift(dx, dy if finger == "left" else -dy)


def untouched_reach_m(pad_center_offset, object_width_m: float, stroke_m: float) -> float:
    """How far beyond the pads' centres at the object's width [m, along the approach] the
    nearest centre lies of an object no pad touched in a whole close (nothing after it on the
    taxels): the pads' distal edges (PAD_LENGTH / 2 beyond their centres) reach at most the
    centres' farthest point over the close, pad_center_offset(opening) [m] at the openings
    0..stroke_m 1 mm apart (the 2F-85's farthest, 4.43 mm near a 10.7 mm opening, within
    0.001 mm of a 0.01 mm grid's); the untouched object's near face lies past that, its
    centre half its depth further, taken as object_width_m (the built-in objects are round or
    square in plan). docs/controller.md, "A close that touched nothing searches beyond the
    fingertips"."""
    openings = np.linspace(0.0, stroke_m, int(round(stroke_m / 0.001)) + 1)
    farthest = max(pad_center_offset(float(o)) for o in openings)
    return PAD_LENGTH / 2 + farthest - pad_center_offset(object_width_m) + object_width_m / 2


def curled_touch(first_touch_opening_m: float, object_width_m: float) -> bool:
    """Whether the close's first touch came at an opening [m] no pad lying flat on an object
    object_width_m [m] across reaches: below that width less both pads' elastomer
    (2 PAD_THICKNESS, each pressed through its whole depth). Narrower, the fingers are off
    their pins: they curled past the object and their fingertips touch its far side, so the
    taxel rows are not positions along the approach (docs/controller.md, "Curled fingertips
    hook the object's far side"). False without a touch."""
    return 0.0 <= first_touch_opening_m < object_width_m - 2.0 * PAD_THICKNESS


def caged_behind_pads(*, first_touch_offset_m: float, opening_m: float,
                      object_width_m: float, pads_touch: bool, closed_to_request: bool,
                      taxel_config) -> bool:
    """Whether the closed fingers hold the object against the palm, off the pads: a first touch
    on the palm side (below -centre_tolerance_m [m]) and fingers stopped short of the request,
    narrower than the object, neither pad touching (docs/controller.md, "Caged behind the pads")."""
    return (not closed_to_request and not pads_touch and opening_m < object_width_m
            and first_touch_offset_m < -taxel_config.centre_tolerance_m)


def held_tilted(contact: GraspContact, taxel_config) -> bool:
    """A contact line turned past regrasp.tilt_limit_deg, or contacts regrasp.height_mismatch_m
    apart."""
    regrasp = taxel_config.regrasp
    tilted_line = contact.tilt_deg is not None and abs(contact.tilt_deg) > regrasp.tilt_limit_deg
    return tilted_line or abs(contact.height_mismatch_m) > regrasp.height_mismatch_m

