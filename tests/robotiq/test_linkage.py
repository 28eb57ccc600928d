"""The simulated 2F-85 finger linkage against the closed form of its five-bar
(robotiq/linkage.py), on the gripper bench (the gripper alone, welded)."""

import math

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import EventStatus

from tegrasp_drake.control.scripted_grasp import gripper_command
from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.robotiq.drive import grip_rise
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.simulation.gripper_bench import (BenchObstacle, MakeGripperBench,
                                                    loop_closure_error_m)
from tegrasp_drake.simulation.sim_robotiq_driver import GripperDriverConfig
from tests.cheap_contact import CHEAP_CONTACT

FRICTIONLESS = 1e-4  # the rod's friction: the statics of the flip height have none
# The pad (compliant hydroelastic box, its pressure rising linearly to the modulus at half
# its thickness) pressed flat on a rigid face: modulus x area / half thickness [N/m].
RIGID_BOX_PAD_STIFFNESS = PAD_MODULUS * PAD_WIDTH * PAD_LENGTH / (PAD_THICKNESS / 2)
ROD_DIAMETER = 0.030  # m: the pads stop on it at a 30 mm opening


def _run(command, *, t_end=1.6, sample_s=0.005, **bench_options):
    """Runs the bench; returns one sample per sample_s: (driver angle, coupler angle, left
    pad frame X_WP, pad normal forces, loop error); the angles are nan and the loop error 0
    on the prismatic hand."""
    bench = MakeGripperBench(command=command, **bench_options)
    simulator = Simulator(bench.diagram)
    context = simulator.get_mutable_context()
    plant_context = bench.plant.GetMyContextFromRoot(context)
    forces_context = bench.pad_forces.GetMyContextFromRoot(context)
    plant, gripper = bench.plant, bench.gripper
    linkage_hand = plant.HasJointNamed("left_driver_joint", gripper)
    angle = lambda name: (plant.GetJointByName(name, gripper).get_angle(plant_context)
                          if linkage_hand else math.nan)
    samples = []
    for k in range(1, int(round(t_end / sample_s)) + 1):
        simulator.AdvanceTo(k * sample_s)
        samples.append((
            angle("left_driver_joint"), angle("left_coupler_joint"),
            plant.GetFrameByName("left_pad", gripper).CalcPoseInWorld(plant_context),
            bench.pad_forces.GetOutputPort("pad_normal_forces").Eval(forces_context).copy(),
            loop_closure_error_m(plant, plant_context, gripper) if linkage_hand else 0.0))
    return samples


def _pad_tilt_deg(X_WP) -> float:
    """The pad normal's turn from the stroke axis toward the approach axis [deg]."""
    normal = X_WP.rotation().matrix()[:, 2].copy()
    return math.degrees(math.asin(float(normal[2])))


def _rod_at(height_above_flip_m: float, force_n: float) -> BenchObstacle:
    """The rod across the pads, height_above_flip_m [m] above the closed-form flip height
    where the pads stop on it."""
    theta = linkage.driver_angle(ROD_DIAMETER / 2)
    z = (linkage.PAD_CENTER_OPEN[1] + linkage.pad_travel(theta)
         + linkage.flip_height(theta, force_n) + height_above_flip_m)
    return BenchObstacle("rod", (ROD_DIAMETER, 0.06), z, friction=FRICTIONLESS)


def test_half_opening_is_the_pad_centres_distance_from_the_axis_to_the_bit():
    for theta in np.linspace(-0.1, linkage.DRIVER_RANGE_RAD, 471):
        assert linkage.half_opening(theta) == float(linkage.pad_center(theta)[0])


def test_driver_angle_inverts_half_opening_and_clips_to_the_stroke():
    for theta in np.linspace(0.0, linkage.THETA_PADS_MEET, 47):
        assert linkage.driver_angle(linkage.half_opening(theta)) == pytest.approx(
            theta, abs=1e-9)
    assert linkage.driver_angle(1.0) == pytest.approx(0.0, abs=1e-12)  # beyond open: open
    assert linkage.driver_angle(-1.0) == linkage.THETA_PADS_MEET


