"""MakeGraspStation: the simulated hardware of the paper (Sec. III-A, Fig. 4) as one Diagram.

A JACO2 arm on a table, the tactile 2F-85-like gripper on its flange, the object on its
marker (plus its offset), and the sensors: both pads' taxel arrays and vibration
films. The exported ports are those of the hardware interface, so a controller cannot tell
the two apart:

  inputs:  arm.desired_state (12: q [rad], v [rad/s]), gripper.command (3: rPR, rSP, rFR)
  outputs: arm.position_measured (6), arm.velocity_measured (6), arm.torque_measured (6),
           gripper.status (8, robotiq_units order),
           tactile.left_taxel_forces (12, N), tactile.right_taxel_forces (12, N),
           tactile.left_pad_acceleration (3), tactile.right_pad_acceleration (3): each pad's
           PVDF film in acceleration-equivalent units [m/s^2], on the pad normal (z)
  simulation only (evaluation): object.state (13: quaternion wxyz, p_WO, w_WO, v_WO),
           tactile.true_taxel_forces (24, N), contact_results, body_poses, query_object,
           gripper.plant_desired_state (2: the simulated 2F-85 controller's set-point of
           the hand's actuated joint, position and rate, for the plant's PD),
           gripper.state (the gripper model instance's joint positions and velocities)

The hand is `gripper.model` (gripper_hands.py): the 2F-85's finger linkage (the
default) or the earlier prismatic fingers.

The Jaco's firmware compensates gravity, so gravity is off for the arm and gripper bodies and
their joints track `arm.desired_state` with the plant's implicit PD.
"""

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import Demultiplexer

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import (ARM_URL, R_WG_SIDE_GRASP, X_FLANGE_GRIPPER,
                                              make_arm_control_plant, solve_grasp_frame_ik)
from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.simulation.gripper_hands import (LinkageHand, actuated_state_selector,
                                                    gripper_hand)
from tegrasp_drake.simulation.pad_normal_forces import PadNormalForces
from tegrasp_drake.simulation.object_model import AddObject, object_body
from tegrasp_drake.simulation.object_force_pulse import DisturbanceConfig, ObjectForcePulse
from tegrasp_drake.simulation.pad_slip_vibration import PadSlipVibration
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig, AddPadFilms
from tegrasp_drake.simulation.sim_robotiq_driver import GripperDriverConfig, SimRobotiqDriver
from tegrasp_drake.simulation.station_visualization import (AddStationVisualization,
                                                           grasp_camera_pose)
from tegrasp_drake.simulation.tactile_pads import PadGeometry, TactilePads, TactileSensorConfig

TABLE_URL = "package://tegrasp/table/table.sdf"
ARM_JOINTS = 6


@dataclasses.dataclass
class ArmDriverConfig:
    """The simulated JACO2 joint controller; the firmware compensates gravity."""
    position_gain: float = 400.0  # N m/rad
    damping_gain: float = 40.0  # N m s/rad
    initial_gripper_xyz: list[float] = dataclasses.field(
        default_factory=lambda: [0.69, 0.0, 0.145])  # m, grasp frame in world at t = 0;
    # 3 cm behind and 9 cm above the grasp: further back, the Jaco nears its wrist singularity
    # Period [s] of the Cartesian controller (differential IK) that makes arm.desired_state;
    # the Jaco's own velocity interface runs at 100 Hz.
    control_period_s: float = 0.005


@dataclasses.dataclass
class SimulatedStationConfig:
    """The simulated station (MakeGraspStation); its settings are the scenario's sections
    (scenario/grasp_diagram.py MakeSimulatedStation hands them over)."""


def object_pose_on_table(expected_object_xy, object_offset, object_yaw_deg: float
                         ) -> RigidTransform:
    """X_WO of an object resting on its marker `expected_object_xy` [m, world] moved by
    `object_offset` [m] and yawed by `object_yaw_deg` [deg]."""
    x, y = np.add(expected_object_xy, object_offset)
    return RigidTransform(RollPitchYaw(0, 0, math.radians(object_yaw_deg)), [x, y, 0.0])


