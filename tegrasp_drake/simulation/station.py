"""MakeGraspStation: the simulated hardware of the paper (Sec. III-A, Fig. 4) as one Diagram.

A JACO2 on a table, the tactile 2F-85 on its flange (`gripper.model`, gripper_hands.py), the
object on its marker plus its offset, and both pads' taxels and films. Its ports are the hardware
interface's (rig/station_interface.py) plus the ground truth listed there as simulation only.
Gravity is off for the arm and gripper (the JACO2's firmware compensates it). The arm is driven
as the real one (jaco_velocity_drive.py; docs/model.md, "The arm: joint velocities at 100 Hz,
late"), or a carriage carries the gripper (SimulatedStationConfig.arm; carriage.py;
docs/model.md, "The carriage: the arm as a stiff pose source (for sweeps)")."""

import dataclasses
import functools
import math
from typing import Annotated

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import Demultiplexer, MatrixGain
from pydrake.geometry import Meshcat
from pydrake.multibody.plant import MultibodyPlantConfig

from tegrasp_drake.rig.ranges import EVENT_WINDOW_RATE_LOW_HZ, SEED_RANGE, bounded, chosen
from tegrasp_drake.rig import paths
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.arm_kinematics import (ARM_URL, GRASP_HEIGHT_RANGE, R_WG_SIDE_GRASP,
                                              X_FLANGE_GRIPPER, UnreachablePoseError,
                                              make_arm_control_plant, solve_grasp_frame_ik)
from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.rig.jaco_velocity_tracker import JacoVelocityTrackerConfig
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.robotiq.dimensions import HALF_STROKE
from tegrasp_drake.simulation.carriage import (AddCarriage, ArmGraspFrameKinematics, Carriage,
                                               EndpointImpedance, carriage_positions)
from tegrasp_drake.simulation.carriage_systems import CarriageCommand, CarriageWristWrench
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.simulation.jaco_velocity_drive import AddJacoVelocityDrive
from tegrasp_drake.simulation.gripper_hands import (LinkageHand, actuated_state_selector,
                                                    add_gripper_model,
                                                    configure_drive, gripper_hand,
                                                    set_pad_contact)
from tegrasp_drake.simulation.linkage_pad_statics import JOINT_FORCES, LinkagePadStatics
from tegrasp_drake.simulation.pad_normal_forces import PadNormalForces
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig, pad_refinement_for
from tegrasp_drake.simulation.object_model import AddObject, object_body
from tegrasp_drake.simulation.capacitive_taxels import AddTaxelTransducer
from tegrasp_drake.simulation.body_force_pulse import BodyForcePulse, DisturbanceConfig
from tegrasp_drake.simulation.pad_accelerometers import AddPadAccelerometers
from tegrasp_drake.simulation.pad_slip_vibration import PadSlipVibration
from tegrasp_drake.simulation.film_chain import AddPadFilms
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig,
                                                         MakeSimRobotiqDriver)
from tegrasp_drake.simulation.station_visualization import (AddStationVisualization,
                                                           grasp_camera_pose)
from tegrasp_drake.simulation.table_model import AddTable
from tegrasp_drake.simulation.tactile_pads import PadGeometry, TactilePads, TactileSensorConfig
from tegrasp_drake.rig.api_boundary import public_api, public_dataclass



