"""The Cartesian carriage station (simulation/carriage.py, carriage_systems.py): it tracks
a commanded pose as its gains say, its weld measures the weight it carries, the arm's
torque port maps back to that wrench, and a closed-loop trial on it grasps and lifts."""


import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import SpatialInertia, UnitInertia
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.control.finger_strike import grasp_wrench_from_torques
from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.scenario.scenario import LoadScenario, with_controller
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import R_WG_SIDE_GRASP
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.simulation.carriage import (AddCarriage, ArmGraspFrameKinematics,
                                               carriage_positions, carriage_state)
from tegrasp_drake.simulation.carriage_systems import CarriageCommand, CarriageWristWrench
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.scenario import MakeSimulatedStation
from tegrasp_drake.scenario.grasp_diagram import station_carriage
from tegrasp_drake.scenario.scenario import object_pose
from tegrasp_drake.simulation.station import AddStationPlant, initial_arm_positions

GRAVITY = 9.81


def station_plant(builder, scenario):
    """The scenario's station plant (the carriage's when its station says so)."""
    return AddStationPlant(builder, plant_config=scenario.plant_config, arm=scenario.arm,
                           gripper=scenario.gripper, object=scenario.object,
                           X_WO=object_pose(scenario),
                           pad_modulus_pa=scenario.tactile.pad_modulus_pa,
                           random_seed=scenario.random_seed,
                           carriage=station_carriage(scenario))


@pytest.fixture(scope="module")
def scenario():
    return LoadScenario(name="box", overrides=["station.arm=carriage", "random_seed=600"])


def test_an_unknown_arm_is_refused_with_the_choices():
    with pytest.raises(ConfigError, match="station.arm.*'jaco2', 'carriage'"):
        LoadScenario(name="box", overrides=["station.arm=ur5"])


def test_the_carriage_station_keeps_the_arm_ports(scenario):
    station = MakeSimulatedStation(scenario)
    jaco = MakeSimulatedStation(LoadScenario(name="box"))
    for port in ("arm.desired_state",):
        assert station.GetInputPort(port).size() == jaco.GetInputPort(port).size() == 12
    for port in ("arm.position_measured", "arm.velocity_measured", "arm.torque_measured"):
        assert station.GetOutputPort(port).size() == jaco.GetOutputPort(port).size() == 6


def test_the_carriage_starts_where_the_arm_puts_the_grasp_frame(scenario):
    """The arm's commanded start joints, through CarriageCommand's kinematics, are the
    carriage's default positions."""
    station = MakeSimulatedStation(scenario)
    context = station.CreateDefaultContext()
    set_point = station.GetOutputPort("carriage.desired_state").Eval(context)
    X_WG, _ = ArmGraspFrameKinematics().pose_and_jacobian(initial_arm_positions(scenario.arm))
    parts = station_plant(DiagramBuilder(), scenario)
    default = parts.plant.GetDefaultPositions(parts.arm)
    np.testing.assert_allclose(set_point[:6], default, atol=1e-9)
    np.testing.assert_allclose(set_point[6:], 0.0, atol=1e-12)
    np.testing.assert_allclose(X_WG.translation(), scenario.arm.initial_gripper_xyz, atol=1e-6)


def _reported_pose_error(parts, q0, deflection):
    """(position error [m], rotation error [rad], joint move [rad]) between G at the joints
    CarriageCommand reports and G where the carriage has it, deflected by `deflection`
    (actuator order) from its set-point at the joints q0."""
    command = CarriageCommand(parts.carriage, initial_positions=q0, period_s=0.001)
    context = command.CreateDefaultContext()
    command.GetInputPort("joint_set_point").FixValue(context, np.concatenate([q0, np.zeros(6)]))
    moved = command.GetOutputPort("carriage_desired_state").Eval(context)[:6] + deflection
    command.GetInputPort("carriage_state").FixValue(context,
                                                    np.concatenate([moved, np.zeros(6)]))
    q = command.GetOutputPort("arm.position_measured").Eval(context)
    X_WG_reported, _ = ArmGraspFrameKinematics().pose_and_jacobian(q)
    R_WG = RollPitchYaw(moved[5], moved[4], moved[3]).ToRotationMatrix() @ R_WG_SIDE_GRASP
    position_error = np.linalg.norm(X_WG_reported.translation()
                                    - parts.carriage.translation_axes @ moved[:3])
    rotation_error = abs((X_WG_reported.rotation().inverse() @ R_WG).ToAngleAxis().angle())
    return position_error, rotation_error, np.linalg.norm(q - q0)


