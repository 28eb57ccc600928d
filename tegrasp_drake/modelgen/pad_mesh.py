"""Writes models/robotiq_2f85/pad_refined_<k>.vtk: the pad's compliant box as a finer
tetrahedral mesh with the same pressure field.

Drake meshes a compliant Box from its medial axis (44 tetrahedra for the 20 x 4 x 24 mm
pad, whatever its resolution hint): the coarsest mesh on which the box's pressure field,
E times the distance to the surface over the half-thickness, is linear in every
tetrahedron. A hydroelastic contact surface has one face per tetrahedron it crosses (per
triangle of a rigid partner), and each face is one SAP contact constraint, so this mesh
gives a pad few faces (docs/model.md, "Friction creep"). Here that same mesh is split k
times into eight (each tetrahedron at its edges' midpoints: four corner tetrahedra and the
inner octahedron cut along one diagonal), which multiplies the faces a contact surface
crosses by about 4^k. Drake loads a compliant .vtk mesh with the pressure E d / d_max,
d each vertex's distance to the mesh's surface: the new vertices lie inside the old
tetrahedra, where the distance is linear, and the deepest vertices stay on the medial
plane at half the thickness, so the field is the box's own, value for value.
"""

import numpy as np
from pydrake.geometry import (AddCompliantHydroelasticProperties, Box, GeometryInstance,
                              ProximityProperties, SceneGraph)
from pydrake.math import RigidTransform

from tegrasp_drake.modelgen.sdf_text import number_text
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH

# The pad box in its collision frame (x across, y through, z along: modelgen/robotiq_sdf.py).
PAD_SIZE = (PAD_WIDTH, PAD_THICKNESS, PAD_LENGTH)
# The levels a scenario can select (0: Drake's own mesh of the box); each level multiplies
# the faces of the pads' contact surfaces by about 4, and the CPU time of a step in contact
# with them (docs/model.md, "Friction creep").
PAD_REFINEMENTS = (0, 1, 2)


def medial_axis_mesh(size) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (V, 3) [m], tetrahedra (T, 4) vertex indices) of Drake's own compliant
    mesh of a box of `size` [m], centred at its frame's origin."""
    scene_graph = SceneGraph()
    source = scene_graph.RegisterSource("pad_mesh")
    properties = ProximityProperties()
    # Drake ignores the hint for a compliant box; the modulus only scales the field.
    AddCompliantHydroelasticProperties(resolution_hint=1.0, hydroelastic_modulus=1.0,
                                       properties=properties)
    instance = GeometryInstance(RigidTransform(), Box(*size), "pad")
    instance.set_proximity_properties(properties)
    geometry = scene_graph.RegisterAnchoredGeometry(source, instance)
    mesh = scene_graph.model_inspector().maybe_get_hydroelastic_mesh(geometry)
    vertices = np.array([mesh.vertex(i) for i in range(mesh.num_vertices())])
    tetrahedra = np.array([[mesh.element(e).vertex(k) for k in range(4)]
                           for e in range(mesh.num_elements())])
    return vertices, tetrahedra


def split_in_eight(vertices: np.ndarray, tetrahedra: np.ndarray):
    """Each tetrahedron split at its edges' midpoints into eight (shared midpoints are one
    vertex); every new tetrahedron positively oriented, as Drake's are."""
    points = [tuple(v) for v in vertices]
    index = {}

    def midpoint(a: int, b: int) -> int:
        key = (min(a, b), max(a, b))
        if key not in index:
            index[key] = len(points)
            points.append(tuple((np.asarray(points[a]) + points[b]) / 2))
        return index[key]

    split = []
    for a, b, c, d in tetrahedra:
        ab, ac, ad = midpoint(a, b), midpoint(a, c), midpoint(a, d)
        bc, bd, cd = midpoint(b, c), midpoint(b, d), midpoint(c, d)
        split += [(a, ab, ac, ad), (ab, b, bc, bd), (ac, bc, c, cd), (ad, bd, cd, d),
                  (ab, ac, ad, bd), (ab, ac, bd, bc), (ac, ad, bd, cd), (ac, bd, bc, cd)]
    points, split = np.array(points), np.array(split)
    p = points[split]
    volume6 = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                        p[:, 3] - p[:, 0])
    split[volume6 < 0] = split[volume6 < 0][:, [0, 2, 1, 3]]
    return points, split


def refined_pad_mesh(refinement: int) -> tuple[np.ndarray, np.ndarray]:
    """The pad's medial-axis mesh split `refinement` times (0: Drake's own)."""
    vertices, tetrahedra = medial_axis_mesh(PAD_SIZE)
    for _ in range(refinement):
        vertices, tetrahedra = split_in_eight(vertices, tetrahedra)
    return vertices, tetrahedra


def vtk_text(vertices: np.ndarray, tetrahedra: np.ndarray, title: str) -> str:
    """A legacy ASCII VTK unstructured grid of tetrahedra (cell type 10), as Drake reads."""
    lines = ["# vtk DataFile Version 3.0", title, "ASCII", "DATASET UNSTRUCTURED_GRID",
             f"POINTS {len(vertices)} double"]
    lines += [" ".join(number_text(x) for x in v) for v in vertices]
    lines += [f"CELLS {len(tetrahedra)} {5 * len(tetrahedra)}"]
    lines += ["4 " + " ".join(str(int(i)) for i in t) for t in tetrahedra]
    lines += [f"CELL_TYPES {len(tetrahedra)}"] + ["10"] * len(tetrahedra)
    return "\n".join(lines) + "\n"


def pad_vtk(refinement: int) -> str:
    """The text of models/robotiq_2f85/pad_refined_<refinement>.vtk."""
    vertices, tetrahedra = refined_pad_mesh(refinement)
    return vtk_text(vertices, tetrahedra,
                    f"the 2F-85 tactile pad ({' x '.join(f'{s * 1e3:g}' for s in PAD_SIZE)} "
                    f"mm), Drake's medial-axis box mesh split {refinement} times")
