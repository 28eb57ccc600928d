"""The two simulated hands' kinematic maps (simulation/gripper_hands.py): the actuated
coordinate to half the pad opening and back, its rate, where the pads' centres lie along
the approach axis, and the selector of the actuated joint's state."""

import numpy as np
import pytest
from pydrake.multibody.plant import MultibodyPlant

from tegrasp_drake.rig import paths
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.robotiq.dimensions import PALM_Z
from tegrasp_drake.simulation.gripper_hands import (LinkageHand, PrismaticHand,
                                                    actuated_state_selector, gripper_hand)

LINKAGE, PRISMATIC = LinkageHand(), PrismaticHand()
DRIVER_ANGLES = np.radians([0.0, 10.0, 25.0, 40.0, 45.0])  # up to the pads meeting, 45.96 deg


def test_gripper_hand_names_select_the_two_hands():
    assert isinstance(gripper_hand("linkage"), LinkageHand)
    assert isinstance(gripper_hand("prismatic"), PrismaticHand)


@pytest.mark.parametrize("angle", DRIVER_ANGLES)
def test_linkage_actuated_coordinate_inverts_half_opening(angle):
    assert LINKAGE.actuated(LINKAGE.half_opening(angle)) == pytest.approx(angle, abs=1e-9)


@pytest.mark.parametrize("angle", DRIVER_ANGLES[1:-1])
def test_linkage_half_opening_rate_is_the_derivative(angle):
    h = 1e-6
    difference = (LINKAGE.half_opening(angle + h) - LINKAGE.half_opening(angle - h)) / (2 * h)
    assert LINKAGE.half_opening_rate(angle) == pytest.approx(difference, rel=1e-6)
    assert LINKAGE.half_opening_rate(angle) < 0  # the driver closes the fingers


def test_linkage_opens_to_the_full_stroke_and_closes_as_the_driver_turns():
    assert 2 * LINKAGE.half_opening(0.0) == pytest.approx(0.085, abs=1e-4)  # 85 mm stroke
    openings = [LINKAGE.half_opening(a) for a in DRIVER_ANGLES]
    assert np.all(np.diff(openings) < 0)


def test_linkage_pad_centres_move_along_the_approach_axis_as_the_2f85s_do():
    # The pad centre's travel from open (gap 85 mm) along the approach axis, from the
    # linkage's closed form (robotiq/linkage.py: 5.43 / 10.24 / 11.82 / 12.91 / 13.54 mm at gaps
    # 70 / 50 / 40 / 30 / 20 mm, matched by the simulated linkage within 0.01 mm).
    open_offset = LINKAGE.pad_center_offset(0.085)
    travel_mm = [1000 * (LINKAGE.pad_center_offset(gap) - open_offset)
                 for gap in (0.07, 0.05, 0.04, 0.03, 0.02)]
    np.testing.assert_allclose(travel_mm, [5.43, 10.24, 11.82, 12.91, 13.54], rtol=0,
                               atol=0.02)
    # The figures its docstring gives: -9.3 mm open, +1.8 mm at 45 mm, +4.0 mm at 25 mm.
    np.testing.assert_allclose([1000 * LINKAGE.pad_center_offset(g)
                                for g in (0.085, 0.045, 0.025)], [-9.3, 1.8, 4.0], rtol=0,
                               atol=0.05)


def test_curled_linkage_fingertips_place_the_hooked_cylinder_toward_the_palm():
    # The figure its docstring gives: the 25 mm cylinder hooked at 4.5 mm open on the distal
    # row (+9 mm) lies 25.5 mm toward the palm from the pads' centres at its width; hooked
    # nearer the pads' centres it lies less far; no hand can put it inside the palm.
    assert 1000 * LINKAGE.hooked_object_offset(0.0045, 0.009, 0.025) == pytest.approx(
        -25.5, abs=0.05)
    assert (LINKAGE.hooked_object_offset(0.0045, 0.009, 0.025)
            < LINKAGE.hooked_object_offset(0.0045, 0.003, 0.025) < 0.0)
    palm = PALM_Z + 0.0125 - linkage.pad_center(linkage.driver_angle(0.0125))[1]
    assert LINKAGE.hooked_object_offset(0.0, 0.012, 0.025) >= palm
    assert LINKAGE.hooked_object_offset(0.030, 0.0, 0.025) is None  # flat pads reach it
    assert PRISMATIC.hooked_object_offset(0.0045, 0.009, 0.025) is None


