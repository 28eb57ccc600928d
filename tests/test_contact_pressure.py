import numpy as np
import pytest

from tegrasp_drake.systems.contact_pressure import (polygon_fan_triangles, subdivision_weights,
                                                    taxel_normal_forces)
from tegrasp_drake.systems.taxel_layout import PAD_LENGTH, PAD_WIDTH, taxel_centers

W, L = PAD_WIDTH / 2, PAD_LENGTH / 2
PAD_SQUARE = np.array([[-W, -L, 0.0], [W, -L, 0.0], [W, L, 0.0], [-W, L, 0.0]])


def test_fan_triangulation_of_mixed_polygons():
    triangles = polygon_fan_triangles([4, 0, 1, 2, 3, 3, 4, 5, 6])
    np.testing.assert_array_equal(triangles, [[0, 1, 2], [0, 2, 3], [4, 5, 6]])


@pytest.mark.parametrize("n", [1, 2, 5])
def test_subdivision_weights_tile_the_triangle(n):
    weights = subdivision_weights(n)
    assert weights.shape == (n * n, 3)
    np.testing.assert_allclose(weights.sum(axis=1), 1.0)
    np.testing.assert_allclose(weights.mean(axis=0), 1.0 / 3.0)


def test_uniform_pressure_over_two_large_faces_gives_an_even_pattern():
    forces = taxel_normal_forces(PAD_SQUARE, np.full(4, 1e4), polygon_fan_triangles(
        [4, 0, 1, 2, 3]), subdivision_weights(6))
    np.testing.assert_allclose(forces, forces.mean(), rtol=1e-9)
    assert forces.sum() == pytest.approx(1e4 * PAD_WIDTH * PAD_LENGTH)


def test_coarse_faces_without_subdivision_give_a_wrong_pattern():
    # The reason subdivision exists: one piece per triangle puts all force in two taxels.
    forces = taxel_normal_forces(PAD_SQUARE, np.full(4, 1e4), polygon_fan_triangles(
        [4, 0, 1, 2, 3]), subdivision_weights(1))
    assert np.count_nonzero(forces) == 2


def test_off_centre_press_shifts_the_pattern_toward_the_fingertip():
    # Pressure rising linearly along +y (toward the fingertip).
    pressure = 1e4 * (1.0 + PAD_SQUARE[:, 1] / L)
    forces = taxel_normal_forces(PAD_SQUARE, pressure, polygon_fan_triangles([4, 0, 1, 2, 3]),
                                 subdivision_weights(6))
    centroid = forces @ taxel_centers() / forces.sum()
    assert centroid[1] > 0.25 * L
    assert abs(centroid[0]) < 1e-9


def test_tilted_face_counts_only_its_normal_component():
    tilted = PAD_SQUARE.copy()
    tilted[:, 2] = tilted[:, 0]  # 45 degrees about y
    forces = taxel_normal_forces(tilted, np.full(4, 1e4), polygon_fan_triangles([4, 0, 1, 2, 3]),
                                 subdivision_weights(4))
    # Area grows by sqrt(2), the normal component shrinks by 1/sqrt(2).
    assert forces.sum() == pytest.approx(1e4 * PAD_WIDTH * PAD_LENGTH)