@public_dataclass
@dataclasses.dataclass
class ArmDriverConfig:
    """The simulated JACO2: its joint-velocity command path and joint servos
    (jaco_velocity_drive.py gives each setting's source); the firmware compensates gravity."""
    # N m/rad, the joint servos' stiffness (the plant's PD). Low end: the hand's give to a
    # contact scales as 1 / gain, 2.1 mm while the box is lifted at 400 N m/rad
    # (docs/model.md, "The arm"); at a tenth it gives 2 cm, an arm no longer servoed to its pose.
    position_gain: float = bounded(400.0, low=40.0, high=1e5, unit="N m/rad",
                                   why="below 40 the hand gives centimetres to a contact")
    damping_gain: float = bounded(40.0, low=0.0, high=1e4, unit="N m s/rad")
    # The grasp frame in world at t = 0; 3 cm behind and 9 cm above the grasp: further back,
    # the Jaco nears its wrist singularity.
    initial_gripper_xyz: list[float] = bounded(
        default_factory=lambda: [0.69, 0.0, 0.145], low=-0.9, high=0.9, unit="m", length=3,
        why="within the JACO2's 0.9 m reach, Kinova JACO2 specifications")
    # The start pose's repeatability: G starts off initial_gripper_xyz by an offset drawn
    # uniformly on +-start_position_bound_m along each world axis from the scenario's seed
    # (start_offset_m), while the controller plans from initial_gripper_xyz, as a robot sent
    # to its start pose believes it is there; 0, the default, starts it there exactly. The
    # plausible range: docs/model.md, "What was guessed".
    start_position_bound_m: float = bounded(
        0.0, low=0.0, high=0.02, unit="m",
        why="an arm's start pose repeats to millimetres; 2 cm is beyond any working arm's")
    # Period [s] of the Cartesian controller (differential IK) that makes arm.desired_state.
    control_period_s: float = bounded(0.005, low=0.0, low_open=True, high=0.1, unit="s",
                                      why="ten periods of the JACO2's 100 Hz commands at most")
    # The host's joint-velocity commands: rate [Hz], latency [s] (a whole number of plant steps).
    # Low end: the commands carry the reaction to a tactile event, so they come at least as
    # often as the slowest tactile sampling the event windows allow (EVENT_WINDOW_RATE_LOW_HZ).
    command_rate_hz: float = bounded(100.0, low=EVENT_WINDOW_RATE_LOW_HZ, high=1000.0,
                                     unit="Hz",
                                     why="the JACO2 takes 100 Hz, Kinova kinova-ros README; "
                                         "faster fills its buffer; at least as often as the "
                                         "slowest tactile sampling, 16 Hz")
    command_latency_s: float = bounded(0.010, low=0.0, low_open=True, high=0.1, unit="s",
                                       why="the JACO2's is about 0.01, plausible 0.005-0.03; "
                                           "0.1 s is ten commands queued",
                                       below="must be a whole number of plant steps, at least "
                                             "one, e.g. 0.01 [s] (the JACO2's is about 0.01)")
    # Turns arm.desired_state into those commands (on hardware: the hardware config's arm.tracker)
    tracker: JacoVelocityTrackerConfig = dataclasses.field(
        default_factory=JacoVelocityTrackerConfig)


ARM_MOUNTS = ("jaco2", "carriage")


@public_dataclass
@dataclasses.dataclass
class SimulatedStationConfig:
    """The simulated station (MakeGraspStation); its other settings are the scenario's sections.

    arm: what carries the gripper: `jaco2` (default, for demos and hardware twins), the JACO2 on
    the plant's PD; `carriage` (for sweeps), a six-joint Cartesian carriage with the arm's
    end-point impedance at the grasp pose (simulation/carriage.py), with the same arm ports."""
    arm: str = chosen("jaco2", names=ARM_MOUNTS, why="the JACO2 arm, or the Cartesian carriage "
                                                     "with the arm's end-point impedance, for "
                                                     "sweeps")

    def uses_carriage(self) -> bool:
        return self.arm == "carriage"


def object_pose_on_table(expected_object_xy, object_offset, object_yaw_deg: float
                         ) -> RigidTransform:
    """X_WO on the marker `expected_object_xy` [m] plus `object_offset` [m], yawed [deg]."""
    x, y = np.add(expected_object_xy, object_offset)
    return RigidTransform(RollPitchYaw(0, 0, math.radians(object_yaw_deg)), [x, y, 0.0])


