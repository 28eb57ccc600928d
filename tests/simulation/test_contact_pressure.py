import numpy as np
import pytest

from tegrasp_drake.simulation.contact_pressure import (corner_differences,
                                                    polygon_fan_triangles,
                                                    taxel_normal_forces)
from tegrasp_drake.rig.taxel_layout import (CELL_X, CELL_Y, PAD_LENGTH, PAD_WIDTH,
                                                taxel_centers)

W, L = PAD_WIDTH / 2, PAD_LENGTH / 2
PAD_SQUARE = np.array([[-W, -L, 0.0], [W, -L, 0.0], [W, L, 0.0], [-W, L, 0.0]])
TWO_TRIANGLES = polygon_fan_triangles([4, 0, 1, 2, 3])


def test_fan_triangulation_of_mixed_polygons():
    triangles = polygon_fan_triangles([4, 0, 1, 2, 3, 3, 4, 5, 6])
    np.testing.assert_array_equal(triangles, [[0, 1, 2], [0, 2, 3], [4, 5, 6]])


def test_uniform_pressure_over_two_large_faces_gives_an_even_pattern():
    forces = taxel_normal_forces(PAD_SQUARE, np.full(4, 1e4), TWO_TRIANGLES)
    np.testing.assert_allclose(forces, forces.mean(), rtol=1e-12)
    assert forces.sum() == pytest.approx(1e4 * PAD_WIDTH * PAD_LENGTH)


def test_faces_larger_than_a_taxel_are_split_exactly_at_the_cell_edges():
    # A linear pressure over two faces that each span all 12 taxels: each taxel's force is
    # the pressure at its centre times its area, exactly.
    def pressure(p):
        return 1e4 + 3e5 * p[:, 0] - 2e5 * p[:, 1]
    forces = taxel_normal_forces(PAD_SQUARE, pressure(PAD_SQUARE), TWO_TRIANGLES)
    np.testing.assert_allclose(forces, pressure(taxel_centers()) * CELL_X * CELL_Y, rtol=1e-12)


def test_a_slanted_triangle_with_a_pressure_ramp_keeps_its_total_and_orientation_free():
    corners = np.array([[-0.009, -0.017, 0.0], [0.010, -0.002, 0.0], [-0.004, 0.018, 0.0]])
    pressure = np.array([0.0, 2e4, 5e4])
    forces = taxel_normal_forces(corners, pressure, [[0, 1, 2]])
    area = 0.5 * abs(np.cross(corners[1] - corners[0], corners[2] - corners[0])[2])
    assert forces.sum() == pytest.approx(area * pressure.mean(), rel=1e-12)
    assert np.count_nonzero(forces) >= 8
    np.testing.assert_allclose(taxel_normal_forces(corners, pressure, [[0, 2, 1]]), forces,
                               rtol=1e-12, atol=1e-15)


def test_a_face_inside_one_taxel_loads_only_that_taxel():
    corners = np.array([[0.001, 0.001, 0.0], [0.003, 0.001, 0.0], [0.001, 0.004, 0.0]])
    forces = taxel_normal_forces(corners, np.array([1e4, 2e4, 3e4]), [[0, 1, 2]])
    assert np.count_nonzero(forces) == 1
    assert forces[7] == pytest.approx(0.5 * 0.002 * 0.003 * 2e4, rel=1e-12)  # row 2, column 1


def test_pressure_beyond_the_pad_edge_counts_to_the_edge_taxels():
    wide = PAD_SQUARE * [1.5, 1.5, 1.0]
    forces = taxel_normal_forces(wide, np.full(4, 1e4), TWO_TRIANGLES)
    assert forces.sum() == pytest.approx(1e4 * 1.5 * PAD_WIDTH * 1.5 * PAD_LENGTH)
    grid = forces.reshape(4, 3)
    assert grid[1, 1] == pytest.approx(1e4 * CELL_X * CELL_Y)
    assert grid[0, 0] == pytest.approx(1e4 * (CELL_X + W / 2) * (CELL_Y + L / 2))


