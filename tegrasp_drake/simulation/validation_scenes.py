"""Minimal scenes of the station's contact world, to check it against closed-form mechanics
(docs/model.md, "Validation against closed form"): the station's gripper welded to the world,
the table if asked for and one object, with the scenario's `plant_config` and
`contact_geometry`; the fingers on a force-limited position loop allowed below the 2F-85's
20 N so that slip can be provoked."""

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, EventStatus, LeafSystem

from tegrasp_drake.robotiq.dimensions import HALF_STROKE, PAD_CENTER_Z
from tegrasp_drake.modelgen.table_sdf import EXPECTED_XY
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import GRIPPER_URL, R_WG_SIDE_GRASP
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig
from tegrasp_drake.simulation.object_model import AddObject, object_body
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig,
                                                        force_limited_set_point)
from tegrasp_drake.simulation.table_model import AddTable

GRAVITY = 9.81  # m/s^2, Drake's default
SCENE_XY = EXPECTED_XY  # m; scenes stand at the station's expected object position


@dataclasses.dataclass(frozen=True)
class GripProgram:
    """How the fingers move: from `start_q` toward `goal_q` [m, the pad surface's distance
    from the grasp axis] at `closing_speed` [m/s], each pad's force at most the one interpolated
    from (`force_times_s` [s], `force_n` [N])."""
    start_q: float
    force_times_s: tuple = (0.0,)
    force_n: tuple = (25.0,)
    goal_q: float = 0.0
    closing_speed: float = math.inf

    def force(self, t: float) -> float:
        return float(np.interp(t, self.force_times_s, self.force_n))

    def reference(self, t: float) -> tuple[float, float]:
        """(q_ref [m], v_ref [m/s]) of the finger at time t [s]."""
        travel = self.start_q - self.goal_q
        if math.isinf(self.closing_speed) or self.closing_speed * t >= travel:
            return self.goal_q, 0.0
        return self.start_q - self.closing_speed * t, -self.closing_speed


class FingerDrive(LeafSystem):
    """The fingers' force-limited position loop for a GripProgram.

    .. pydrake_system::

        name: FingerDrive
        input_ports:
        - finger_state
        output_ports:
        - desired_state

    Ports:
        finger_state: [q_left, q_right, v_left, v_right] (m, m, m/s, m/s).
        desired_state: [q, v] of the actuated left finger (m, m/s), for the plant's PD.
    """

    def __init__(self, *, program: GripProgram, position_gain: float):
        super().__init__()
        self._program = program
        self._position_gain = position_gain
        self._finger_state = self.DeclareVectorInputPort("finger_state", 4)
        self.DeclareVectorOutputPort(
            "desired_state", 2, self._calc_desired_state,
            prerequisites_of_calc={self.time_ticket(), self._finger_state.ticket()})

    def _calc_desired_state(self, context, output):
        t = context.get_time()
        q_ref, v_ref = self._program.reference(t)
        q = self._finger_state.Eval(context)[0]
        output.SetFromVector([force_limited_set_point(q, q_ref, self._program.force(t),
                                                      self._position_gain), v_ref])


@dataclasses.dataclass
class PinchScene:
    """A built scene: its diagram, the plant in it and the object's body."""
    diagram: object
    plant: object
    object_body: object

    def object_pose(self, context) -> RigidTransform:
        plant_context = self.plant.GetMyContextFromRoot(context)
        return self.plant.EvalBodyPoseInWorld(plant_context, self.object_body)

    def object_velocity(self, context):
        plant_context = self.plant.GetMyContextFromRoot(context)
        return self.plant.EvalBodySpatialVelocityInWorld(plant_context, self.object_body)