def initial_arm_positions(arm: ArmDriverConfig,
                          start_offset=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Joint angles [rad] that put G at arm.initial_gripper_xyz plus `start_offset` [m,
    world] (none: where the controller plans from), side-grasp orientation; ConfigError
    naming arm.initial_gripper_xyz when the arm cannot reach it (start_pose_problem)."""
    problem = start_pose_problem(arm)
    if problem is not None:
        field, words, value = problem
        raise ConfigError(f"field 'arm.{field}' {words}, got {value}")
    return _start_positions(_start_key(arm, start_offset)).copy()


def start_pose_problem(arm: ArmDriverConfig) -> tuple[str, str, list] | None:
    """(field, what it must be, value) when no arm configuration puts G at
    arm.initial_gripper_xyz in the side grasp's orientation, else None (the IK is solved once
    per start)."""
    try:
        _start_positions(_start_key(arm))
    except UnreachablePoseError:
        return ("initial_gripper_xyz", "must be a point the JACO2 reaches in the side grasp's "
                "orientation (e.g. the default [0.69, 0.0, 0.145] m, in front of the arm)",
                list(arm.initial_gripper_xyz))
    return None


def _start_key(arm: ArmDriverConfig, start_offset=(0.0, 0.0, 0.0)) -> tuple[float, ...]:
    return tuple(float(v) for v in np.add(arm.initial_gripper_xyz, start_offset))


@functools.lru_cache(maxsize=32)
def _start_positions(xyz: tuple[float, ...]) -> np.ndarray:
    return solve_grasp_frame_ik(make_arm_control_plant(), RigidTransform(R_WG_SIDE_GRASP, xyz))


_START_POSE_STREAM = 7101  # separates the start pose's draw from other streams of the seed


def start_offset_m(arm: ArmDriverConfig, random_seed: int) -> np.ndarray:
    """Where G starts off arm.initial_gripper_xyz [m, world]: uniform on
    +-arm.start_position_bound_m along x, y and z, drawn from `random_seed`; zeros at 0."""
    bound = arm.start_position_bound_m
    if bound == 0.0:
        return np.zeros(3)
    return np.random.default_rng([random_seed, _START_POSE_STREAM]).uniform(-bound, bound, 3)


def set_pd_gains(plant, instance, kp, kd):
    # GetJointActuatorIndices(instance) is empty before Finalize(): walk all actuators.
    actuators = [plant.get_joint_actuator(JointActuatorIndex(i))
                 for i in range(plant.num_actuators())]
    for actuator in actuators:
        if actuator.model_instance() == instance:
            actuator.set_controller_gains(PdControllerGains(p=kp, d=kd))


def pad_geometries(plant, scene_graph, gripper) -> dict:
    """{finger name: PadGeometry} of the gripper's two pads."""
    inspector = scene_graph.model_inspector()
    pads = {}
    for finger in FINGER_NAMES:
        body = plant.GetBodyByName(f"{finger}_finger", gripper)
        (geometry_id,) = [g for g in plant.GetCollisionGeometriesForBody(body)
                          if inspector.GetName(g).endswith("pad")]
        frame = plant.GetFrameByName(f"{finger}_pad", gripper)
        pads[finger] = PadGeometry(geometry_id, body.index(),
                                   frame.GetFixedPoseInBodyFrame())
    return pads


def _add_slip_vibration(builder, plant, pads, body, taxels, config: VibrationSensorConfig):
    """The pads' texture vibration under slip, or None when the texture is switched off."""
    if config.slip_texture_height_m <= 0.0:
        return None
    slip = builder.AddNamedSystem("pad_slip_vibration", PadSlipVibration(
        pads=pads, object_body_index=body.index(), config=config))
    builder.Connect(plant.get_body_poses_output_port(), slip.GetInputPort("body_poses"))
    builder.Connect(plant.get_body_spatial_velocities_output_port(),
                    slip.GetInputPort("body_spatial_velocities"))
    builder.Connect(taxels.GetOutputPort("true_taxel_forces"),
                    slip.GetInputPort("true_taxel_forces"))
    return slip


