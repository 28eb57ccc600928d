"""The taxel-aware controller's contact geometry (taxel_aware/contact_geometry.py), as
pure functions: the approach shift, the push and whether it topples the object, a touch
beyond the pads, a cage behind them, the faces the fingers touched and the bracket."""

import dataclasses

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import GraspControllerConfig, TaxelAwareConfig
from tegrasp_drake.control.taxel_aware.contact_geometry import (
    FaceTouch, Shift, approach_shift, beyond_pads_shift, bracketed_object, caged_behind_pads,
    curled_touch, held_tilted, opposite_face, pushed_distance_m, release_topples, remembered_faces,
    touched_beyond_pads, touched_face, touched_faces, untouched_reach_m)
from tegrasp_drake.control.taxel_contact import grasp_contact
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS
from tegrasp_drake.rig.taxel_layout import CELL_Y, COLUMNS, ROWS
from tegrasp_drake.robotiq.units import STROKE_M

TAXEL = TaxelAwareConfig()
CONTACT_N = GraspControllerConfig().taxel_contact_n  # the ideal force taxels' number


def line_on_row(row, force=1.0):
    taxels = np.zeros((ROWS, COLUMNS))
    taxels[row, :] = force
    return taxels.reshape(-1)


def both(row_left, row_right=None):
    return grasp_contact(np.concatenate([line_on_row(row_left),
                                         line_on_row(row_left if row_right is None
                                                     else row_right)]), CONTACT_N)


def test_a_contact_on_the_fingertip_row_moves_the_gripper_forward_by_its_offset():
    shift = approach_shift(both(3), TAXEL)
    assert shift == pytest.approx(1.5 * CELL_Y)
    assert approach_shift(both(0), TAXEL) == pytest.approx(-1.5 * CELL_Y)


def test_a_centred_contact_or_none_needs_no_approach_shift():
    assert approach_shift(both(1, 2), TAXEL) == 0.0  # between the middle rows
    assert approach_shift(grasp_contact(np.zeros(24), CONTACT_N), TAXEL) == 0.0


def test_the_linkage_pads_travel_still_to_come_is_taken_off_the_approach_shift():
    # A fingertip-row contact (9 mm out) read while the linkage's pads have 5 mm still to
    # travel along the approach axis before they close on the object: move 4 mm, not 9.
    assert approach_shift(both(3), TAXEL, 0.005) == pytest.approx(1.5 * CELL_Y - 0.005)
    # Travel that brings the pads onto the contact needs no shift at all.
    assert approach_shift(both(3), TAXEL, 1.5 * CELL_Y) == 0.0


def test_the_approach_shift_is_clipped_to_its_limit():
    tight = dataclasses.replace(TAXEL, max_approach_shift_m=0.005)
    assert approach_shift(both(3), tight) == pytest.approx(0.005)


def test_the_push_is_half_the_opening_closed_from_the_first_touch_to_the_width():
    # The faithful sweep's thin cylinder 15 mm along the stroke: first touch 55.4 mm open.
    assert pushed_distance_m(0.0554, 0.025) == pytest.approx(0.0152)
    assert pushed_distance_m(0.0247, 0.025) == 0.0  # first touch at the width: no push
    assert pushed_distance_m(-1.0, 0.025) == 0.0  # no touch yet


def _topples(object_name, pushed_m, grasp_height_m=0.055):
    o = BUILTIN_OBJECTS[object_name]
    return release_topples(pushed_m, grasp_height_m=grasp_height_m,
                           object_width_m=o.width_along_stroke(), object_height_m=o.height())


def test_a_pushed_object_topples_when_let_go_past_its_standing_tilt():
    """Tipped by atan(push / grasp height); stands while under atan(width / height)."""
    thin = BUILTIN_OBJECTS["thin_cylinder"]
    limit_m = 0.055 * thin.width_along_stroke() / thin.height()  # 11.5 mm
    assert _topples("thin_cylinder", 0.015)  # the paper's grid: 15 mm along the stroke
    assert not _topples("thin_cylinder", 0.9 * limit_m)
    assert _topples("thin_cylinder", 1.1 * limit_m)
    assert not _topples("thin_cylinder", 0.0015)  # a centred rod: the pads meet it together
    # The box (45 mm x 110 mm) and thick cylinder (50 mm x 110 mm) stand after 15-17 mm.
    assert not _topples("box", 0.017) and not _topples("thick_cylinder", 0.017)
    assert _topples("box", 0.025)  # the second grid's 2.5 cm, where the box does not


