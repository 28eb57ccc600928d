"""The two systems that let the carriage (carriage.py) stand in for the JACO2 behind the
arm's ports: CarriageCommand (the arm's servo set-point to the carriage's, and the arm's
joints) and CarriageWristWrench (the weld's wrench and the joint torques that would hold it)."""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialForce
from pydrake.systems.framework import BasicVector, LeafSystem

from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.simulation.carriage import (ArmGraspFrameKinematics, carriage_displacement,
                                               carriage_state, wrench_on_arm)

ARM_JOINTS = ports.ARM_JOINTS


class CarriageCommand(LeafSystem):
    """The arm's joint servo set-point as a carriage set-point, and the arm's reported joint state.

    .. pydrake_system::

        name: CarriageCommand
        input_ports:
        - joint_set_point
        - carriage_state
        output_ports:
        - carriage_desired_state
        - arm.position_measured
        - arm.velocity_measured

    It samples the set-point every plant step `period_s`. When the set-point's rates change
    (a new command reaches the arm) it runs the arm model's kinematics for G's pose,
    velocity and Jacobian; in between it moves the carriage's set-point on at that velocity
    (second-order drift: tens of micrometres at top speed). The carriage follows a step late.

    Ports:
        joint_set_point: the arm's joint servo set-point [rad, rad/s] (12).
        carriage_state: the carriage joints' positions and rates (12, actuator order).
        carriage_desired_state: the carriage joints' state [m, rad, m/s, rad/s] (12) that
            puts G where the set-point's joints put it, moving as they move it.
        arm.position_measured: the set-point's joints [rad] (6) moved by the carriage's
            deflection from its set-point, J^-1 [dtheta; dp]; starts at `initial_positions`.
        arm.velocity_measured: the set-point's joint rates [rad/s] (6): ideal servos.
    """

    def __init__(self, carriage, *, initial_positions: np.ndarray, period_s: float):
        super().__init__()
        self._carriage = carriage
        self._period_s = period_s
        self._kinematics = ArmGraspFrameKinematics()
        self._command = self.DeclareVectorInputPort("joint_set_point", 2 * ARM_JOINTS)
        self._carriage_state = self.DeclareVectorInputPort("carriage_state", 2 * ARM_JOINTS)
        initial = np.concatenate([initial_positions, np.zeros(ARM_JOINTS)])
        set_point, jacobian = self._carriage_set_point(initial)
        self._arm_state = self.DeclareDiscreteState(initial)
        self._set_point = self.DeclareDiscreteState(set_point)
        self._jacobian = self.DeclareDiscreteState(jacobian.ravel())
        self.DeclarePeriodicDiscreteUpdateEvent(period_s, 0.0, self._sample_command)
        self.DeclareStateOutputPort("carriage_desired_state", self._set_point)
        self.DeclareVectorOutputPort(ports.ARM_POSITION_MEASURED, ARM_JOINTS,
                                     self._calc_positions,
                                     prerequisites_of_calc={
                                         self.xd_ticket(),
                                         self._carriage_state.ticket()})
        self.DeclareVectorOutputPort(ports.ARM_VELOCITY_MEASURED, ARM_JOINTS,
                                     self._calc_velocities,
                                     prerequisites_of_calc={self.xd_ticket()})

    def _carriage_set_point(self, command: np.ndarray):
        """(carriage set-point, J_WG) of the arm's joint state `command`."""
        X_WG, J = self._kinematics.pose_and_jacobian(command[:ARM_JOINTS])
        return carriage_state(self._carriage, X_WG, J @ command[ARM_JOINTS:]), J

    def _sample_command(self, context, discrete_state):
        command = self._command.Eval(context)
        previous = context.get_discrete_state(self._arm_state).value()
        discrete_state.set_value(self._arm_state, command)
        if np.array_equal(command[ARM_JOINTS:], previous[ARM_JOINTS:]):
            set_point = context.get_discrete_state(self._set_point).value().copy()
            set_point[:ARM_JOINTS] += self._period_s * set_point[ARM_JOINTS:]
        else:
            set_point, J = self._carriage_set_point(command)
            discrete_state.set_value(self._jacobian, J.ravel())
        discrete_state.set_value(self._set_point, set_point)

    def _calc_positions(self, context, output):
        q = context.get_discrete_state(self._arm_state).value()[:ARM_JOINTS]
        set_point = context.get_discrete_state(self._set_point).value()
        J = context.get_discrete_state(self._jacobian).value().reshape(6, ARM_JOINTS)
        deflection = self._carriage_state.Eval(context)[:ARM_JOINTS] - set_point[:ARM_JOINTS]
        output.SetFromVector(q + np.linalg.solve(J, carriage_displacement(
            self._carriage, set_point[:ARM_JOINTS], deflection)))

    def _calc_velocities(self, context, output):
        output.SetFromVector(context.get_discrete_state(self._arm_state).value()[ARM_JOINTS:])


class CarriageWristWrench(LeafSystem):
    """The wrench at the carriage-gripper weld, and the arm joint torques that hold it.

    .. pydrake_system::

        name: CarriageWristWrench
        input_ports:
        - reaction_forces
        - body_poses
        - arm.position_measured
        output_ports:
        - wrist_wrench
        - arm.torque_measured

    Ports:
        reaction_forces, body_poses: the plant's.
        arm.position_measured: the arm's reported joint angles [rad] (6).
        wrist_wrench: [Mx, My, Mz, Fx, Fy, Fz] [N m, N], the wrench the gripper puts on the
            arm at G, in world (contact forces and the hand's inertia; its gravity is off).
        arm.torque_measured: the joint torques [N m] (6) that hold it, -J_WG(q)^T w.
    """

    def __init__(self, *, weld_index, gripper_body_index):
        super().__init__()
        self._weld_index = int(weld_index)
        self._gripper_body_index = int(gripper_body_index)
        self._kinematics = ArmGraspFrameKinematics()
        self._reactions = self.DeclareAbstractInputPort(
            "reaction_forces", AbstractValue.Make([SpatialForce()]))
        self._poses = self.DeclareAbstractInputPort("body_poses",
                                                    AbstractValue.Make([RigidTransform()]))
        self._q = self.DeclareVectorInputPort(ports.ARM_POSITION_MEASURED, ARM_JOINTS)
        self.DeclareVectorOutputPort("wrist_wrench", 6, self._calc_wrench)
        self.DeclareVectorOutputPort(ports.ARM_TORQUE_MEASURED, ARM_JOINTS, self._calc_torques)

    def _wrench(self, context) -> np.ndarray:
        reaction = self._reactions.Eval(context)[self._weld_index]
        R_WG = self._poses.Eval(context)[self._gripper_body_index].rotation()
        return wrench_on_arm(reaction.get_coeffs(), R_WG)

    def _calc_wrench(self, context, output: BasicVector):
        output.SetFromVector(self._wrench(context))

    def _calc_torques(self, context, output: BasicVector):
        _, J = self._kinematics.pose_and_jacobian(self._q.Eval(context))
        output.SetFromVector(-J.T @ self._wrench(context))