def MakePinchScene(*, obj: ObjectConfig, X_WO: RigidTransform, program: GripProgram,
                   grasp_xyz, plant_config: MultibodyPlantConfig, with_table: bool,
                   gripper: GripperDriverConfig | None = None,
                   contact_geometry: ContactGeometryConfig | None = None) -> PinchScene:
    """The gripper (grasp frame at `grasp_xyz`, side grasp), the object at X_WO and the
    table if `with_table`; the fingers start at `program.start_q`."""
    gripper = gripper or GripperDriverConfig()
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(plant_config, builder)
    parser = paths.make_parser(plant)
    (hand,) = parser.AddModels(url=GRIPPER_URL)
    X_WG = RigidTransform(R_WG_SIDE_GRASP, np.asarray(grasp_xyz, float))
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", hand),
                     X_WG @ RigidTransform([0.0, 0.0, -PAD_CENTER_Z]))
    if with_table:
        AddTable(parser, contact_geometry)
    body = object_body(plant, AddObject(parser, obj, contact_geometry))
    plant.set_gravity_enabled(hand, False)  # as in the station: the arm carries the gripper
    # The gripper's one actuator (the left finger; the right one mimics it).
    plant.get_joint_actuator(JointActuatorIndex(0)).set_controller_gains(
        PdControllerGains(p=gripper.position_gain, d=gripper.damping_gain))
    plant.Finalize()
    plant.SetDefaultPositions(hand, [program.start_q, program.start_q])
    plant.SetDefaultFloatingBaseBodyPose(body, X_WO)
    drive = builder.AddNamedSystem("finger_drive", FingerDrive(
        program=program, position_gain=gripper.position_gain))
    builder.Connect(plant.get_state_output_port(hand), drive.GetInputPort("finger_state"))
    builder.Connect(drive.GetOutputPort("desired_state"), plant.get_desired_state_input_port(hand))
    diagram = builder.Build()
    diagram.set_name("pinch_scene")
    return PinchScene(diagram, plant, body)


def tilt_from_vertical_deg(X_WO: RigidTransform) -> float:
    """Angle [deg] between the object's z axis and the world's."""
    z = X_WO.rotation().matrix()[:, 2].copy()
    return math.degrees(math.acos(min(1.0, float(z[2]))))


def tilt_about_grasp_axis_deg(X_WO: RigidTransform) -> float:
    """Signed angle [deg] of the object's z axis from vertical about world y (the grasp axis)."""
    z = X_WO.rotation().matrix()[:, 2].copy()
    return math.degrees(math.atan2(float(z[0]), float(z[2])))


@dataclasses.dataclass(frozen=True)
class PushResult:
    tilt_deg: float  # the object's tilt from vertical at the end
    slide_m: float  # how far its base centre moved along the push


def push_standing_object(obj: ObjectConfig, *, push_height: float,
                         plant_config: MultibodyPlantConfig, distance: float = 0.02,
                         speed: float = 0.02, force_limit: float = 25.0,
                         contact_geometry: ContactGeometryConfig | None = None) -> PushResult:
    """Stands `obj` on the table just inside the open left pad and closes the gripper at
    `speed` until the left pad, its centre `push_height` [m] above the table, has pushed
    `distance` [m] past first touch (the right pad stays clear while distance < the open gap)."""
    half_width = obj.width_along_stroke() / 2
    gap = 0.001  # m between the open left pad and the object
    y_object = SCENE_XY[1] + HALF_STROKE - gap - half_width
    X_WO = RigidTransform([SCENE_XY[0], y_object, 0.0])
    program = GripProgram(start_q=HALF_STROKE, force_n=(force_limit,),
                          goal_q=HALF_STROKE - gap - distance, closing_speed=speed)
    scene = MakePinchScene(obj=obj, X_WO=X_WO, program=program,
                           grasp_xyz=(SCENE_XY[0], SCENE_XY[1], push_height),
                           plant_config=plant_config, with_table=True,
                           contact_geometry=contact_geometry)
    simulator = Simulator(scene.diagram)
    settle = 0.2  # s after the pad reaches its goal
    simulator.AdvanceTo((gap + distance) / speed + settle)
    X = scene.object_pose(simulator.get_context())
    return PushResult(tilt_deg=tilt_from_vertical_deg(X),
                      slide_m=float(y_object - X.translation()[1]))