def AddTactileSensors(builder, *, plant, scene_graph, gripper, object_body,
                      tactile: TactileSensorConfig, vibration: VibrationSensorConfig,
                      gripper_model: str, random_seed: int, drive_rates=()):
    """(TactilePads, films' Diagram) of both pads on the finalized `plant`: taxels, slip texture
    and films (the linkage's pad forces from `vibration.pad_force_source`), or with the
    accelerometer transducer PadAccelerometers and no texture. `drive_rates`:
    (DriveVibrationConfig, joint-rate port) of the drives the films feel (drive_vibration.py)."""
    pads = pad_geometries(plant, scene_graph, gripper)
    taxels = builder.AddNamedSystem(
        "tactile_pads", TactilePads(pads=pads, config=tactile, seed=random_seed))
    builder.Connect(plant.get_contact_results_output_port(),
                    taxels.GetInputPort("contact_results"))
    builder.Connect(plant.get_body_poses_output_port(), taxels.GetInputPort("body_poses"))
    if vibration.transducer == "accelerometer":
        return taxels, AddPadAccelerometers(builder, plant=plant, pads=pads, config=vibration)
    slip = _add_slip_vibration(builder, plant, pads, object_body, taxels, vibration)
    pad_forces = pad_statics = None  # the prismatic fingers' joints move along the normals
    if isinstance(gripper_hand(gripper_model), LinkageHand):
        if vibration.pad_force_source == JOINT_FORCES:
            pad_statics = LinkagePadStatics(plant, gripper)
        else:
            pad_forces = builder.AddNamedSystem("pad_normal_forces",
                                                PadNormalForces(plant=plant, pads=pads))
            builder.Connect(plant.get_contact_results_output_port(),
                            pad_forces.GetInputPort("contact_results"))
            builder.Connect(plant.get_body_poses_output_port(),
                            pad_forces.GetInputPort("body_poses"))
    films = AddPadFilms(builder, plant=plant, pads=pads, gripper=gripper, config=vibration,
                        pad_modulus_pa=tactile.pad_modulus_pa, slip_vibration=slip,
                        pad_forces=pad_forces, pad_statics=pad_statics, drive_rates=drive_rates)
    return taxels, films


def _drive_rates(builder, *, hand, selector, arm_velocity, vibration: VibrationSensorConfig):
    """[(DriveVibrationConfig, rate port)] the films feel: the gripper's half-opening rate [m/s]
    (lever at mid-stroke) and the arm's joint rates [rad/s]."""
    if vibration.transducer != "film":
        return []
    rates = [(vibration.arm_drive, arm_velocity)] if vibration.arm_drive.enabled() else []
    if vibration.gripper_drive.enabled():
        lever = abs(hand.half_opening_rate(hand.actuated(HALF_STROKE / 2)))
        finger_rate = builder.AddNamedSystem("gripper_half_opening_rate",
                                             MatrixGain(np.array([[0.0, lever]])))
        builder.Connect(selector.get_output_port(), finger_rate.get_input_port())
        rates.insert(0, (vibration.gripper_drive, finger_rate.get_output_port()))
    return rates


def _add_disturbance(builder, plant, body, config: DisturbanceConfig):
    """The hit on the object (`config`), if it has one."""
    if config.hit_time_s < 0.0:
        return
    pulse = builder.AddNamedSystem("object_force_pulse",
                                   BodyForcePulse.object_hit(body_index=body.index(),
                                                             config=config))
    builder.Connect(pulse.get_output_port(), plant.get_applied_spatial_force_input_port())


@dataclasses.dataclass
class StationPlant:
    """The station's plant, SceneGraph and model instances (`arm`: the carriage's, if any)."""
    plant: object
    scene_graph: object
    arm: object
    gripper: object
    object_instance: object
    carriage: Carriage | None = None
    carriage_weld: object = None  # the carriage-gripper weld joint
    initial_arm_positions: np.ndarray | None = None  # the arm's joints at t = 0 [rad]


def side_grasp_pose(xy, height: float) -> RigidTransform:
    """X_WG of the side grasp over the point `xy` [m, world] at `height` [m]."""
    return RigidTransform(R_WG_SIDE_GRASP, [xy[0], xy[1], height])


