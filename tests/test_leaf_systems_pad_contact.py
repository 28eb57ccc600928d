"""Fixed-input tests of the systems that read the plant's contact results: TactilePads (the
taxel arrays) and PadNormalForces (each finger's force along its pad normal).

The scene: the station's gripper, its base welded to the world, and a rigid block pressed
0.5 mm into the left pad over the pad's whole width and the far 9.5 mm of its 24 mm length
(pad frame y from 2.5 mm to beyond the 12 mm edge). The plant's contact results for that
configuration are the systems' fixed input. What must follow, by hand:
- the right pad and the left pad's two rows nearest the palm (y < 0) feel nothing;
- the block is centred across the pad, so columns 0 and 2 read alike;
- the pressure of a flat block on a flat pad is uniform away from the edges, so row 3
  (6 mm of overlap) carries about 6 / 3.5 times row 2 (3.5 mm);
- the taxels of the left pad sum to the normal component of the force the solver applied
  on the contact, which is also the net force on the left finger along its pad normal.
"""

import functools

import numpy as np
import pytest
from pydrake.geometry import AddContactMaterial, AddRigidHydroelasticProperties, Box
from pydrake.geometry import ProximityProperties
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlant, CoulombFriction, MultibodyPlantConfig
from pydrake.multibody.tree import SpatialInertia, UnitInertia
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.modelgen.robotiq_sdf import HALF_STROKE
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import GRIPPER_URL
from tegrasp_drake.simulation.pad_normal_forces import (PadNormalForces, bodies_contact_forces,
                                                        collision_geometry_bodies)
from tegrasp_drake.simulation.station import pad_geometries
from tegrasp_drake.simulation.tactile_pads import TactilePads, TactileSensorConfig

BLOCK_SIZE = np.array([0.030, 0.0095 + 0.005, 0.010])  # m, in the left pad frame
PENETRATION = 0.0005  # m
OVERLAP_Y = (0.0025, 0.012)  # m, the block's footprint on the pad along y


def _add_block(plant):
    block = plant.AddRigidBody("block", plant.AddModelInstance("block"), SpatialInertia(
        0.1, np.zeros(3), UnitInertia.SolidBox(*BLOCK_SIZE)))
    properties = ProximityProperties()
    AddRigidHydroelasticProperties(resolution_hint=0.002, properties=properties)
    AddContactMaterial(friction=CoulombFriction(0.5, 0.5), properties=properties)
    plant.RegisterCollisionGeometry(block, RigidTransform(), Box(*BLOCK_SIZE), "block",
                                    properties)


@functools.cache
def _pressed_pad(block_first: bool = False, representation: str = "polygon"):
    """(plant, pads, contact results, body poses, X_WP) of the block pressed into the left
    pad. `block_first` registers the block's geometry before the gripper's, which makes the
    pad the contact surface's other geometry (N instead of M: F_Ac_W then acts on the
    block). representation: the contact surface's, "polygon" or "triangle"."""
    builder = DiagramBuilder()
    # Unsampled output ports: the contact results of the context's own configuration.
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(
        time_step=1e-3, use_sampled_output_ports=False,
        contact_surface_representation=representation), builder)
    if block_first:
        _add_block(plant)
    (gripper,) = paths.make_parser(plant).AddModels(url=GRIPPER_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper))
    if not block_first:
        _add_block(plant)
    plant.mutable_gravity_field().set_gravity_vector(np.zeros(3))
    plant.Finalize()
    pads = pad_geometries(plant, scene_graph, gripper)
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    for finger in ("left", "right"):  # open: each pad half the stroke from the grasp axis
        plant.GetJointByName(f"{finger}_finger_joint", gripper).set_translation(
            plant_context, HALF_STROKE)
    X_WP = plant.EvalBodyPoseInWorld(plant_context, plant.get_body(pads["left"].body_index)) \
        @ pads["left"].X_BP
    # The block's near face 0.5 mm inside the pad (pad frame z points into the object);
    # along y it starts 2.5 mm past the pad centre and overhangs the far edge.
    p_PB = [0.0, OVERLAP_Y[0] + BLOCK_SIZE[1] / 2, BLOCK_SIZE[2] / 2 - PENETRATION]
    plant.SetFreeBodyPose(plant_context, plant.GetBodyByName("block"),
                          X_WP @ RigidTransform(p_PB))
    contacts = plant.get_contact_results_output_port().Eval(plant_context)
    poses = plant.get_body_poses_output_port().Eval(plant_context)
    return plant, pads, contacts, poses, X_WP


def _applied_normal_force(block_first: bool = False) -> float:
    """The normal component [N] of the solver's force on the block-pad contact."""
    _, _, contacts, _, X_WP = _pressed_pad(block_first)
    assert contacts.num_hydroelastic_contacts() == 1
    force = contacts.hydroelastic_contact_info(0).F_Ac_W().translational()
    return abs(float(force @ X_WP.rotation().matrix()[:, 2]))


def _sampled_pads(config: TactileSensorConfig, seed: int = 600, samples: int = 1):
    """TactilePads on the pressed pad, after `samples` samples; its system and context."""
    plant, pads, contacts, poses, _ = _pressed_pad()
    tactile = TactilePads(pads=pads, config=config, seed=seed)
    context = tactile.CreateDefaultContext()
    tactile.GetInputPort("contact_results").FixValue(context, contacts)
    tactile.GetInputPort("body_poses").FixValue(context, poses)
    Simulator(tactile, context).AdvanceTo((samples - 0.5) / config.sample_rate_hz)
    return tactile, context


