"""Per-taxel normal force from a hydroelastic contact surface: the pure numpy core.

A face's force on the pad is its pressure integrated over its projection on the pad plane.
The pressure is linear over each face and the taxels form a grid, so each cell's share of
each triangle has a closed form, exact however large the faces: the cumulative integral over
{x < a, y < b} summed from the triangle's edges (Green's theorem), a cell's force by
inclusion-exclusion at its corners; a triangle is cut only at the column edges that cross it
(cell_pressure_integrals). Points beyond the pad's edge count to the nearest edge taxel."""

import numpy as np

from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y, COLUMNS, PAD_LENGTH, PAD_WIDTH, ROWS

_OPEN_EDGE = 1.0  # m; stands for "unbounded" on a pad's outer cell edges (pads are cm wide)
# The upper edges of the columns (along x) and rows (along y), the last one open.
COLUMN_UPPER_EDGES = np.append(-PAD_WIDTH / 2 + CELL_X * np.arange(1, COLUMNS), _OPEN_EDGE)
ROW_UPPER_EDGES = np.append(-PAD_LENGTH / 2 + CELL_Y * np.arange(1, ROWS), _OPEN_EDGE)
# A projected triangle this much flatter than its edges are long is treated as a segment
# (zero area): its pressure gradient in the pad plane is undefined.
_FLAT_TRIANGLE = 1e-9


def polygon_fan_triangles(face_data) -> np.ndarray:
    """Vertex indices (T, 3) of a fan triangulation of PolygonSurfaceMesh.face_data()."""
    data = np.asarray(face_data, dtype=np.intp)
    headers = data.tolist()  # Python ints: the walk below reads one per face
    starts, counts = [], []
    k = 0
    while k < len(headers):  # walks the face headers only; the triangles are built vectorised
        starts.append(k + 1)
        counts.append(headers[k])
        k += headers[k] + 1
    starts, counts = np.asarray(starts, np.intp), np.asarray(counts, np.intp)
    fans = counts - 2
    face_of_triangle = np.repeat(np.arange(starts.size), fans)
    first = np.cumsum(fans) - fans
    corner = np.arange(fans.sum()) - np.repeat(first, fans) + 1
    origin = data[starts[face_of_triangle]]
    return np.column_stack([origin, data[starts[face_of_triangle] + corner],
                            data[starts[face_of_triangle] + corner + 1]])


def cumulative_pressure_integrals(xy: np.ndarray, pressure: np.ndarray, x_edges: np.ndarray,
                                  y_edges: np.ndarray) -> np.ndarray:
    """F[t, i, j] = integral of triangle t's linear pressure over t and {x < x_edges[i],
    y < y_edges[j]} [N for Pa and m]; xy: corners (T, 3, 2), pressure: at them (T, 3);
    x_edges shared (X,) or per triangle (T, X)."""
    origin = xy[:, :1]
    corner = xy - origin  # coordinates relative to each triangle's first corner
    e1, e2 = corner[:, 1], corner[:, 2]
    twice_area = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]  # signed
    flat = np.abs(twice_area) <= _FLAT_TRIANGLE * (np.sum(e1 * e1, 1) + np.sum(e2 * e2, 1))
    safe = np.where(flat, 1.0, twice_area)
    dp1, dp2 = pressure[:, 1] - pressure[:, 0], pressure[:, 2] - pressure[:, 0]
    # The pressure plane f(x, y) = p0 + fx x + fy y, shaped (T, 1, 1, 1) to broadcast over
    # (triangle, edge, x edge, y edge).
    fx = np.where(flat, 0.0, (dp1 * e2[:, 1] - dp2 * e1[:, 1]) / safe)[:, None, None, None]
    fy = np.where(flat, 0.0, (dp2 * e1[:, 0] - dp1 * e2[:, 0]) / safe)[:, None, None, None]
    p0 = pressure[:, :1, None, None]
    # Edges P -> Q (corner k to k + 1) as lines y = c + slope x, shaped (T, 3, 1, 1).
    start, end = corner, np.roll(corner, -1, axis=1)
    dx = end[:, :, 0] - start[:, :, 0]
    vertical = dx == 0.0  # sweeps nothing
    slope = np.where(vertical, 0.0, (end[:, :, 1] - start[:, :, 1]) / np.where(vertical, 1.0, dx))
    c = (start[:, :, 1] - slope * start[:, :, 0])[:, :, None, None]
    slope = slope[:, :, None, None]
    curvature = (2.0 * fx * slope + fy * slope * slope) / 24.0  # g'' / 24 on the edge
    a = (np.atleast_2d(x_edges) - origin[:, :, 0])[:, None, :, None]
    b = (y_edges[None, :] - origin[:, :, 1])[:, None, None, :]
    # The sweep runs from x_P to x_Q, cut at x = a, split where the edge crosses y = b.
    x0 = np.minimum(start[:, :, 0, None, None], a)
    x2 = np.minimum(end[:, :, 0, None, None], a)
    level = slope == 0.0
    crossing = (b - c) / np.where(level, 1.0, slope)
    x1 = np.where(level, x0, np.clip(crossing, np.minimum(x0, x2), np.maximum(x0, x2)))

    def swept(u, v):
        """Directed integral of g from u to v, exact for g quadratic on [u, v]."""
        width, middle = v - u, 0.5 * (u + v)
        y = c + slope * middle
        on_edge = y < b  # else g is cut off at y = b (linear in x, no curvature term)
        y = np.minimum(y, b)
        return width * ((p0 + fx * middle) * y + 0.5 * fy * y * y
                        + np.where(on_edge, curvature * width * width, 0.0))

    edge_sums = (swept(x0, x1) + swept(x1, x2)).sum(axis=1)
    return -np.sign(twice_area)[:, None, None] * edge_sums