def _caged(**changes):
    # The thin cylinder (25 mm) misplaced 15 mm toward the palm: first
    # touched on the palm-side edge row (-9 mm), the fingers stopped at 16.9 mm, no pad on it.
    args = dict(first_touch_offset_m=-0.009, opening_m=0.0169, object_width_m=0.025,
                pads_touch=False, closed_to_request=False, taxel_config=TAXEL)
    return caged_behind_pads(**{**args, **changes})


def test_fingers_closed_past_an_object_first_touched_on_the_palm_side_cage_it():
    assert _caged()
    assert not _caged(pads_touch=True)  # on the pads: the paper's rules
    assert not _caged(opening_m=0.026)  # the fingers stopped on the object's width
    assert not _caged(closed_to_request=True)  # closed on nothing (fell over, slid away)
    assert not _caged(first_touch_offset_m=0.009)  # fingertip side: pushed out beyond them
    assert not _caged(first_touch_offset_m=0.0)  # no pad ever touched it


def test_a_first_touch_narrower_than_the_object_less_both_pads_elastomer_is_a_curl():
    width = 0.025
    flat_limit = width - 2 * PAD_THICKNESS  # both pads pressed through their 4 mm
    assert curled_touch(0.0045, width)
    assert curled_touch(flat_limit - 1e-4, width)
    assert not curled_touch(flat_limit + 1e-4, width)
    assert not curled_touch(0.0217, width)  # the distal rows meeting it beyond the pads
    assert not curled_touch(-1.0, width)  # no touch


def test_a_diagonal_contact_line_is_a_tilted_hold():
    diagonal = np.zeros((ROWS, COLUMNS))
    diagonal[[0, 1, 2], [0, 1, 2]] = 1.0
    tilted = grasp_contact(np.concatenate([diagonal.reshape(-1), diagonal.reshape(-1)]),
                           CONTACT_N)
    assert held_tilted(tilted, TAXEL)
    assert not held_tilted(both(1), TAXEL)


def test_the_taxel_aware_settings_are_reasoned_in_pad_units():
    assert TaxelAwareConfig().centre_tolerance_m < CELL_Y  # within a row
    assert TaxelAwareConfig().max_approach_shift_m > 2 * CELL_Y


def _beyond(first_touch_offset_m=grasp_contact(
        np.concatenate([np.zeros(12), line_on_row(3, 0.1)]), CONTACT_N).approach_offset_m,
        one_pad=True, first_touch_opening_m=0.0719):
    # The thin cylinder 1.5 cm beyond the nominal grasp and 2.5 cm
    # along the stroke; the right pad's distal row alone touched at 71.9 mm.
    thin = BUILTIN_OBJECTS["thin_cylinder"]
    return touched_beyond_pads(
        first_touch_offset_m=first_touch_offset_m, one_pad=one_pad,
        pushed_m=pushed_distance_m(first_touch_opening_m, thin.width_along_stroke()),
        grasp_height_m=0.055, object_width_m=thin.width_along_stroke(),
        object_height_m=thin.height(), taxel_config=TAXEL)


def test_a_first_touch_on_one_pads_distal_row_that_would_push_the_object_over_stops_it():
    assert _beyond()
    # Force above the taxel threshold on the third row too: the object lies on the face.
    face = grasp_contact(np.concatenate([np.zeros(12), line_on_row(3, 0.15)
                                         + line_on_row(2, 0.06)]), CONTACT_N)
    assert not _beyond(first_touch_offset_m=face.approach_offset_m)
    assert not _beyond(one_pad=False)  # both pads at once: centred along the stroke
    # A push within the tipping limit (11.5 mm): the paper's rule grasps it.
    assert not _beyond(first_touch_opening_m=0.025 + 2 * 0.010)


def test_the_stop_beyond_the_pads_moves_forward_and_toward_the_touching_pad():
    shift = beyond_pads_shift(finger="right", first_touch_opening_m=0.0719,
                              object_width_m=0.025, taxel_config=TAXEL)
    # Forward by the pad's half length (its centre onto its distal edge: 2 rows).
    assert shift == Shift(pytest.approx(2 * CELL_Y), pytest.approx(-0.02345))
    left = beyond_pads_shift(finger="left", first_touch_opening_m=0.0719,
                             object_width_m=0.025, taxel_config=TAXEL)
    assert left.dy_m == pytest.approx(0.02345) and left.dx_m > 0.0