def initial_arm_positions(arm: ArmDriverConfig) -> np.ndarray:
    """Joint angles [rad] that put the grasp frame at the arm's start pose
    (arm.initial_gripper_xyz, side-grasp orientation)."""
    X_WG = RigidTransform(R_WG_SIDE_GRASP, arm.initial_gripper_xyz)
    return solve_grasp_frame_ik(make_arm_control_plant(), X_WG)


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
                      gripper_model: str, random_seed: int):
    """Both pads' taxel arrays (TactilePads, seeded by `random_seed`), the slip texture
    (PadSlipVibration) and the films (PadFilms) of the hand `gripper_model`, connected to
    the finalized `plant`; returns (TactilePads, PadFilms)."""
    pads = pad_geometries(plant, scene_graph, gripper)
    taxels = builder.AddNamedSystem(
        "tactile_pads", TactilePads(pads=pads, config=tactile, seed=random_seed))
    builder.Connect(plant.get_contact_results_output_port(),
                    taxels.GetInputPort("contact_results"))
    builder.Connect(plant.get_body_poses_output_port(), taxels.GetInputPort("body_poses"))
    slip = _add_slip_vibration(builder, plant, pads, object_body, taxels, vibration)
    pad_forces = None
    if isinstance(gripper_hand(gripper_model), LinkageHand):
        pad_forces = builder.AddNamedSystem("pad_normal_forces",
                                            PadNormalForces(plant=plant, pads=pads))
        builder.Connect(plant.get_contact_results_output_port(),
                        pad_forces.GetInputPort("contact_results"))
        builder.Connect(plant.get_body_poses_output_port(), pad_forces.GetInputPort("body_poses"))
    films = AddPadFilms(builder, plant=plant, pads=pads, gripper=gripper,
                        config=vibration, slip_vibration=slip, pad_forces=pad_forces)
    return taxels, films


def _add_disturbance(builder, plant, body, config: DisturbanceConfig):
    """The hit on the object (`config`), if it has one."""
    if config.hit_time_s < 0.0:
        return
    pulse = builder.AddNamedSystem("object_force_pulse",
                                   ObjectForcePulse(body_index=body.index(), config=config))
    builder.Connect(pulse.get_output_port(), plant.get_applied_spatial_force_input_port())


@dataclasses.dataclass
class StationPlant:
    """The station's MultibodyPlant and SceneGraph and its model instances."""
    plant: object
    scene_graph: object
    arm: object
    gripper: object
    object_instance: object


