"""An emulated JACO2 on LCM: a Drake simulation of the arm answering the Kinova driver's
messages, as Drake's hardware_sim does for its arms.

    KINOVA_JACO_COMMAND -> JacoCommandReceiver -> JacoVelocityModeFirmware -> plant PD
    plant state -> JacoStatusSender -> KINOVA_JACO_STATUS (100 Hz)

The plant is the arm alone (the JACO2 model of the station, gravity off because the
firmware compensates it, the station's joint PD gains), so it runs well faster than real
time; the gripper and the tactile pads have their own emulators. Like the real driver in
joint-velocity mode, it executes only the commanded joint velocities (the positions in
the command are ignored) and holds still when commands stop for `command_timeout`.

Run it with `tegrasp emulate jaco` (or `all`), or build it with `MakeJacoArmEmulator` and
step it in real time.
"""

import numpy as np
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains, SpatialInertia
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.lcm import LcmInterfaceSystem
from pydrake.systems.primitives import Demultiplexer

from tegrasp_drake import paths
from tegrasp_drake.arm_kinematics import ARM_URL, X_FLANGE_GRIPPER
from tegrasp_drake.drivers.jaco_lcm import JACO_NUM_JOINTS
from tegrasp_drake.drivers.jaco_lcm_interface import AddJacoLcmEmulator

PLANT_TIME_STEP = 1e-3  # [s]
# The 2F-85 as a solid cylinder (the tactile gripper model's 0.8 kg base and two 0.05 kg
# fingers); without it, the bare wrist's tiny inertias make SAP fail to converge at rest.
GRIPPER_MASS = 0.9        # [kg]
GRIPPER_RADIUS = 0.04     # [m]
GRIPPER_LENGTH = 0.15     # [m]
GRIPPER_COM_Z = 0.06      # [m] from the flange along its z


def integrate_velocity(q_reference, velocity, time_step: float) -> np.ndarray:
    """The servo reference after one step of the commanded joint velocities [rad]."""
    return np.asarray(q_reference) + time_step * np.asarray(velocity)


class JacoVelocityModeFirmware(LeafSystem):
    """The arm firmware's joint-velocity mode: integrates the commanded velocities into the
    reference its joint servos (the plant's PD) track.

    Input ports:
        command (12): [q (ignored), v] from JacoCommandReceiver [rad, rad/s].
        position_measured (6): the joints [rad]; the reference starts there.
    Output ports:
        desired_state (12): [q_reference, v] for the plant's PD.
    """

    def __init__(self, time_step: float = PLANT_TIME_STEP):
        super().__init__()
        n = JACO_NUM_JOINTS
        self._time_step = time_step
        self._command_port = self.DeclareVectorInputPort("command", 2 * n)
        self._position_port = self.DeclareVectorInputPort("position_measured", n)
        self._reference = self.DeclareDiscreteState(n)
        self.DeclareInitializationDiscreteUpdateEvent(self._initialize)
        self.DeclarePeriodicDiscreteUpdateEvent(time_step, 0.0, self._integrate)
        self.DeclareVectorOutputPort(
            "desired_state", 2 * n, self._calc_desired_state,
            prerequisites_of_calc={self.xd_ticket(), self._command_port.ticket()})

    def _initialize(self, context, discrete_state):
        discrete_state.get_mutable_vector(self._reference).SetFromVector(
            self._position_port.Eval(context))

    def _integrate(self, context, discrete_state):
        velocity = self._command_port.Eval(context)[JACO_NUM_JOINTS:]
        discrete_state.get_mutable_vector(self._reference).SetFromVector(integrate_velocity(
            context.get_discrete_state(self._reference).get_value(), velocity,
            self._time_step))

    def _calc_desired_state(self, context, output):
        output.SetFromVector(np.concatenate([
            context.get_discrete_state(self._reference).get_value(),
            self._command_port.Eval(context)[JACO_NUM_JOINTS:]]))


def MakeJacoArmEmulator(*, lcm, initial_positions, position_gain: float = 400.0,
                        damping_gain: float = 40.0, command_timeout: float = 0.05):
    """The emulator Diagram (module docstring) on `lcm` (a DrakeLcm, which the diagram's
    LcmInterfaceSystem pumps); the arm starts at `initial_positions` [rad].

    Output ports: position_measured (6), velocity_measured (6) [rad, rad/s], for tests."""
    builder = DiagramBuilder()
    builder.AddNamedSystem("lcm", LcmInterfaceSystem(lcm))
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(
        time_step=PLANT_TIME_STEP, discrete_contact_approximation="lagged"), builder)
    parser = paths.make_parser(plant)
    (arm,) = parser.AddModels(url=ARM_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", arm))
    # The gripper as one rigid body of its mass and inertia on the flange: its fingers
    # are the Robotiq emulator's business, and without their joints a step is 5x cheaper.
    gripper = plant.AddRigidBody("gripper", arm, SpatialInertia.SolidCylinderWithMass(
        GRIPPER_MASS, GRIPPER_RADIUS, GRIPPER_LENGTH, [0.0, 0.0, 1.0]).Shift(
            [0.0, 0.0, -GRIPPER_COM_Z]))
    plant.WeldFrames(plant.GetFrameByName("flange", arm), gripper.body_frame(),
                     X_FLANGE_GRIPPER)
    plant.set_gravity_enabled(arm, False)
    for i in range(plant.num_actuators()):
        plant.get_joint_actuator(JointActuatorIndex(i)).set_controller_gains(
            PdControllerGains(p=position_gain, d=damping_gain))
    plant.Finalize()
    plant.SetDefaultPositions(arm, np.asarray(initial_positions, dtype=float))

    state = builder.AddNamedSystem("arm_state_demux", Demultiplexer([JACO_NUM_JOINTS] * 2))
    builder.Connect(plant.get_state_output_port(arm), state.get_input_port())
    firmware = builder.AddNamedSystem("velocity_mode_firmware", JacoVelocityModeFirmware())
    builder.Connect(state.get_output_port(0), firmware.GetInputPort("position_measured"))
    builder.Connect(firmware.GetOutputPort("desired_state"),
                    plant.get_desired_state_input_port(arm))
    AddJacoLcmEmulator(builder, lcm=lcm, desired_state_input=firmware.GetInputPort("command"),
                       position_output=state.get_output_port(0),
                       velocity_output=state.get_output_port(1),
                       torque_output=plant.get_net_actuation_output_port(arm),
                       command_timeout=command_timeout)
    builder.ExportOutput(state.get_output_port(0), "position_measured")
    builder.ExportOutput(state.get_output_port(1), "velocity_measured")
    diagram = builder.Build()
    diagram.set_name("jaco_arm_emulator")
    return diagram