def test_the_reported_joints_put_the_grasp_frame_where_the_carriage_has_it(scenario):
    """Deflected 1 mm along each axis and 0.2 deg about each, the carriage reports joints
    whose kinematics put G there to second order (the error falls four-fold with half the
    deflection), so the velocity tracker sees the sag it must remove."""
    parts = station_plant(DiagramBuilder(), scenario)
    q0 = initial_arm_positions(scenario.arm)
    deflection = np.array([1e-3, 1e-3, 1e-3] + [np.radians(0.2)] * 3)
    full = _reported_pose_error(parts, q0, deflection)
    half = _reported_pose_error(parts, q0, deflection / 2)
    assert full[2] > 1e-3  # the joints did move
    assert full[0] < 0.05 * np.linalg.norm(deflection[:3])  # 1.7 mm moved
    assert full[1] < 0.05 * np.linalg.norm(deflection[3:])  # 6 mrad turned
    for full_error, half_error in zip(full[:2], half[:2]):
        assert 0.2 < half_error / full_error < 0.3


def _simulate_tracking(scenario, set_point_of_t, duration_s):
    """The carriage station's plant driven by the carriage set-points set_point_of_t(t)
    (positions and rates, actuator order) sampled at 1 ms (first-order hold); returns (times t_k, the set-points at t_k, the carriage's positions
    after the step that began at t_k)."""
    builder = DiagramBuilder()
    parts = station_plant(builder, scenario)
    times = np.arange(0.0, duration_s + 1e-9, 1e-3)
    commanded = np.column_stack([set_point_of_t(t) for t in times])
    source = builder.AddSystem(TrajectorySource(
        PiecewisePolynomial.FirstOrderHold(times, commanded)))
    builder.Connect(source.get_output_port(),
                    parts.plant.get_desired_state_input_port(parts.arm))
    hand = gripper_hand(scenario.gripper.model)
    diagram = builder.Build()
    simulator = Simulator(diagram)
    plant_context = parts.plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    parts.plant.get_desired_state_input_port(parts.gripper).FixValue(
        plant_context, [hand.actuated(hand.half_opening(0.0)), 0.0])
    measured = []
    for t in times[1:]:
        simulator.AdvanceTo(t)
        measured.append(parts.plant.GetPositions(plant_context, parts.arm).copy())
    # A step from t_k to t_k+1 drives toward the set-point sampled at t_k.
    return times[:-1], commanded[:6, :-1], np.array(measured).T, parts


def _linear_pd_positions(M, K, D, dt, set_points, q0):
    """The joint positions after each step of the linear PD model with the plant's implicit
    step: M (v' - v) / dt = K (q_d - q') + D (v_d - v'), q' = q + dt v', the set-point
    (q_d, v_d) held over the step; starting at q0 at rest."""
    n = len(K)
    step = np.linalg.inv(M + dt * np.diag(D) + dt * dt * np.diag(K))
    q, v, out = np.array(q0, dtype=float), np.zeros(n), []
    for q_d, v_d in zip(set_points[:n].T, set_points[n:].T):
        v = step @ (M @ v + dt * K * (q_d - q) + dt * D * v_d)
        q = q + dt * v
        out.append(q.copy())
    return np.array(out).T


