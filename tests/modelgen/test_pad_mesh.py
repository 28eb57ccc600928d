"""The pad's refined meshes (modelgen/pad_mesh.py): the same box, eight times the
tetrahedra a level, and the same pressure field as Drake's own mesh of the box, so a
contact carries the same force on any of them."""

import numpy as np
import pytest
from pydrake.geometry import (AddCompliantHydroelasticProperties, AddRigidHydroelasticProperties,
                              Box, HydroelasticContactRepresentation, Mesh, ProximityProperties)
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.multibody.tree import SpatialInertia
from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.modelgen.pad_mesh import PAD_SIZE, refined_pad_mesh
from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
from tegrasp_drake.rig import paths


@pytest.mark.parametrize("refinement", [1, 2])
def test_a_refined_mesh_fills_the_pad_box_with_eight_times_the_tetrahedra(refinement):
    vertices, tetrahedra = refined_pad_mesh(refinement)
    coarse = refined_pad_mesh(0)[1]
    assert len(tetrahedra) == len(coarse) * 8 ** refinement
    p = vertices[tetrahedra]
    volumes = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                        p[:, 3] - p[:, 0]) / 6
    assert np.all(volumes > 0)  # Drake's orientation
    assert volumes.sum() == pytest.approx(np.prod(PAD_SIZE), rel=1e-12)
    np.testing.assert_allclose(np.abs(vertices).max(axis=0), np.array(PAD_SIZE) / 2,
                               rtol=1e-12)


def _pressed_force(pad_shape) -> float:
    """The normal force [N] of a rigid plate pressed into the pad's +y face, tilted so that
    its depth runs from 0.05 to 0.35 mm across the pad and its edge crosses the face: the
    integral of the pressure over the polygon contact surface (exact for a linear field)."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
    pad_properties = ProximityProperties()
    AddCompliantHydroelasticProperties(resolution_hint=1.0, hydroelastic_modulus=PAD_MODULUS,
                                       properties=pad_properties)
    plant.RegisterCollisionGeometry(plant.world_body(), RigidTransform(), pad_shape, "pad",
                                    pad_properties)
    plate = plant.AddRigidBody("plate", SpatialInertia.SolidBoxWithMass(0.1, 0.03, 0.01, 0.03))
    plate_properties = ProximityProperties()
    AddRigidHydroelasticProperties(resolution_hint=1.0, properties=plate_properties)
    plant.RegisterCollisionGeometry(plate, RigidTransform(), Box(0.03, 0.01, 0.03), "plate",
                                    plate_properties)
    plant.Finalize()
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    tilt = 0.0003 / 0.02  # rad: 0.3 mm deeper across the pad's 20 mm width
    # The plate's -y face 0.2 mm inside the pad's face at its centre, tilted along x;
    # shifted 6 mm along z, so that the plate's edge crosses the face at z = -9 mm and the
    # pad's rim at z = 12 mm lies under the plate.
    X_WP = RigidTransform(RollPitchYaw(0.0, 0.0, tilt), [0.0, 0.002 - 0.0002 + 0.005, 0.006])
    plant.SetFreeBodyPose(plant.GetMyMutableContextFromRoot(context), plate, X_WP)
    query = scene_graph.get_query_output_port().Eval(
        scene_graph.GetMyContextFromRoot(context))
    (surface,) = query.ComputeContactSurfaces(HydroelasticContactRepresentation.kPolygon)
    mesh, field = surface.poly_mesh_W(), surface.poly_e_MN()
    return sum(mesh.area(f) * field.EvaluateCartesian(f, mesh.element_centroid(f))
               for f in range(mesh.num_elements()))


def test_a_refined_pad_presses_with_the_boxs_pressure_field():
    box = _pressed_force(Box(*PAD_SIZE))
    assert box > 1.0  # a real press, tens of newtons
    for refinement in (1, 2):
        path = paths.models_dir() / f"robotiq_2f85/pad_refined_{refinement}.vtk"
        assert _pressed_force(Mesh(str(path))) == pytest.approx(box, rel=1e-9)
