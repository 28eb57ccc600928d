"""The linkage fingers' pad normal forces from the joints' generalized contact forces
(simulation/linkage_pad_statics.py): against a known force through the plant's own
Jacobian, against PadNormalForces' walk over the contact results on the gripper bench, and
the films on them in the station (vibration.pad_force_source)."""

import numpy as np
import pytest
from pydrake.common import RandomGenerator
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import JacobianWrtVariable
from pydrake.symbolic import Variable
from pydrake.systems.analysis import Simulator

from tegrasp_drake.control.scripted_grasp import gripper_command
from tegrasp_drake.rig import paths
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.scenario import MakeSimulatedStation
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.simulation.gripper_bench import BenchObstacle, MakeGripperBench
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.simulation.linkage_pad_statics import LinkagePadStatics
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.simulation.station import initial_arm_positions

ROD_DIAMETER = 0.030  # m: the pads stop on it at a 30 mm opening
GRIP_FORCE_N = 40.0
TIME_STEP_S = 1e-3  # the bench plant's step


def _linkage_plant():
    plant = MultibodyPlant(time_step=1e-3)
    (gripper,) = paths.make_parser(plant).AddModels(url=gripper_hand("linkage").url)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper))
    plant.Finalize()
    return plant, gripper


def test_a_force_on_the_pad_reads_as_its_normal_component_in_any_pose():
    # tau = J^T f of a force f at a point of the follower, by the plant's own Jacobian: the
    # statics must give back f's component along the pad's outward normal (the pad frame's
    # -z), on both (mirrored) fingers, with the coupler on and off its pin and the follower
    # turned, whatever the point and however much of f lies along the pad or out of the
    # finger's plane. Both are exact, but the model file writes the pad frame's rpy to 9
    # digits, which tilts the right pad's normal 4e-9 rad out of the finger's plane, where
    # no joint sees a force: they agree to 1e-8 of the force.
    plant, gripper = _linkage_plant()
    context = plant.CreateDefaultContext()
    statics = LinkagePadStatics(plant, gripper)
    rng = np.random.default_rng(600)
    for _ in range(20):
        for finger in FINGER_NAMES:
            for link, low, high in (("driver", 0.0, 0.8), ("coupler", -0.6, 0.0),
                                    ("follower", -0.5, 0.5), ("spring_link", -0.5, 0.5)):
                plant.GetJointByName(f"{finger}_{link}_joint", gripper).set_angle(
                    context, rng.uniform(low, high))
        tau = np.zeros(plant.num_velocities())
        expected, scale = [], 0.0
        for finger in FINGER_NAMES:
            pad = plant.GetFrameByName(f"{finger}_pad", gripper)
            p_PQ = np.array([rng.uniform(-0.01, 0.01), rng.uniform(-0.012, 0.012), 0.0])
            f_W = rng.uniform(-30.0, 30.0, 3)
            J = plant.CalcJacobianTranslationalVelocity(
                context, JacobianWrtVariable.kV, pad, p_PQ, plant.world_frame(),
                plant.world_frame())
            tau += J.T @ f_W
            X_WP = pad.CalcPoseInWorld(context)
            expected.append(float(f_W @ -X_WP.rotation().matrix()[:, 2]))
            scale = max(scale, float(np.linalg.norm(f_W)))
        state = plant.GetPositionsAndVelocities(context, gripper)
        forces = statics.normal_forces(plant.GetVelocitiesFromArray(gripper, tau).tolist(),
                                       state.tolist())
        assert forces == pytest.approx(expected, abs=1e-8 * scale)


def _bench_forces(obstacle: BenchObstacle, t_end: float = 1.6, sample_s: float = 0.01):
    """[(PadNormalForces' output, the statics' forces, the chains' fastest joint speed
    [rad/s])] every sample_s [s] of the bench closing on `obstacle` at GRIP_FORCE_N."""
    bench = MakeGripperBench(command=gripper_command(0.0, 0.05, GRIP_FORCE_N),
                             obstacle=obstacle)
    plant, gripper = bench.plant, bench.gripper
    statics = LinkagePadStatics(plant, gripper)
    simulator = Simulator(bench.diagram)
    context = simulator.get_mutable_context()
    plant_context = plant.GetMyContextFromRoot(context)
    forces_context = bench.pad_forces.GetMyContextFromRoot(context)
    samples = []
    for k in range(1, int(round(t_end / sample_s)) + 1):
        simulator.AdvanceTo(k * sample_s)
        tau = plant.get_generalized_contact_forces_output_port(gripper).Eval(plant_context)
        state = plant.get_state_output_port(gripper).Eval(plant_context)
        samples.append((
            bench.pad_forces.GetOutputPort("pad_normal_forces").Eval(forces_context).copy(),
            np.array(statics.normal_forces(tau.tolist(), state.tolist())),
            float(np.abs(plant.GetVelocities(plant_context, gripper)).max())))
    return samples


