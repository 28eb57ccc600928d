"""An emulated JACO2 on LCM (`tegrasp emulate jaco`), as Drake's hardware_sim does:
KINOVA_JACO_COMMAND -> joint velocity servos, plant state -> KINOVA_JACO_STATUS at 100 Hz.
Like the real arm in joint-velocity mode it executes only the commanded velocities (servo
tau = kd (v_cmd - v), the plant's implicit PD with kp = 0) and stops when commands stop.
The gripper is one rigid body on the flange; gravity is off (the firmware compensates it)."""

import numpy as np
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains, SpatialInertia
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem
from pydrake.systems.primitives import Demultiplexer

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import ARM_URL, X_FLANGE_GRIPPER
from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_NUM_JOINTS
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmEmulator
from tegrasp_drake.hardware.message_boundary import MessageBoundary

PLANT_TIME_STEP = 1e-3  # [s]
# [N m s / rad]: a commanded speed is reached, or the arm stops, within a few milliseconds.
SERVO_DAMPING_GAIN = 50.0
# The 2F-85 as a solid cylinder (the gripper model's 0.8 kg base, two 0.05 kg fingers); the
# bare wrist's tiny inertias alone make SAP fail to converge at rest.
GRIPPER_MASS = 0.9        # [kg]
GRIPPER_RADIUS = 0.04     # [m]
GRIPPER_LENGTH = 0.15     # [m]
GRIPPER_COM_Z = 0.06      # [m] from the flange along its z


def MakeJacoArmEmulator(*, lcm, initial_positions, damping_gain: float = SERVO_DAMPING_GAIN,
                        command_timeout: float = 0.05,
                        command_boundary: MessageBoundary | None = None):
    """The emulator Diagram on `lcm`, starting at `initial_positions` [rad]; commands cross
    `command_boundary`. Outputs for tests: position_measured, velocity_measured [rad, rad/s]."""
    builder = DiagramBuilder()
    builder.AddNamedSystem("lcm", LcmInterfaceSystem(lcm))
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(
        time_step=PLANT_TIME_STEP, discrete_contact_approximation="lagged"), builder)
    parser = paths.make_parser(plant)
    (arm,) = parser.AddModels(url=ARM_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", arm))
    # One rigid body: the fingers are the Robotiq emulator's, and a step is 5x cheaper.
    gripper = plant.AddRigidBody("gripper", arm, SpatialInertia.SolidCylinderWithMass(
        GRIPPER_MASS, GRIPPER_RADIUS, GRIPPER_LENGTH, [0.0, 0.0, 1.0]).Shift(
            [0.0, 0.0, -GRIPPER_COM_Z]))
    plant.WeldFrames(plant.GetFrameByName("flange", arm), gripper.body_frame(),
                     X_FLANGE_GRIPPER)
    plant.set_gravity_enabled(arm, False)
    for i in range(plant.num_actuators()):
        plant.get_joint_actuator(JointActuatorIndex(i)).set_controller_gains(
            PdControllerGains(p=0.0, d=damping_gain))
    plant.Finalize()
    plant.SetDefaultPositions(arm, np.asarray(initial_positions, dtype=float))

    state = builder.AddNamedSystem("arm_state_demux", Demultiplexer([JACO_NUM_JOINTS] * 2))
    builder.Connect(plant.get_state_output_port(arm), state.get_input_port())
    AddJacoLcmEmulator(builder, lcm=lcm,
                       desired_state_input=plant.get_desired_state_input_port(arm),
                       position_output=state.get_output_port(0),
                       velocity_output=state.get_output_port(1),
                       torque_output=plant.get_net_actuation_output_port(arm),
                       command_timeout=command_timeout, boundary=command_boundary)
    builder.ExportOutput(state.get_output_port(0), "position_measured")
    builder.ExportOutput(state.get_output_port(1), "velocity_measured")
    diagram = builder.Build()
    diagram.set_name("jaco_arm_emulator")
    return diagram