def AddStationPlant(builder, *, plant_config, arm: ArmDriverConfig,
                    gripper: GripperDriverConfig, object: ObjectConfig,
                    X_WO: RigidTransform) -> StationPlant:
    """Adds the station's plant (`plant_config`) to `builder`: the arm at its start pose,
    the gripper of `gripper.model` (PD gains, no gravity), the table and `object` at
    X_WO, finalized. MakeGraspStation builds its sensors on it; the trial benchmark's
    plant-alone floor (benchmarks/plant_floor.py) drives it alone."""
    arm_config, gripper_config = arm, gripper
    plant, scene_graph = AddMultibodyPlant(plant_config, builder)
    parser = paths.make_parser(plant)
    (arm,) = parser.AddModels(url=ARM_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", arm))
    hand = gripper_hand(gripper_config.model)
    (gripper,) = parser.AddModels(url=hand.url)
    plant.WeldFrames(plant.GetFrameByName("flange", arm), plant.GetFrameByName("base", gripper),
                     X_FLANGE_GRIPPER)
    (table,) = parser.AddModels(url=TABLE_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("top", table))
    obj = AddObject(parser, object)
    plant.set_gravity_enabled(arm, False)
    plant.set_gravity_enabled(gripper, False)
    set_pd_gains(plant, arm, arm_config.position_gain, arm_config.damping_gain)
    set_pd_gains(plant, gripper, *hand.pd_gains(gripper_config))
    plant.Finalize()

    plant.SetDefaultPositions(arm, initial_arm_positions(arm_config))
    plant.SetDefaultPositions(gripper, hand.default_positions())
    plant.SetDefaultFloatingBaseBodyPose(object_body(plant, obj), X_WO)
    return StationPlant(plant, scene_graph, arm, gripper, obj)


def MakeGraspStation(*, plant_config, arm: ArmDriverConfig, gripper: GripperDriverConfig,
                     object: ObjectConfig, X_WO: RigidTransform, tactile: TactileSensorConfig,
                     vibration: VibrationSensorConfig, disturbance: DisturbanceConfig,
                     random_seed: int, grasp_height: float, meshcat=None):
    """Builds the simulated station Diagram (see the module docstring) from the sections it
    uses: the plant, arm and gripper configs, the object at X_WO, the taxels' and films'
    configs (their noise seeded by `random_seed`), the hit on the object; with `meshcat`,
    its visualization, the camera on the grasp at `grasp_height` [m] above the table."""
    builder = DiagramBuilder()
    parts = AddStationPlant(builder, plant_config=plant_config, arm=arm, gripper=gripper,
                            object=object, X_WO=X_WO)
    gripper_config = gripper
    plant, scene_graph = parts.plant, parts.scene_graph
    arm_instance, gripper, obj = parts.arm, parts.gripper, parts.object_instance

    # Arm: the desired state goes straight to the plant's PD; measured state is split.
    builder.ExportInput(plant.get_desired_state_input_port(arm_instance), "arm.desired_state")
    arm_state = builder.AddNamedSystem("arm_state_demux", Demultiplexer([ARM_JOINTS] * 2))
    builder.Connect(plant.get_state_output_port(arm_instance), arm_state.get_input_port())
    builder.ExportOutput(arm_state.get_output_port(0), "arm.position_measured")
    builder.ExportOutput(arm_state.get_output_port(1), "arm.velocity_measured")
    builder.ExportOutput(plant.get_net_actuation_output_port(arm_instance), "arm.torque_measured")

    # Gripper: the simulated 2F-85 controller.
    driver = builder.AddNamedSystem("gripper_driver", SimRobotiqDriver(config=gripper_config))
    selector = builder.AddNamedSystem("gripper_actuated_state", actuated_state_selector(
        plant, gripper, gripper_hand(gripper_config.model)))
    builder.Connect(plant.get_state_output_port(gripper), selector.get_input_port())
    builder.Connect(selector.get_output_port(), driver.GetInputPort("finger_state"))
    builder.ExportOutput(plant.get_state_output_port(gripper), "gripper.state")
    builder.Connect(driver.GetOutputPort("desired_state"),
                    plant.get_desired_state_input_port(gripper))
    builder.ExportInput(driver.GetInputPort("command"), "gripper.command")
    builder.ExportOutput(driver.GetOutputPort("status"), "gripper.status")
    builder.ExportOutput(driver.GetOutputPort("desired_state"), "gripper.plant_desired_state")

    # Tactile pads: taxels and vibration films.
    taxels, films = AddTactileSensors(builder, plant=plant, scene_graph=scene_graph,
                                      gripper=gripper, object_body=object_body(plant, obj),
                                      tactile=tactile, vibration=vibration,
                                      gripper_model=gripper_config.model,
                                      random_seed=random_seed)
    for finger in FINGER_NAMES:
        builder.ExportOutput(taxels.GetOutputPort(f"{finger}_taxel_forces"),
                             f"tactile.{finger}_taxel_forces")
        builder.ExportOutput(films.GetOutputPort(f"{finger}_pad_vibration"),
                             f"tactile.{finger}_pad_acceleration")
    builder.ExportOutput(taxels.GetOutputPort("true_taxel_forces"), "tactile.true_taxel_forces")

    _add_disturbance(builder, plant, object_body(plant, obj), disturbance)

    # Ground truth for evaluation.
    builder.ExportOutput(plant.get_state_output_port(obj), "object.state")
    builder.ExportOutput(plant.get_contact_results_output_port(), "contact_results")
    builder.ExportOutput(plant.get_body_poses_output_port(), "body_poses")
    builder.ExportOutput(scene_graph.get_query_output_port(), "query_object")

    if meshcat is not None:  # the scene, contact forces, taxel forces; a framed camera
        AddStationVisualization(builder, plant=plant, scene_graph=scene_graph, taxels=taxels,
                                pads=pad_geometries(plant, scene_graph, gripper),
                                meshcat=meshcat,
                                camera=grasp_camera_pose(X_WO.translation(), grasp_height))
    diagram = builder.Build()
    diagram.set_name("grasp_station")
    return diagram
