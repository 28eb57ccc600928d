"""TactilePads' reading of real contact surfaces, in both of Drake's representations, against
the plain per-element reading and the every-corner integral (benchmarks/pad_contact_reads.py).

The scene: the station's gripper welded to the world and a rigid block pressed 0.5 mm into
the left pad, across the pad's middle column edges and its rows beyond the centre (the
fixed-input scene of tests/test_leaf_systems_pad_contact.py, wider and off centre)."""

import functools

import numpy as np
import pytest
from pydrake.geometry import AddContactMaterial, AddRigidHydroelasticProperties, Box
from pydrake.geometry import ProximityProperties
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlant, CoulombFriction, MultibodyPlantConfig
from pydrake.multibody.tree import SpatialInertia, UnitInertia
from pydrake.systems.framework import DiagramBuilder

from benchmarks.pad_contact_reads import (per_element_pads_surfaces,
                                          per_element_surface_arrays, pads_forces)
from tegrasp_drake.modelgen.robotiq_sdf import HALF_STROKE
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import GRIPPER_URL
from tegrasp_drake.simulation.station import pad_geometries
from tegrasp_drake.simulation.tactile_pads import _pads_surfaces, pads_forces as bulk_forces
from tegrasp_drake.simulation.tactile_pads import surface_arrays

BLOCK_SIZE = np.array([0.017, 0.015, 0.010])  # m, in the left pad frame
PENETRATION = 0.0005  # m


@functools.cache
def _pressed_pad(representation: str):
    """(contact results, pad geometry ids, pad poses function) of the pressed block; the
    diagram and context are kept alive with them."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(
        time_step=1e-3, use_sampled_output_ports=False,
        contact_surface_representation=representation), builder)
    (gripper,) = paths.make_parser(plant).AddModels(url=GRIPPER_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper))
    block = plant.AddRigidBody("block", plant.AddModelInstance("block"), SpatialInertia(
        0.1, np.zeros(3), UnitInertia.SolidBox(*BLOCK_SIZE)))
    properties = ProximityProperties()
    AddRigidHydroelasticProperties(resolution_hint=0.002, properties=properties)
    AddContactMaterial(friction=CoulombFriction(0.5, 0.5), properties=properties)
    plant.RegisterCollisionGeometry(block, RigidTransform(), Box(*BLOCK_SIZE), "block",
                                    properties)
    plant.mutable_gravity_field().set_gravity_vector(np.zeros(3))
    plant.Finalize()
    pads = pad_geometries(plant, scene_graph, gripper)
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    for finger in ("left", "right"):
        plant.GetJointByName(f"{finger}_finger_joint", gripper).set_translation(
            plant_context, HALF_STROKE)
    pad_list = [pads["left"], pads["right"]]
    poses = [plant.EvalBodyPoseInWorld(plant_context, plant.get_body(p.body_index)) @ p.X_BP
             for p in pad_list]
    p_PB = [0.002, 0.004 + BLOCK_SIZE[1] / 2 - 0.006, BLOCK_SIZE[2] / 2 - PENETRATION]
    plant.SetFreeBodyPose(plant_context, block, poses[0] @ RigidTransform(p_PB))
    contacts = plant.get_contact_results_output_port().Eval(plant_context)
    return contacts, [p.geometry_id for p in pad_list], (lambda: poses), (diagram, context)


@pytest.mark.parametrize("representation", ["triangle", "polygon"])
def test_the_surface_arrays_are_the_per_element_reading(representation):
    contacts, *_ = _pressed_pad(representation)
    assert contacts.num_hydroelastic_contacts() == 1
    surface = contacts.hydroelastic_contact_info(0).contact_surface()
    assert surface.is_triangle() == (representation == "triangle")
    assert surface.num_faces() > 20  # a real surface, many faces
    for read, reference in zip(surface_arrays(surface), per_element_surface_arrays(surface)):
        np.testing.assert_array_equal(read, reference)


@pytest.mark.parametrize("representation", ["triangle", "polygon"])
def test_taxel_forces_equal_the_per_element_reading_and_every_corner_integral(
        representation):
    contacts, ids, poses, _ = _pressed_pad(representation)
    bulk = np.concatenate(bulk_forces(contacts, ids, poses))
    reference = np.concatenate(pads_forces("per element", contacts, ids, poses))
    assert np.count_nonzero(bulk[:12] > 1e-3) >= 4  # the block loads several taxels
    np.testing.assert_allclose(bulk, reference, rtol=1e-12, atol=1e-12 * reference.max())
    for pad, pad_reference in zip(_pads_surfaces(contacts, ids, poses),
                                  per_element_pads_surfaces(contacts, ids, poses)):
        for surface, surface_reference in zip(pad, pad_reference, strict=True):
            for got, expected in zip(surface, surface_reference):
                np.testing.assert_array_equal(got, expected)