def side_grasp_problem(xy, height: float) -> str | None:
    """Why no arm configuration puts G in the side grasp over `xy` [m, world] at `height` [m]
    (the pose the carriage's impedance is taken at), else None (the IK solved once a pose)."""
    try:
        _start_positions((float(xy[0]), float(xy[1]), float(height)))
    except UnreachablePoseError as error:
        return str(error)
    return None


def AddStationPlant(builder, *, plant_config, arm: ArmDriverConfig,
                    gripper: GripperDriverConfig, object: ObjectConfig,
                    X_WO: RigidTransform, pad_modulus_pa: float,
                    random_seed: Annotated[int, SEED_RANGE],
                    carriage: EndpointImpedance | None = None,
                    contact_geometry: ContactGeometryConfig | None = None) -> StationPlant:
    """Adds the station's plant (`plant_config`) to `builder`: the arm at its start pose
    (off it as arm.start_position_bound_m draws from `random_seed`), or with `carriage` the
    gripper on a Cartesian carriage of that impedance; the gripper of `gripper.model` (PD
    gains, no gravity), its pads of gripper.pad_friction and modulus `pad_modulus_pa` [Pa]
    (tactile.pad_modulus_pa), the table and `object` at X_WO meshed as `contact_geometry`
    says (default: the reference geometry), finalized."""
    arm_config, gripper_config, impedance = arm, gripper, carriage
    plant, scene_graph = AddMultibodyPlant(plant_config, builder)
    parser = paths.make_parser(plant)
    carriage = None
    if impedance is not None:
        carriage = AddCarriage(plant, impedance)
        arm = carriage.instance
    else:
        (arm,) = parser.AddModels(url=ARM_URL)
        plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", arm))
    hand = gripper_hand(gripper_config.model)
    gripper = add_gripper_model(parser, hand, pad_refinement_for(
        contact_geometry or ContactGeometryConfig(), gripper_config.model, object.shape))
    if carriage is None:
        weld = plant.WeldFrames(plant.GetFrameByName("flange", arm),
                                plant.GetFrameByName("base", gripper), X_FLANGE_GRIPPER)
    else:
        weld = plant.WeldFrames(carriage.end_body.body_frame(),
                                plant.GetFrameByName("grasp_frame", gripper),
                                RigidTransform(R_WG_SIDE_GRASP))
    AddTable(parser, contact_geometry)
    obj = AddObject(parser, object, contact_geometry)
    plant.set_gravity_enabled(arm, False)
    plant.set_gravity_enabled(gripper, False)
    if carriage is None:
        set_pd_gains(plant, arm, arm_config.position_gain, arm_config.damping_gain)
    configure_drive(plant, gripper, hand, gripper_config)
    set_pad_contact(plant, scene_graph, gripper, friction=gripper_config.pad_friction,
                    modulus_pa=pad_modulus_pa)
    plant.Finalize()

    q_arm = initial_arm_positions(arm_config, start_offset_m(arm_config, random_seed))
    if carriage is None:
        plant.SetDefaultPositions(arm, q_arm)
    else:  # where the arm's start joints put G, so that the first command finds it there
        X_WG_start, _ = ArmGraspFrameKinematics().pose_and_jacobian(q_arm)
        plant.SetDefaultPositions(arm, carriage_positions(carriage, X_WG_start))
    plant.SetDefaultPositions(gripper, hand.default_positions())
    plant.SetDefaultFloatingBaseBodyPose(object_body(plant, obj), X_WO)
    return StationPlant(plant, scene_graph, arm, gripper, obj, carriage, weld, q_arm)