@dataclasses.dataclass(frozen=True)
class SlipResult:
    onset_force_n: float | None  # commanded grip force per pad when the object began to fall
    onset_time_s: float | None
    drop_before_onset_m: float  # how far it had sunk by then (creep before slip)


def slip_onset_grip_force(obj: ObjectConfig, *, plant_config: MultibodyPlantConfig,
                          initial_force: float = 10.0, ramp_rate: float = 2.5,
                          hold_s: float = 0.3, falling_speed: float = 1e-3,
                          contact_geometry: ContactGeometryConfig | None = None
                          ) -> SlipResult:
    """Holds `obj` between the pads (no table) at `initial_force` [N] per pad for `hold_s`,
    then lowers it at `ramp_rate` [N/s]; slip begins where it falls faster than
    `falling_speed` [m/s]."""
    radius = obj.width_along_stroke() / 2
    grasp = np.array([SCENE_XY[0], SCENE_XY[1], 0.3])
    ramp_s = initial_force / ramp_rate
    program = GripProgram(start_q=radius - 2e-4, force_times_s=(hold_s, hold_s + ramp_s),
                          force_n=(initial_force, 0.0))
    X_WO = RigidTransform(grasp - [0.0, 0.0, obj.height() / 2])
    scene = MakePinchScene(obj=obj, X_WO=X_WO, program=program, grasp_xyz=grasp,
                           plant_config=plant_config, with_table=False,
                           contact_geometry=contact_geometry)
    simulator = Simulator(scene.diagram)

    def falling(root_context):
        if root_context.get_time() > hold_s and (
                scene.object_velocity(root_context).translational()[2] < -falling_speed):
            return EventStatus.ReachedTermination(scene.diagram, "slip")
        return EventStatus.DidNothing()

    simulator.set_monitor(falling)
    status = simulator.AdvanceTo(hold_s + ramp_s)
    context = simulator.get_context()
    drop = float(X_WO.translation()[2] - scene.object_pose(context).translation()[2])
    if status.reason() != status.ReturnReason.kReachedTerminationCondition:
        return SlipResult(None, None, drop)
    t = context.get_time()
    return SlipResult(program.force(t), t, drop)


def held_tilt_rate(obj: ObjectConfig, *, tilt_deg: float, com_offset: float, grip_force: float,
                   plant_config: MultibodyPlantConfig, settle_s: float = 0.5,
                   measure_s: float = 1.0,
                   contact_geometry: ContactGeometryConfig | None = None) -> float:
    """Holds `obj` (no table) with `grip_force` [N] per pad, tilted by `tilt_deg` about the grasp
    axis, its centre of mass `com_offset` [m] above the pads' centre along its axis; returns its
    mean rotation rate [deg/s] about the grasp axis over `measure_s` after `settle_s`."""
    radius = obj.width_along_stroke() / 2
    grasp = np.array([SCENE_XY[0], SCENE_XY[1], 0.3])
    R = RotationMatrix.MakeYRotation(math.radians(tilt_deg))
    # Object frame at its base centre: the pads' centre is com_offset below its COM.
    axis_coordinate = obj.height() / 2 - com_offset
    X_WO = RigidTransform(R, grasp - R.multiply([0.0, 0.0, axis_coordinate]))
    program = GripProgram(start_q=radius - 2e-4, force_n=(grip_force,))
    scene = MakePinchScene(obj=obj, X_WO=X_WO, program=program, grasp_xyz=grasp,
                           plant_config=plant_config, with_table=False,
                           contact_geometry=contact_geometry)
    simulator = Simulator(scene.diagram)
    simulator.AdvanceTo(settle_s)
    start = tilt_about_grasp_axis_deg(scene.object_pose(simulator.get_context()))
    simulator.AdvanceTo(settle_s + measure_s)
    end = tilt_about_grasp_axis_deg(scene.object_pose(simulator.get_context()))
    return (end - start) / measure_s