def test_joint_coordinates_form_the_published_parallelogram():
    length = lambda p, q: float(np.linalg.norm(p - q))
    assert length(linkage.A, linkage.C) == pytest.approx(0.05715, abs=5e-5)
    assert length(linkage.E, linkage.D) == pytest.approx(length(linkage.A, linkage.C), abs=5e-5)
    assert length(linkage.A, linkage.E) == pytest.approx(0.01905, abs=5e-5)
    assert length(linkage.C, linkage.D) == pytest.approx(length(linkage.A, linkage.E), abs=5e-5)


def test_closed_form_pad_travel_is_the_derived_13_5_mm():
    # Derived from the joint coordinates (Robotiq's Isaac Sim kinematics asset): 5.3-5.4 / 10.2 / 11.8 / 12.9 / 13.5 mm.
    travel = [linkage.pad_travel_at_opening(gap) * 1000 for gap in (0.07, 0.05, 0.04, 0.03, 0.02)]
    np.testing.assert_allclose(travel, [5.43, 10.24, 11.82, 12.91, 13.54], atol=0.05)


def test_pad_centre_follows_the_four_bar_and_the_loops_stay_closed_while_closing():
    samples = _run(gripper_command(0.0, 0.05, 20.0), t_end=2.0)
    errors = [np.linalg.norm(X.translation()[1:] - linkage.pad_center(theta))
              for theta, _, X, _, _ in samples]
    assert max(errors) < 0.5e-3
    assert samples[-1][0] > math.radians(45)  # it closed all the way
    assert max(s[4] for s in samples) < 0.1e-3
    assert max(abs(s[1]) for s in samples) < math.radians(0.1)  # on the pin throughout


@pytest.mark.parametrize("force_n", [50.0, 235.0])
def test_pads_stay_parallel_above_the_flip_height(force_n):
    samples = _run(gripper_command(0.0, 0.05, force_n), obstacle=_rod_at(0.002, force_n))
    _, beta, X_WP, forces, _ = samples[-1]
    assert min(forces) > 0.8 * force_n  # gripping the rod
    assert abs(_pad_tilt_deg(X_WP)) < 1.0
    assert abs(math.degrees(beta)) < 0.2


@pytest.mark.parametrize("force_n", [50.0, 235.0])
def test_contact_below_the_flip_height_lifts_the_pin_and_curls_the_fingertip(force_n):
    samples = _run(gripper_command(0.0, 0.05, force_n), obstacle=_rod_at(-0.002, force_n))
    _, beta, X_WP, forces, _ = samples[-1]
    assert math.degrees(beta) < -3.0  # off the pin
    assert abs(_pad_tilt_deg(X_WP)) > 3.0
    assert min(forces) > 0.5 * force_n


@pytest.mark.parametrize("force_n", [20.0, 100.0, 235.0])
def test_grip_force_at_the_pad_follows_the_force_setting(force_n):
    # A box face covering the pads, its centre where the pads' centres meet a 45 mm object.
    z = linkage.PAD_CENTER_OPEN[1] + linkage.pad_travel_at_opening(0.045)
    samples = _run(gripper_command(0.0, 0.05, force_n),
                   obstacle=BenchObstacle("box", (0.04, 0.045, 0.06), z))
    force_setting = float(ru.force_from_byte(ru.force_byte_from_force(force_n)))
    # The screw holds at least what the capped motor pushed (less the spring's 0.7 N
    # share), at most that plus all of the rotor's kinetic energy at 25 mm/s a finger
    # pressed into the pad against the rigid box (the drive's lumped model with no
    # dissipation: friction and damping only take energy away).
    lossless = grip_rise(stiffness_n_per_m=RIGID_BOX_PAD_STIFFNESS, force_n=force_setting,
                         finger_speed_mps=0.025,
                         lever_m=-linkage.half_opening_rate(linkage.driver_angle(0.0225)))
    assert min(samples[-1][3]) > 0.97 * force_setting
    assert max(samples[-1][3]) < lossless.held_n