def test_a_finger_touching_alone_presses_the_face_half_the_opening_to_its_side():
    assert touched_face("left", 0.10, 0.060) == FaceTouch("left", pytest.approx(0.13))
    assert touched_face("right", 0.10, 0.060) == FaceTouch("right", pytest.approx(0.07))


def test_faces_touched_from_both_sides_in_turn_put_the_object_at_their_midpoint():
    """Box m20 of the second grid with seed 700, yawed to 32 deg by the approach's push: the
    right finger alone at 80.9 mm open with the gripper 20 mm off (y in mm from the
    expected position), then the left alone at 57.7 mm open 37.9 mm off. The paper's
    shift, (57.7 - 45) / 2 = +6.3 mm, overshot the box (measured at -34.8 mm) and the
    right finger touched alone next."""
    right = touched_face("right", -0.020, 0.0809)
    left = touched_face("left", -0.0379, 0.0577)
    centre, extent = bracketed_object(right, left, 0.045)
    assert centre == pytest.approx(-0.0348, abs=2e-4)
    assert extent == pytest.approx(0.0514, abs=2e-4)
    shift = centre - (-0.0379)
    assert 0.0 < shift < (0.0577 - 0.045) / 2  # toward the left finger, short of the paper's
    # Faces farther apart than the width: the midpoint, whichever finger touched last.
    assert bracketed_object(left, right, 0.045) == pytest.approx((centre, extent))


def test_the_latest_face_of_each_finger_is_remembered_until_a_close_touches_nothing():
    """Box m20 with seed 600: the right finger alone, then both pads (a Re-Reach along
    the approach axis after the Reach-Load event), then the left alone: the right face of
    the two-pad close is the one to bracket the left touch with."""
    right_alone = touched_faces((False, True), 0.0, 0.080)
    assert right_alone == (FaceTouch("right", pytest.approx(-0.040)),)
    both_pads = touched_faces((True, True), -0.018, 0.050)
    faces = remembered_faces(remembered_faces((), right_alone), both_pads)
    assert sorted(face.finger for face in faces) == ["left", "right"]
    assert opposite_face(faces, "left").face_y_m == pytest.approx(-0.043)
    assert opposite_face(faces, "right").face_y_m == pytest.approx(0.007)
    assert remembered_faces(faces, ()) == ()  # closed on nothing
    assert opposite_face((), "left") is None


def test_the_same_finger_twice_or_no_earlier_touch_brackets_nothing():
    left = FaceTouch("left", 0.01)
    assert bracketed_object(None, left, 0.045) is None
    assert bracketed_object(FaceTouch("left", 0.02), left, 0.045) is None


def test_faces_read_closer_than_the_objects_width_fall_back_to_the_papers_shift():
    """The object moved between the touches: the fresh face and the nominal width say where
    it is (the paper's shift)."""
    right = FaceTouch("right", 0.0)
    left = FaceTouch("left", 0.030)  # 30 mm apart, the box is 45 mm wide
    centre, extent = bracketed_object(right, left, 0.045)
    assert extent == pytest.approx(0.045)
    assert centre == pytest.approx(0.030 - 0.0225)



def test_an_untouched_object_lies_past_the_pads_distal_reach_plus_its_half_depth():
    """A hand whose pads do not move along the approach (the prismatic hand): their distal
    edge, half a pad beyond their centres, plus the object's half depth."""
    reach = untouched_reach_m(lambda opening_m: 0.0, 0.025, STROKE_M)
    assert reach == pytest.approx(PAD_LENGTH / 2 + 0.0125)


def test_the_linkage_pads_farthest_travel_over_the_close_adds_to_the_untouched_reach():
    """On the 2F-85 the pads' centres travel on past the object's width as the close goes on
    (farthest near a 10 mm opening): an untouched object lies beyond that farthest point."""
    from tegrasp_drake.simulation.gripper_hands import LinkageHand
    offset = LinkageHand().pad_center_offset
    reach = untouched_reach_m(offset, 0.025, STROKE_M)
    past_the_width = offset(0.010) - offset(0.025)
    assert past_the_width > 0.0
    assert reach >= PAD_LENGTH / 2 + 0.0125 + past_the_width
    assert reach < PAD_LENGTH / 2 + 0.0125 + past_the_width + 0.001