def test_the_carriage_tracks_a_smooth_move_as_its_gains_say(scenario):
    """A cosine move of 40 mm back and up in 0.8 s, the commanded rates fed forward: the
    carriage's joints follow the linear PD model of the plant's implicit step
    (_linear_pd_positions: K, D its PD gains, M its block of the mass matrix with the hand
    held rigid), within 2 % of that model's peak tracking error in each joint (measured:
    0.07 % or less where the error is above 1 um).
    The pitch that the hand's offset centre of mass couples in is included. (A turn about
    the fingers' own joint axes, world z here, is left out: the hand's passive finger
    joints lag it, so the carriage feels about half the inertia the rigid model gives.)"""
    start, _ = ArmGraspFrameKinematics().pose_and_jacobian(initial_arm_positions(scenario.arm))
    parts0 = station_plant(DiagramBuilder(), scenario)
    duration, move = 0.8, np.array([-0.04, 0.0, 0.04])

    def profile(t):
        s = 0.5 * (1 - np.cos(np.pi * min(t, duration) / duration))
        s_dot = 0.5 * np.pi / duration * np.sin(np.pi * min(t, duration) / duration)
        X = RigidTransform(start.rotation(), start.translation() + move * s)
        V = np.concatenate([np.zeros(3), move * s_dot])
        return carriage_state(parts0.carriage, X, V)

    times, commanded, measured, parts = _simulate_tracking(scenario, profile, duration + 1.0)
    plant = parts.plant
    dofs = [j.velocity_start() for j in parts.carriage.joints]
    M = plant.CalcMassMatrix(plant.CreateDefaultContext())[np.ix_(dofs, dofs)]
    actuators = [plant.get_joint_actuator(a) for a in plant.GetJointActuatorIndices(parts.arm)]
    K = np.array([a.get_controller_gains().p for a in actuators])
    D = np.array([a.get_controller_gains().d for a in actuators])
    set_points = np.column_stack([profile(t) for t in times])
    model = _linear_pd_positions(M, K, D, times[1] - times[0], set_points, commanded[:, 0])
    peak = np.max(np.abs(model - commanded), axis=1)
    mismatch = np.max(np.abs(measured - model), axis=1)
    assert np.all(mismatch <= 0.02 * peak + 1e-7), (mismatch, peak)
    np.testing.assert_allclose(measured[:, -1], commanded[:, -1], atol=1e-5)


def test_the_carriage_yields_to_a_steady_force_as_its_stiffness_says(scenario):
    """A 20 N push along world y on the hand at G, held: G moves by the carriage's
    compliance times the force, C = E diag(1 / k) E^T (E its prismatic axes)."""
    from pydrake.multibody.math import SpatialForce
    from pydrake.multibody.plant import ExternallyAppliedSpatialForce
    from pydrake.systems.primitives import ConstantValueSource
    from pydrake.common.value import AbstractValue
    builder = DiagramBuilder()
    parts = station_plant(builder, scenario)
    plant = parts.plant
    base = plant.GetBodyByName("base", parts.gripper)
    push = ExternallyAppliedSpatialForce()
    push.body_index = base.index()
    push.p_BoBq_B = plant.GetFrameByName("grasp_frame", parts.gripper) \
        .GetFixedPoseInBodyFrame().translation()
    push.F_Bq_W = SpatialForce(np.zeros(3), [0.0, 20.0, 0.0])
    source = builder.AddSystem(ConstantValueSource(AbstractValue.Make([push])))
    builder.Connect(source.get_output_port(), plant.get_applied_spatial_force_input_port())
    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    q0 = plant.GetPositions(context, parts.arm).copy()
    plant.get_desired_state_input_port(parts.arm).FixValue(context,
                                                           np.concatenate([q0, np.zeros(6)]))
    plant.get_desired_state_input_port(parts.gripper).FixValue(context, [0.0, 0.0])
    simulator.AdvanceTo(1.0)  # ten of the carriage's d / k = 0.1 s time constants
    axes = parts.carriage.translation_axes
    compliance = axes @ np.diag(1.0 / station_carriage(scenario).stiffness[3:]) @ axes.T
    shift = axes @ (plant.GetPositions(context, parts.arm)[:3] - q0[:3])
    np.testing.assert_allclose(shift, compliance @ [0.0, 20.0, 0.0], atol=0.02 * 20.0 *
                               compliance[1, 1])