def test_fifty_newtons_pushing_a_finger_open_moves_it_less_than_half_a_millimetre():
    samples = _run(gripper_command(0.040, 0.05, 20.0), t_end=2.0, push_n=50.0,
                   push_start_s=1.2)
    before = samples[int(1.15 / 0.005)][2].translation()[1]
    after = max(s[2].translation()[1] for s in samples[int(1.2 / 0.005):])
    assert after - before < 0.5e-3


def test_the_prismatic_hand_yields_to_the_same_push():
    # The check above can fail: the earlier prismatic hand's drive is backdrivable.
    samples = _run(gripper_command(0.040, 0.05, 20.0), t_end=2.0, push_n=50.0,
                   push_start_s=1.2, driver=GripperDriverConfig(model="prismatic"))
    before = samples[int(1.15 / 0.005)][2].translation()[1]
    after = max(s[2].translation()[1] for s in samples[int(1.2 / 0.005):])
    assert after - before > 0.5e-3


@pytest.mark.slow
def test_the_loops_stay_closed_through_a_whole_trial():
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram, MakeSimulator
    from tegrasp_drake.scenario.scenario import LoadScenario
    # The cheap contact: the claim is the loop constraints under the grip's load, which
    # the pads' meshing spreads over other faces but does not change.
    scenario = LoadScenario(overrides=["gripper.model=linkage", *CHEAP_CONTACT],
                            controller="open_loop")
    grasp = MakeGraspDiagram(scenario, log=False)
    simulator = MakeSimulator(grasp.diagram, scenario)
    plant = grasp.station.GetSubsystemByName("plant")
    gripper = plant.GetModelInstanceByName("robotiq_2f85")
    plant_context = plant.GetMyContextFromRoot(simulator.get_context())
    worst = []

    def monitor(context):
        worst.append(loop_closure_error_m(plant, plant_context, gripper))
        return EventStatus.Succeeded()

    simulator.set_monitor(monitor)
    simulator.AdvanceTo(12.5)  # reach, grip, lift, hold, place, release
    assert len(worst) > 10000  # every plant step
    assert max(worst) < 0.1e-3


@pytest.mark.parametrize("opening_m,beta_deg,contact_height_m",
                         [(0.0045, -37.0, 0.009), (0.0045, -32.0, 0.003),
                          (0.010, -30.0, 0.006), (0.020, -20.0, 0.009)])
def test_the_hooked_objects_centre_is_where_the_curled_pads_normal_meets_the_grasp_axis(
        opening_m, beta_deg, contact_height_m):
    # forward through the five-bar: the curled finger's contact point and face normal; the
    # round object touching it there, centred on y = 0, has the radius that normal reaches
    theta, beta = linkage.driver_angle(opening_m / 2), math.radians(beta_deg)
    pose = linkage.finger_pose(theta, beta)
    p = linkage.point_on_follower(theta, beta,
                                  linkage.PAD_CENTER_OPEN + np.array([0.0, contact_height_m]))
    phi = pose.follower_angle
    normal = np.array([-math.cos(phi), -math.sin(phi)])  # the open pose's -y, turned by phi
    radius = p[0] / math.cos(phi)
    centre = p + radius * normal
    assert centre[0] == pytest.approx(0.0, abs=1e-12)
    assert linkage.hooked_object_z(theta, contact_height_m, radius) == pytest.approx(
        centre[1], abs=1e-6)


def test_pads_flat_on_an_object_at_its_width_hook_nothing_beyond_their_centre():
    # 0.1 mm: the joint coordinates close the five-bar's loop to 4 um, so at the width the
    # root lies a fraction of a degree off the pin
    radius = 0.0125
    theta = linkage.driver_angle(radius)
    assert linkage.hooked_object_z(theta, 0.0, radius) == pytest.approx(
        linkage.pad_center(theta)[1], abs=1e-4)
    assert linkage.hooked_object_z(linkage.driver_angle(0.015), 0.0, radius) is None