def test_prismatic_hand_moves_its_pads_along_the_stroke_only():
    for q in (0.0, 0.02, 0.0425):
        assert (PRISMATIC.half_opening(q), PRISMATIC.actuated(q)) == (q, q)
        assert PRISMATIC.half_opening_rate(q) == 1.0
        assert PRISMATIC.pad_center_offset(2 * q) == 0.0


@pytest.mark.parametrize("hand", [LINKAGE, PRISMATIC], ids=["linkage", "prismatic"])
def test_actuated_state_selector_picks_the_actuated_joints_position_and_velocity(hand):
    plant = MultibodyPlant(0.0)
    (gripper,) = paths.make_parser(plant).AddModels(url=hand.url)
    plant.Finalize()
    joint = plant.GetJointByName(hand.actuated_joint, gripper)
    q = np.arange(1, plant.num_positions(gripper) + 1) * 0.01  # every coordinate distinct
    v = -np.arange(1, plant.num_velocities(gripper) + 1) * 0.1
    q_all, v_all = np.zeros(plant.num_positions()), np.zeros(plant.num_velocities())
    plant.SetPositionsInArray(gripper, q, q_all)
    plant.SetVelocitiesInArray(gripper, v, v_all)
    selector = actuated_state_selector(plant, gripper, hand)
    context = selector.CreateDefaultContext()
    selector.get_input_port().FixValue(context, np.concatenate([q, v]))
    np.testing.assert_array_equal(selector.get_output_port().Eval(context),
                                  [q_all[joint.position_start()],
                                   v_all[joint.velocity_start()]])


def _pad_and_object_properties(scenario):
    """(each pad's Coulomb coefficients (static, dynamic), the object's, each pad's
    hydroelastic modulus [Pa]) as the built plant reads them at run time (the query object's
    inspector), copied out of the diagram."""
    from pydrake.systems.framework import DiagramBuilder
    from tegrasp_drake.scenario.scenario import object_pose
    from tegrasp_drake.simulation.object_model import object_body
    from tegrasp_drake.simulation.station import AddStationPlant, pad_geometries
    builder = DiagramBuilder()
    parts = AddStationPlant(builder, plant_config=scenario.plant_config, arm=scenario.arm,
                            gripper=scenario.gripper, object=scenario.object,
                            X_WO=object_pose(scenario),
                            pad_modulus_pa=scenario.tactile.pad_modulus_pa,
                            random_seed=scenario.random_seed,
                            contact_geometry=scenario.contact_geometry)
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    inspector = parts.scene_graph.get_query_output_port().Eval(
        parts.scene_graph.GetMyContextFromRoot(context)).inspector()

    def friction(geometry):
        coulomb = inspector.GetProximityProperties(geometry).GetProperty(
            "material", "coulomb_friction")
        return float(coulomb.static_friction()), float(coulomb.dynamic_friction())
    pads = [pad.geometry_id for pad in
            pad_geometries(parts.plant, parts.scene_graph, parts.gripper).values()]
    (obj,) = parts.plant.GetCollisionGeometriesForBody(
        object_body(parts.plant, parts.object_instance))
    moduli = [float(inspector.GetProximityProperties(pad).GetProperty(
        "hydroelastic", "hydroelastic_modulus")) for pad in pads]
    return [friction(pad) for pad in pads], friction(obj), moduli


def test_the_pad_friction_setting_replaces_the_pads_coefficient_and_only_theirs():
    from tegrasp_drake.rig import materials
    from tegrasp_drake.scenario.scenario import LoadScenario
    default_pads, default_object, _ = _pad_and_object_properties(LoadScenario())
    assert default_pads == [(materials.PAD_COVER, materials.PAD_COVER)] * 2
    pads, obj, _ = _pad_and_object_properties(
        LoadScenario(overrides=["gripper.pad_friction=0.91"]))
    assert pads == [(0.91, 0.91)] * 2
    assert obj == default_object == (materials.CARDBOARD, materials.CARDBOARD)
    # the box's pair with the pads, as Drake combines them: 0.60 (0.81 at the default)
    assert materials.pair_friction(0.91, obj[1]) == pytest.approx(0.60,
                                                                                 abs=0.005)


@pytest.mark.parametrize("modulus_pa", [5.0e5, 4.0e6])
def test_the_pad_modulus_setting_replaces_the_pads_hydroelastic_modulus(modulus_pa):
    from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
    from tegrasp_drake.scenario.scenario import LoadScenario
    assert _pad_and_object_properties(LoadScenario())[2] == [PAD_MODULUS] * 2
    scenario = LoadScenario(overrides=[f"tactile.pad_modulus_pa={modulus_pa}"])
    assert _pad_and_object_properties(scenario)[2] == [modulus_pa] * 2