def _output(tactile, context, name: str) -> np.ndarray:
    return tactile.GetOutputPort(name).Eval(context)


NOISELESS = TactileSensorConfig(noise_std_n=0.0, quantization_n=0.0, offset_n=0.0)


def test_taxels_read_the_blocks_footprint_and_sum_to_the_applied_normal_force():
    tactile, context = _sampled_pads(NOISELESS)
    left = _output(tactile, context, "left_taxel_forces")
    total = _applied_normal_force()
    assert total > 1.0  # a real press: the checks below are not on zeros
    np.testing.assert_allclose(left.sum(), total, rtol=1e-9)
    np.testing.assert_array_equal(_output(tactile, context, "right_taxel_forces"), np.zeros(12))
    rows = left.reshape(4, 3)  # taxel = 3 row + column, row 0 nearest the palm
    np.testing.assert_allclose(rows[:2], 0.0, atol=1e-9 * total)
    np.testing.assert_allclose(rows[:, 0], rows[:, 2], rtol=0, atol=0.02 * total)
    # Uniform pressure: forces in proportion to the overlaps (6 mm and 3.5 mm); the
    # hydroelastic pressure falls off within about the penetration of the block's edge.
    assert rows[3].sum() / rows[2].sum() == pytest.approx(6.0 / 3.5, rel=0.15)
    np.testing.assert_array_equal(_output(tactile, context, "true_taxel_forces"),
                                  np.concatenate([left, np.zeros(12)]))


def test_measured_taxels_are_offset_then_quantised_to_the_lsb():
    config = TactileSensorConfig(noise_std_n=0.0, quantization_n=0.01, offset_n=0.1)
    tactile, context = _sampled_pads(config)
    true = _output(tactile, context, "true_taxel_forces")
    measured = np.concatenate([_output(tactile, context, f"{f}_taxel_forces")
                               for f in ("left", "right")])
    np.testing.assert_allclose(measured / 0.01, np.round(measured / 0.01), rtol=0, atol=1e-9)
    np.testing.assert_array_less(np.abs(measured - (true + 0.1)), 0.005 + 1e-12)
    np.testing.assert_allclose(measured[12:], 0.1, rtol=0, atol=1e-12)  # the untouched pad


def test_taxel_noise_has_its_std_and_is_reproducible_per_seed():
    config = TactileSensorConfig(noise_std_n=0.05, quantization_n=0.0, offset_n=0.0)
    errors = []
    for seed in (600, 600, 700):
        tactile, context = _sampled_pads(config, seed=seed, samples=20)
        errors.append(np.concatenate([_output(tactile, context, f"{f}_taxel_forces")
                                      for f in ("left", "right")])
                      - _output(tactile, context, "true_taxel_forces"))
    np.testing.assert_array_equal(errors[0], errors[1])
    assert not np.allclose(errors[0], errors[2])
    # 24 samples of N(0, 0.05): their std is within 40 % of 0.05 unless a 1-in-1000 draw
    # (chi-square with 23 degrees of freedom).
    assert np.std(errors[0]) == pytest.approx(0.05, rel=0.4)


@pytest.mark.parametrize("block_first", [False, True], ids=["pad_is_M", "pad_is_N"])
def test_pad_normal_force_is_the_applied_force_pushing_the_left_pad_open(block_first):
    plant, pads, contacts, poses, _ = _pressed_pad(block_first)
    system = PadNormalForces(plant=plant, pads=pads)
    context = system.CreateDefaultContext()
    system.GetInputPort("contact_results").FixValue(context, contacts)
    system.GetInputPort("body_poses").FixValue(context, poses)
    np.testing.assert_allclose(system.GetOutputPort("pad_normal_forces").Eval(context),
                               [_applied_normal_force(block_first), 0.0], rtol=1e-9,
                               atol=1e-12)


@pytest.mark.parametrize("block_first", [False, True], ids=["pad_is_M", "pad_is_N"])
def test_one_contact_walk_gives_each_body_its_net_contact_force(block_first):
    plant, pads, contacts, _, _ = _pressed_pad(block_first)
    (info,) = [contacts.hydroelastic_contact_info(0)]
    force = info.F_Ac_W().translational()  # on the body of the surface's geometry M
    left, right = (int(pads[f].body_index) for f in ("left", "right"))
    block = int(plant.GetBodyByName("block").index())
    on_pad = -force if block_first else force  # Newton's third law: the block takes -F
    bodies = (left, right, block)
    totals = bodies_contact_forces(contacts, collision_geometry_bodies(plant), bodies)
    assert np.linalg.norm(force) > 1.0  # a real press
    np.testing.assert_array_equal(totals[0], on_pad)
    np.testing.assert_array_equal(totals[1], np.zeros(3))
    np.testing.assert_array_equal(totals[2], -on_pad)
    for body, total in zip(bodies, totals):  # the same as walking for one body alone
        np.testing.assert_array_equal(
            bodies_contact_forces(contacts, collision_geometry_bodies(plant), (body,))[0],
            total)