def _add_carriage_arm_ports(builder, parts: StationPlant, arm: ArmDriverConfig,
                            time_step: float) -> None:
    """The arm's ports on the carriage, `carriage.desired_state` and `gripper.wrist_wrench`."""
    plant = parts.plant
    q0 = parts.initial_arm_positions
    command = builder.AddNamedSystem("carriage_command", CarriageCommand(
        parts.carriage, initial_positions=q0, period_s=time_step))
    # The JACO2 mount's velocity drive with an ideal servo: the carriage follows its set-point.
    drive = AddJacoVelocityDrive(builder, arm=arm, time_step=time_step, initial_positions=q0,
                                 position_measured=command.GetOutputPort(
                                     ports.ARM_POSITION_MEASURED))
    builder.ExportInput(drive.desired_state, ports.ARM_DESIRED_STATE)
    builder.Connect(drive.set_point, command.GetInputPort("joint_set_point"))
    builder.Connect(plant.get_state_output_port(parts.arm), command.GetInputPort("carriage_state"))
    builder.ExportOutput(drive.commanded_state, ports.ARM_COMMANDED_STATE)
    builder.Connect(command.GetOutputPort("carriage_desired_state"),
                    plant.get_desired_state_input_port(parts.arm))
    builder.ExportOutput(command.GetOutputPort("carriage_desired_state"),
                         ports.CARRIAGE_DESIRED_STATE)
    for name in (ports.ARM_POSITION_MEASURED, ports.ARM_VELOCITY_MEASURED):
        builder.ExportOutput(command.GetOutputPort(name), name)
    wrench = builder.AddNamedSystem("carriage_wrist_wrench", CarriageWristWrench(
        weld_index=parts.carriage_weld.index(),
        gripper_body_index=plant.GetBodyByName("base", parts.gripper).index()))
    builder.Connect(plant.get_reaction_forces_output_port(),
                    wrench.GetInputPort("reaction_forces"))
    builder.Connect(plant.get_body_poses_output_port(), wrench.GetInputPort("body_poses"))
    builder.Connect(command.GetOutputPort(ports.ARM_POSITION_MEASURED),
                    wrench.GetInputPort(ports.ARM_POSITION_MEASURED))
    builder.ExportOutput(wrench.GetOutputPort(ports.ARM_TORQUE_MEASURED),
                         ports.ARM_TORQUE_MEASURED)
    builder.ExportOutput(wrench.GetOutputPort("wrist_wrench"), ports.GRIPPER_WRIST_WRENCH)