def test_off_centre_press_shifts_the_pattern_toward_the_fingertip():
    # Pressure rising linearly along +y (toward the fingertip).
    pressure = 1e4 * (1.0 + PAD_SQUARE[:, 1] / L)
    forces = taxel_normal_forces(PAD_SQUARE, pressure, TWO_TRIANGLES)
    centroid = forces @ taxel_centers() / forces.sum()
    assert centroid[1] > 0.25 * L
    assert abs(centroid[0]) < 1e-9


def test_tilted_face_counts_only_its_normal_component():
    tilted = PAD_SQUARE.copy()
    tilted[:, 2] = tilted[:, 0]  # 45 degrees about y
    forces = taxel_normal_forces(tilted, np.full(4, 1e4), TWO_TRIANGLES)
    # Area grows by sqrt(2), the normal component shrinks by 1/sqrt(2).
    assert forces.sum() == pytest.approx(1e4 * PAD_WIDTH * PAD_LENGTH)


def test_faces_edge_on_to_the_pad_and_empty_surfaces_give_no_force():
    edge_on = np.array([[0.0, -0.01, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.002]])
    np.testing.assert_array_equal(taxel_normal_forces(edge_on, np.full(3, 1e4), [[0, 1, 2]]),
                                  np.zeros(12))
    empty = taxel_normal_forces(PAD_SQUARE, np.full(4, 1e4), np.zeros((0, 3), dtype=int))
    assert empty.shape == (12,) and empty.dtype == float and not empty.any()


def test_surfaces_in_one_pass_give_each_surfaces_forces_bit_for_bit():
    from tegrasp_drake.simulation.contact_pressure import surfaces_taxel_normal_forces
    rng = np.random.default_rng(11)
    surfaces = []
    for count in (1, 7, 30):
        corners = np.column_stack([rng.uniform(-0.012, 0.012, 3 * count),
                                   rng.uniform(-0.01, 0.01, 3 * count), np.zeros(3 * count)])
        surfaces.append((corners, rng.uniform(0.0, 3e4, 3 * count),
                         np.arange(3 * count).reshape(count, 3)))
    together = surfaces_taxel_normal_forces(surfaces)
    for surface, forces in zip(surfaces, together):
        np.testing.assert_array_equal(forces, taxel_normal_forces(*surface))
        assert forces.sum() > 0.0


def test_corner_differences_are_numpys_diffs_bit_for_bit():
    rng = np.random.default_rng(600)
    cumulative = rng.normal(0.0, 1.0, (40, 3, 4)) * 10.0 ** rng.integers(-12, 3, (40, 3, 4))
    cumulative[0] = -0.0  # signed zeros keep their sign as in np.diff
    expected = np.diff(np.diff(cumulative, axis=1, prepend=0.0), axis=2, prepend=0.0)
    assert corner_differences(cumulative).tobytes() == expected.tobytes()


def test_cells_from_the_edges_a_triangle_reaches_equal_those_from_every_cell_corner():
    # Small faces (most within one column), faces across one or two column edges, faces
    # beyond the pad, a face with a corner on a column edge and a flat one.
    from tegrasp_drake.simulation.contact_pressure import (COLUMN_UPPER_EDGES,
                                                        cell_pressure_integrals,
                                                        every_corner_cell_integrals)
    rng = np.random.default_rng(600)
    centres = rng.uniform([-1.3 * W, -1.3 * L], [1.3 * W, 1.3 * L], size=(300, 1, 2))
    sizes = np.repeat([0.001, 0.004, 0.012], 100)[:, None, None]
    xy = centres + sizes * rng.uniform(-1.0, 1.0, size=(300, 3, 2))
    xy[0, 0, 0] = xy[0, 1, 0] = COLUMN_UPPER_EDGES[0]  # on the edge, the third corner right
    xy[0, 2, 0] = COLUMN_UPPER_EDGES[0] + 0.001
    xy[1] = [[0.001, 0.002], [0.002, 0.004], [0.003, 0.006]]  # flat (collinear corners)
    pressure = rng.uniform(0.0, 1e5, size=(300, 3))
    every_corner = every_corner_cell_integrals(xy, pressure)
    cells = cell_pressure_integrals(xy, pressure)
    np.testing.assert_allclose(cells, every_corner, rtol=1e-12,
                               atol=1e-12 * np.abs(every_corner).max())
    assert np.count_nonzero(cells.reshape(300, -1).any(axis=1)) > 250  # not all zero
