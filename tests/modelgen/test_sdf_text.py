"""The SDF text helpers' mass properties (modelgen/sdf_text.py) against closed forms."""

import numpy as np
import pytest

from tegrasp_drake.modelgen.sdf_text import box_inertia, number_text, tube_inertia


def test_box_inertia_is_the_uniform_solids():
    np.testing.assert_allclose(box_inertia(1.2, (0.1, 0.2, 0.3)),
                               np.diag([0.1 * (0.04 + 0.09), 0.1 * (0.01 + 0.09),
                                        0.1 * (0.01 + 0.04)]), rtol=1e-15)


def _straight_tube(mass: float):
    """(com, inertia) of a 0.4 m tube along x, 0.1 m off the axis along y, radius 3 cm."""
    return tube_inertia(mass, np.array([[0.0, 0.1, 0.0], [0.4, 0.1, 0.0]]), 0.03)


def test_a_straight_tube_of_unit_mass_has_its_centre_midway_and_a_rods_inertia():
    com, inertia = _straight_tube(1.0)
    np.testing.assert_allclose(com, [0.2, 0.1, 0.0], rtol=0, atol=1e-15)
    # About its axis: a solid rod's m r^2 / 2.
    assert inertia[0, 0] == pytest.approx(0.03 ** 2 / 2, rel=1e-12)
    # Across it: m L^2 / 12 from the mass spread along the axis (20 midpoints per segment
    # give (1 - 1/20^2) of it), plus the rod's cross-section term, which the helper takes
    # as m r^2 / 2 on every axis (a solid rod's is m r^2 / 4: an upper bound).
    across = 0.4 ** 2 / 12 * (1 - 1 / 400) + 0.03 ** 2 / 2
    np.testing.assert_allclose([inertia[1, 1], inertia[2, 2]], [across, across], rtol=1e-12)
    np.testing.assert_allclose(inertia - np.diag(np.diag(inertia)), 0.0, atol=1e-15)


def test_a_straight_tubes_centre_and_inertia_do_not_depend_on_its_mass():
    com, inertia = _straight_tube(0.8)
    com_unit, inertia_unit = _straight_tube(1.0)
    np.testing.assert_allclose(com, com_unit, rtol=0, atol=1e-15)
    np.testing.assert_allclose(inertia, 0.8 * inertia_unit, rtol=1e-12, atol=1e-18)


def test_a_bent_tube_puts_its_centre_where_its_length_is():
    # Segments of 0.3 m along x and 0.1 m along y: centre at the length-weighted mean of
    # their midpoints, (0.75 (0.15, 0) + 0.25 (0.3, 0.05)).
    com, inertia = tube_inertia(1.0, np.array([[0.0, 0.0, 0.0], [0.3, 0.0, 0.0],
                                               [0.3, 0.1, 0.0]]), 0.01)
    np.testing.assert_allclose(com, [0.1875, 0.0125, 0.0], rtol=0, atol=1e-15)
    np.testing.assert_allclose(inertia, inertia.T, rtol=0, atol=1e-18)
    assert np.all(np.linalg.eigvalsh(inertia) > 0)


def test_number_text_writes_nine_digits_and_round_off_as_zero():
    assert number_text(1 / 3) == "0.333333333"
    assert number_text(-2.5e-13) == "0"
    assert float(number_text(123456.7891234)) == pytest.approx(123456.789, abs=1e-3)