@public_api
def MakeGraspStation(*, plant_config: MultibodyPlantConfig, arm: ArmDriverConfig,
                     gripper: GripperDriverConfig, object: ObjectConfig, X_WO: RigidTransform,
                     tactile: TactileSensorConfig,
                     vibration: VibrationSensorConfig, disturbance: DisturbanceConfig,
                     random_seed: Annotated[int, SEED_RANGE],
                     grasp_height: Annotated[float, GRASP_HEIGHT_RANGE],
                     carriage: EndpointImpedance | None = None,
                     contact_geometry: ContactGeometryConfig | None = None,
                     meshcat: Meshcat | None = None):
    """The simulated station Diagram (module docstring) from the scenario's sections, the
    noise seeded by `random_seed`; with `carriage`, a Cartesian carriage of that impedance in
    the arm's place; with `meshcat`, its visualization, the camera at `grasp_height` [m]."""
    builder = DiagramBuilder()
    parts = AddStationPlant(builder, plant_config=plant_config, arm=arm, gripper=gripper,
                            object=object, X_WO=X_WO, pad_modulus_pa=tactile.pad_modulus_pa,
                            random_seed=random_seed, carriage=carriage,
                            contact_geometry=contact_geometry)
    gripper_config = gripper
    plant, scene_graph = parts.plant, parts.scene_graph
    arm_instance, gripper, obj = parts.arm, parts.gripper, parts.object_instance

    if parts.carriage is None:
        # Arm: the desired state goes through the velocity drive to the plant's PD.
        arm_state = builder.AddNamedSystem("arm_state_demux",
                                           Demultiplexer([ports.ARM_JOINTS] * 2))
        builder.Connect(plant.get_state_output_port(arm_instance), arm_state.get_input_port())
        drive = AddJacoVelocityDrive(builder, arm=arm, time_step=plant_config.time_step,
                                     initial_positions=parts.initial_arm_positions,
                                     position_measured=arm_state.get_output_port(0))
        builder.ExportInput(drive.desired_state, ports.ARM_DESIRED_STATE)
        builder.Connect(drive.set_point, plant.get_desired_state_input_port(arm_instance))
        builder.ExportOutput(drive.commanded_state, ports.ARM_COMMANDED_STATE)
        builder.ExportOutput(drive.set_point, ports.ARM_SERVO_SET_POINT)
        builder.ExportOutput(arm_state.get_output_port(0), ports.ARM_POSITION_MEASURED)
        builder.ExportOutput(arm_state.get_output_port(1), ports.ARM_VELOCITY_MEASURED)
        arm_velocity = arm_state.get_output_port(1)
        builder.ExportOutput(plant.get_net_actuation_output_port(arm_instance),
                             ports.ARM_TORQUE_MEASURED)
    else:
        _add_carriage_arm_ports(builder, parts, arm, plant_config.time_step)
        arm_velocity = builder.GetSubsystemByName("carriage_command").GetOutputPort(
            ports.ARM_VELOCITY_MEASURED)

    # Gripper: the simulated 2F-85 controller.
    driver = builder.AddNamedSystem("gripper_driver", MakeSimRobotiqDriver(
        config=gripper_config, time_step=plant.time_step()))
    selector = builder.AddNamedSystem("gripper_actuated_state", actuated_state_selector(
        plant, gripper, gripper_hand(gripper_config.model)))
    builder.Connect(plant.get_state_output_port(gripper), selector.get_input_port())
    builder.Connect(selector.get_output_port(), driver.GetInputPort("finger_state"))
    builder.ExportOutput(plant.get_state_output_port(gripper), ports.GRIPPER_STATE)
    builder.Connect(driver.GetOutputPort("desired_state"),
                    plant.get_desired_state_input_port(gripper))
    builder.ExportInput(driver.GetInputPort("command"), ports.GRIPPER_COMMAND)
    builder.ExportOutput(driver.GetOutputPort("status"), ports.GRIPPER_STATUS)
    builder.ExportOutput(driver.GetOutputPort("desired_state"),
                         ports.GRIPPER_PLANT_DESIRED_STATE)

    # Tactile pads: taxels and vibration films.
    taxels, films = AddTactileSensors(builder, plant=plant, scene_graph=scene_graph,
                                      gripper=gripper, object_body=object_body(plant, obj),
                                      tactile=tactile, vibration=vibration,
                                      gripper_model=gripper_config.model,
                                      random_seed=random_seed, drive_rates=_drive_rates(
                                          builder, hand=gripper_hand(gripper_config.model),
                                          selector=selector, arm_velocity=arm_velocity,
                                          vibration=vibration))
    readings = AddTaxelTransducer(builder, taxels=taxels, tactile_config=tactile)
    for finger in FINGER_NAMES:
        builder.ExportOutput(readings.GetOutputPort(f"{finger}_taxel_forces"),
                             ports.taxel_forces(finger))
        builder.ExportOutput(films.GetOutputPort(f"{finger}_pad_vibration"),
                             ports.pad_acceleration(finger))
    builder.ExportOutput(taxels.GetOutputPort("true_taxel_forces"), ports.TRUE_TAXEL_FORCES)

    _add_disturbance(builder, plant, object_body(plant, obj), disturbance)

    # Ground truth for evaluation.
    builder.ExportOutput(plant.get_state_output_port(obj), ports.OBJECT_STATE)
    builder.ExportOutput(plant.get_contact_results_output_port(), ports.CONTACT_RESULTS)
    builder.ExportOutput(plant.get_body_poses_output_port(), ports.BODY_POSES)
    builder.ExportOutput(scene_graph.get_query_output_port(), ports.QUERY_OBJECT)

    if meshcat is not None:  # the scene, contact forces, taxel forces; a framed camera
        AddStationVisualization(builder, plant=plant, scene_graph=scene_graph, taxels=taxels,
                                pads=pad_geometries(plant, scene_graph, gripper),
                                meshcat=meshcat,
                                camera=grasp_camera_pose(X_WO.translation(), grasp_height))
    diagram = builder.Build()
    diagram.set_name("grasp_station")
    ports.declare_sample_rates(diagram, (tactile.sample_rate_hz, vibration.sample_rate_hz))
    return diagram