@pytest.mark.parametrize("obstacle", [
    BenchObstacle("box", (0.04, 0.045, 0.06), 0.13),  # a parallel grasp, pads on the pin
    # a rod 12 mm below the pad centres where they stop: the fingertips curl (B off its pin)
    BenchObstacle("rod", (ROD_DIAMETER, 0.06),
                  linkage.PAD_CENTER_OPEN[1] + linkage.pad_travel(
                      linkage.driver_angle(ROD_DIAMETER / 2)) - 0.012)],
    ids=["box", "rod_below_flip"])
def test_the_statics_give_the_contact_results_walks_pad_forces_on_the_bench(obstacle):
    # The same contact forces, summed from the contact results in Python or projected on the
    # joints by the plant and solved back here. The plant projected them at the step's
    # start and both read the links where the step ended, so they differ to first order in
    # the links' turn over the step, delta = (fastest joint speed) x dt: by at most
    # delta |F| (the lever arms turn by delta; their ratios here are below 1), and to
    # round-off when the fingers are still, through the touch, the squeeze and the hold.
    samples = _bench_forces(obstacle)
    touching = [walk for walk, _, _ in samples if walk.min() > 1.0]
    assert len(touching) >= 20  # both pads hold the obstacle for 0.2 s or more
    for walk, statics, joint_speed in samples:
        scale = float(np.abs(walk).max())
        assert statics == pytest.approx(walk, abs=scale * (joint_speed * TIME_STEP_S + 1e-9)
                                        + 1e-9)


def _station_films(pad_force_source: str, close_at_s=0.3, until_s=2.2):
    """(station, both films' samples on z every 1 ms [m/s^2]) of the linkage station, its
    pads open around the box, closing at 30 N from close_at_s [s]; films' noise seed 600."""
    scenario = LoadScenario(overrides=["arm.initial_gripper_xyz=[0.72, 0.0, 0.055]",
                                       f"vibration.pad_force_source={pad_force_source}"])
    station = MakeSimulatedStation(scenario)
    context = station.CreateDefaultContext()
    station.SetRandomContext(context, RandomGenerator(600))
    station.GetInputPort(ports.ARM_DESIRED_STATE).FixValue(
        context, np.concatenate([initial_arm_positions(scenario.arm), np.zeros(6)]))
    command = station.GetInputPort(ports.GRIPPER_COMMAND)
    command.FixValue(context, gripper_command(ru.STROKE_M, 0.05, 30.0))
    simulator = Simulator(station, context)
    samples = []
    for k in range(1, int(round(until_s / TIME_STEP_S)) + 1):
        if k == int(round(close_at_s / TIME_STEP_S)):
            command.FixValue(context, gripper_command(0.0, 0.05, 30.0))
        simulator.AdvanceTo(k * TIME_STEP_S)
        samples.append([station.GetOutputPort(ports.pad_acceleration(f)).Eval(context)[2]
                        for f in FINGER_NAMES])
    return station, np.array(samples)


def test_films_on_the_joints_forces_read_as_on_the_contact_results_walk():
    # The station with vibration.pad_force_source joint_forces has no PadNormalForces; its
    # films read the gripper's generalized contact forces and state. Through the touch (a
    # film peak near 1,000 m/s^2), the squeeze and the hold, its samples differ from the
    # contact-results walk's by less than a tenth of the film's own noise per sample
    # (0.05 m/s^2): the two pad forces differ by a step's turn of the links at most.
    walk_station, walk = _station_films("contact_results")
    joint_station, joints = _station_films("joint_forces")
    names = lambda station: {s.get_name() for s in station.GetSystems()}
    assert "pad_normal_forces" in names(walk_station)
    assert "pad_normal_forces" not in names(joint_station)
    films = joint_station.GetSubsystemByName("pad_films")
    assert films.HasInputPort("gripper_state")
    assert np.abs(walk).max() > 100.0  # the touch rang the films
    assert np.abs(joints - walk).max() < 0.1 * VibrationSensorConfig().noise_std_mps2


def test_the_symbolic_statics_evaluate_to_the_float_ones():
    # normal_force_expressions is the same formula on pydrake.symbolic variables; its
    # evaluation may round differently (symbolic sums reorder), so to round-off.
    plant, gripper = _linkage_plant()
    statics = LinkagePadStatics(plant, gripper)
    tau = [Variable(f"tau_{i}") for i in range(statics.velocities)]
    state = [Variable(f"x_{i}") for i in range(statics.states)]
    expressions = statics.normal_force_expressions(tau, state)
    rng = np.random.default_rng(601)
    for _ in range(20):
        tau_values = rng.uniform(-2.0, 2.0, statics.velocities).tolist()
        state_values = rng.uniform(-0.6, 0.8, statics.states).tolist()
        environment = dict(zip(tau + state, tau_values + state_values))
        floats = statics.normal_forces(tau_values, state_values)
        for expression, value in zip(expressions, floats):
            assert expression.Evaluate(environment) == pytest.approx(value, rel=1e-12, abs=1e-12)
