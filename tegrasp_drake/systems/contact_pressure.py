"""Per-taxel normal force from a hydroelastic contact surface: the pure numpy core.

A contact face's pressure is linear over the face, so cutting each face into n^2 small
triangles and giving each one pressure(centroid) x area distributes the face's force
correctly even when faces are large (a compliant box's faces are a few cm across). Each
small triangle's force goes to the taxel under its centroid.
"""

import numpy as np

from tegrasp_drake.systems.taxel_layout import COLUMNS, ROWS, taxel_index


def polygon_fan_triangles(face_data) -> np.ndarray:
    """Vertex indices (T, 3) of a fan triangulation of a flat polygon list.

    `face_data` is Drake's PolygonSurfaceMesh.face_data(): [n, v0 .. v(n-1), n, ...].
    """
    data = np.asarray(face_data, dtype=np.intp)
    starts, counts = [], []
    k = 0
    while k < data.size:  # walks the face headers only; the triangles are built vectorised
        starts.append(k + 1)
        counts.append(data[k])
        k += data[k] + 1
    starts, counts = np.asarray(starts, np.intp), np.asarray(counts, np.intp)
    fans = counts - 2
    face_of_triangle = np.repeat(np.arange(starts.size), fans)
    first = np.cumsum(fans) - fans
    corner = np.arange(fans.sum()) - np.repeat(first, fans) + 1
    origin = data[starts[face_of_triangle]]
    return np.column_stack([origin, data[starts[face_of_triangle] + corner],
                            data[starts[face_of_triangle] + corner + 1]])


def subdivision_weights(n: int) -> np.ndarray:
    """Barycentric coordinates (n^2, 3) of the centroids of the n^2 congruent triangles that
    cut a triangle with n divisions per edge."""
    weights = []
    for i in range(n):
        for j in range(n - i):
            # Upward triangle (i, j), (i+1, j), (i, j+1) in the barycentric grid.
            weights.append([(i + 1 / 3), (j + 1 / 3)])
            if i + j < n - 1:  # downward triangle (i+1, j), (i, j+1), (i+1, j+1)
                weights.append([(i + 2 / 3), (j + 2 / 3)])
    w = np.asarray(weights) / n
    return np.column_stack([1.0 - w.sum(axis=1), w[:, 0], w[:, 1]])


def taxel_normal_forces(p_PV: np.ndarray, pressure_V: np.ndarray, triangles: np.ndarray,
                        weights: np.ndarray) -> np.ndarray:
    """Normal force on each of the 12 taxels [N] from one contact surface.

    p_PV: vertex positions in the pad frame (V, 3) [m]; pressure_V: pressure at each vertex
    [Pa]; triangles: (T, 3) vertex indices; weights: subdivision_weights(n). The force of a
    piece is pressure x area x |cos| of the angle between the face normal and the pad's z.
    """
    corners = p_PV[triangles]  # (T, 3, 3)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    area = 0.5 * np.linalg.norm(cross, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos_normal = np.abs(cross[:, 2]) / np.where(area > 0, 2 * area, 1.0)
    piece_points = np.einsum("sk,tkd->tsd", weights, corners).reshape(-1, 3)
    piece_pressure = (pressure_V[triangles] @ weights.T).reshape(-1)
    piece_force = piece_pressure * np.repeat(area * cos_normal / len(weights), len(weights))
    return np.bincount(taxel_index(piece_points), weights=np.maximum(piece_force, 0.0),
                       minlength=ROWS * COLUMNS)