def taxel_normal_forces(p_PV: np.ndarray, pressure_V: np.ndarray,
                        triangles: np.ndarray) -> np.ndarray:
    """Normal force on each of the 12 taxels [N] from one contact surface, exactly: p_PV
    vertices in the pad frame (V, 3) [m], pressure_V at each [Pa], triangles (T, 3) indices.
    A triangle's share of a cell is clipped at zero (only rounding can make it negative)."""
    return surfaces_taxel_normal_forces([(p_PV, pressure_V, triangles)])[0]


def corner_differences(cumulative: np.ndarray) -> np.ndarray:
    """Each cell's integral from the cumulative integrals F (T, x edge, y edge) at its upper
    corners, F[i, j] - F[i - 1, j] - F[i, j - 1] + F[i - 1, j - 1], in place."""
    columns = cumulative.copy()
    columns[:, 1:] -= cumulative[:, :-1]
    cells = columns.copy()
    cells[:, :, 1:] -= columns[:, :, :-1]
    return cells


def cell_pressure_integrals(xy: np.ndarray, pressure: np.ndarray) -> np.ndarray:
    """Each triangle's pressure integral over each taxel cell (T, column, row) [N], corners xy
    (T, 3, 2) [m, pad frame] and pressure (T, 3) [Pa] as in cumulative_pressure_integrals.

    The cumulative integral at a column edge at or below all of a triangle's corners is zero
    (every sweep has zero width), and at every edge at or beyond all of them it is the same
    number (each sweep ends at its corners): the integrals are computed at the edges that
    cross a triangle and at the first edge beyond it only (one edge for most triangles, the
    faces being finer than the cells), the others filled in, then differenced at the cell
    corners: the same numbers as computing all of them."""
    corner_x = xy[:, :, 0] - xy[:, :1, 0]  # as cumulative_pressure_integrals computes them
    a = COLUMN_UPPER_EDGES[None, :] - xy[:, :1, 0]  # the column edges relative to corner 0
    beyond = corner_x.max(axis=1)[:, None] <= a
    below = corner_x.min(axis=1)[:, None] >= a
    first = np.argmax(beyond, axis=1)  # the first edge beyond (the last edge is open)
    edge = np.arange(COLUMN_UPPER_EDGES.size)[None, :]
    needed = ~below & (~beyond | (edge == first[:, None]))
    triangle, column = np.nonzero(needed)
    cumulative = np.zeros((len(xy), COLUMN_UPPER_EDGES.size, ROW_UPPER_EDGES.size))
    cumulative[triangle, column] = cumulative_pressure_integrals(
        xy[triangle], pressure[triangle], COLUMN_UPPER_EDGES[column][:, None],
        ROW_UPPER_EDGES)[:, 0]
    further = beyond & (edge > first[:, None])
    cumulative = np.where(further[:, :, None],
                          cumulative[np.arange(len(xy)), first][:, None, :], cumulative)
    return corner_differences(cumulative)


def every_corner_cell_integrals(xy: np.ndarray, pressure: np.ndarray) -> np.ndarray:
    """cell_pressure_integrals by its definition: every triangle's cumulative integral at every
    cell corner, differenced."""
    return corner_differences(cumulative_pressure_integrals(xy, pressure, COLUMN_UPPER_EDGES,
                                                            ROW_UPPER_EDGES))


def surfaces_taxel_normal_forces(surfaces, cell_integrals=cell_pressure_integrals
                                 ) -> list[np.ndarray]:
    """taxel_normal_forces of each surface in `surfaces`, in one pass over all triangles;
    cell_integrals: cell_pressure_integrals or every_corner_cell_integrals."""
    triangles = [np.asarray(t, dtype=np.intp).reshape(-1, 3) for _, _, t in surfaces]
    xy = np.concatenate([np.asarray(p_PV, dtype=float)[t][:, :, :2]
                         for (p_PV, _, _), t in zip(surfaces, triangles)])
    pressure = np.concatenate([np.asarray(p, dtype=float)[t]
                               for (_, p, _), t in zip(surfaces, triangles)])
    cells = cell_integrals(xy, pressure)  # (T, col, row)
    np.maximum(cells, 0.0, out=cells)
    forces, start = [], 0
    for t in triangles:
        forces.append(cells[start:start + len(t)].sum(axis=0).T.reshape(ROWS * COLUMNS))
        start += len(t)
    return forces