def _carriage_with_load(scenario, mass_kg, p_GL):
    """A carriage, the hand, and a `mass_kg` point mass welded to the hand at p_GL (in G),
    gravity on the load only; the CarriageWristWrench on the weld; at rest at the start."""
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    carriage = AddCarriage(plant, station_carriage(scenario))
    (gripper,) = paths.make_parser(plant).AddModels(url=gripper_hand("linkage").url)
    weld = plant.WeldFrames(carriage.end_body.body_frame(),
                            plant.GetFrameByName("grasp_frame", gripper),
                            RigidTransform(R_WG_SIDE_GRASP))
    load_instance = plant.AddModelInstance("load")
    load = plant.AddRigidBody("load", load_instance, SpatialInertia(
        mass_kg, np.zeros(3), UnitInertia.SolidSphere(0.01)))
    plant.WeldFrames(plant.GetFrameByName("grasp_frame", gripper), load.body_frame(),
                     RigidTransform(p_GL))
    plant.set_gravity_enabled(gripper, False)
    plant.Finalize()
    X_WG = RigidTransform(R_WG_SIDE_GRASP, scenario.arm.initial_gripper_xyz)
    plant.SetDefaultPositions(carriage.instance, carriage_positions(carriage, X_WG))
    wrench = builder.AddSystem(CarriageWristWrench(
        weld_index=weld.index(), gripper_body_index=plant.GetBodyByName("base",
                                                                        gripper).index()))
    builder.Connect(plant.get_reaction_forces_output_port(),
                    wrench.GetInputPort("reaction_forces"))
    builder.Connect(plant.get_body_poses_output_port(), wrench.GetInputPort("body_poses"))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    root = simulator.get_mutable_context()
    context = plant.GetMyMutableContextFromRoot(root)
    q0 = plant.GetPositions(context, carriage.instance).copy()
    plant.get_desired_state_input_port(carriage.instance).FixValue(
        context, np.concatenate([q0, np.zeros(6)]))
    plant.get_desired_state_input_port(gripper).FixValue(context, [0.0, 0.0])
    wrench.GetInputPort("arm.position_measured").FixValue(
        wrench.GetMyMutableContextFromRoot(root), initial_arm_positions(scenario.arm))
    return simulator, wrench


def test_the_wrist_wrench_is_the_weight_of_a_held_mass_at_rest(scenario):
    """0.5 kg held 3 cm along G's y (world y in the side grasp): the wrench on the arm at G
    is its weight, F = (0, 0, -m g), and the moment r x F about G."""
    mass, p_GL = 0.5, np.array([0.0, 0.03, 0.0])
    simulator, wrench = _carriage_with_load(scenario, mass, p_GL)
    simulator.AdvanceTo(1.0)  # settled: ten of the carriage's time constants
    w = wrench.GetOutputPort("wrist_wrench").Eval(
        wrench.GetMyContextFromRoot(simulator.get_context()))
    weight = np.array([0.0, 0.0, -mass * GRAVITY])
    r_W = R_WG_SIDE_GRASP.matrix() @ p_GL
    np.testing.assert_allclose(w[3:], weight, atol=0.02 * mass * GRAVITY)
    np.testing.assert_allclose(w[:3], np.cross(r_W, weight), atol=0.02 * mass * GRAVITY
                               * np.linalg.norm(p_GL))


def test_the_arm_torques_map_back_to_the_wrist_wrench(scenario):
    """arm.torque_measured on the carriage is -J^T w: the taxel_aware controller's
    estimator (grasp_wrench_from_torques) recovers w."""
    simulator, wrench = _carriage_with_load(scenario, 0.5, np.array([0.0, 0.03, 0.02]))
    simulator.AdvanceTo(0.3)
    context = wrench.GetMyContextFromRoot(simulator.get_context())
    w = wrench.GetOutputPort("wrist_wrench").Eval(context)
    tau = wrench.GetOutputPort("arm.torque_measured").Eval(context)
    _, J = ArmGraspFrameKinematics().pose_and_jacobian(initial_arm_positions(scenario.arm))
    np.testing.assert_allclose(grasp_wrench_from_torques(J, tau), w, atol=1e-9)


@pytest.mark.slow
def test_a_memorized_trial_on_the_carriage_reaches_lift(scenario):
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram, MakeSimulator
    memorized = with_controller(scenario, "memorized")
    grasp = MakeGraspDiagram(memorized, log=False)
    simulator = MakeSimulator(grasp.diagram, memorized)
    simulator.Initialize()
    simulator.AdvanceTo(4.5)  # the ideal grasp loads at about 3.8 s
    assert grasp.controller.current_mode(simulator.get_context()) == Mode.LIFT
