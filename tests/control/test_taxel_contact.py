"""The contact's place and tilt on the pads from the 3 x 4 taxel pattern."""

import math

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.control.taxel_contact import (contact_line_tilt_deg, grasp_contact,
                                                 pad_contact)
from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y, COLUMNS, ROWS

CONTACT_N = GraspControllerConfig().taxel_contact_n  # the ideal force taxels' number


def pad(rows_by_column=None, force=1.0, every=None):
    """A pad's 12 forces [N]: `force` on row rows_by_column[c] of each column c."""
    taxels = np.zeros((ROWS, COLUMNS))
    if every is not None:
        taxels[:] = every
    for column, row in enumerate(rows_by_column or ()):
        if row is not None:
            taxels[row, column] = force
    return taxels.reshape(-1)


def test_a_line_contact_on_the_fingertip_row_sits_one_and_a_half_rows_forward():
    contact = pad_contact(pad([3, 3, 3]), CONTACT_N)
    assert contact.force_n == pytest.approx(3.0)
    assert contact.y_m == pytest.approx(1.5 * CELL_Y)
    assert contact.x_m == pytest.approx(0.0, abs=1e-12)


def test_noise_below_the_contact_force_draws_no_contact():
    contact = pad_contact(np.full(12, 0.9 * CONTACT_N), CONTACT_N)
    assert not contact.touching and contact.y_m == 0.0


def test_an_upright_line_has_no_tilt_and_a_diagonal_one_has_its_angle():
    assert contact_line_tilt_deg(pad([1, 1, 1]), CONTACT_N) == pytest.approx(0.0, abs=1e-9)
    # One row per column: rises CELL_Y per CELL_X.
    assert contact_line_tilt_deg(pad([0, 1, 2]), CONTACT_N) == pytest.approx(
        math.degrees(math.atan(CELL_Y / CELL_X)))
    assert contact_line_tilt_deg(pad([2, 1, 0]), CONTACT_N) == pytest.approx(
        -math.degrees(math.atan(CELL_Y / CELL_X)))
    assert contact_line_tilt_deg(pad([None, 1, None]), CONTACT_N) is None  # one column: no line


def test_a_uniform_face_contact_is_centred_and_untilted():
    shape = grasp_contact(np.concatenate([pad(every=0.5), pad(every=0.5)]), CONTACT_N)
    assert shape.approach_offset_m == pytest.approx(0.0, abs=1e-12)
    assert shape.tilt_deg == pytest.approx(0.0, abs=1e-9)
    assert shape.height_mismatch_m == pytest.approx(0.0, abs=1e-12)


def test_contacts_at_different_heights_on_the_two_pads_show_a_mismatch():
    left = np.zeros((ROWS, COLUMNS))
    left[:, 0] = 1.0  # column 0 (pad x < 0, world up)
    right = np.zeros((ROWS, COLUMNS))
    right[:, 2] = 1.0
    shape = grasp_contact(np.concatenate([left.reshape(-1), right.reshape(-1)]), CONTACT_N)
    assert shape.height_mismatch_m == pytest.approx(-2 * CELL_X)


def test_the_approach_offset_weights_the_pads_by_force():
    shape = grasp_contact(np.concatenate([pad([3, 3, 3], force=3.0), pad([0, 0, 0])]),
                          CONTACT_N)
    # 9 N at +1.5 rows and 3 N at -1.5 rows: (9 - 3) / 12 * 1.5 rows.
    assert shape.approach_offset_m == pytest.approx(0.75 * CELL_Y)
