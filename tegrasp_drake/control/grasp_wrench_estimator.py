"""GraspWrenchEstimator: the wrench the arm's joint torques hold at the grasp frame G, for
the taxel_aware controller's finger-strike sense (finger_strike.py)."""

import numpy as np
from pydrake.multibody.tree import JacobianWrtVariable
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.control.finger_strike import grasp_wrench_from_torques
from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant
from tegrasp_drake.rig import station_interface as ports


class GraspWrenchEstimator(LeafSystem):
    """The wrench on the arm at G from its measured joint torques, statically.

    .. pydrake_system::

        name: GraspWrenchEstimator
        input_ports:
        - arm.position_measured
        - arm.torque_measured
        output_ports:
        - wrench

    Joint angles [rad] and torques [N m] (simulated: net actuation; JACO2: gravity-free
    sensor torques) in; wrench [Mx, My, Mz, Fx, Fy, Fz] [N m, N] at G in world out,
    ignoring the arm's inertia (below 0.81 N in the slow approach).
    """

    def __init__(self):
        super().__init__()
        self._plant = make_arm_control_plant()
        self._plant_context = self._plant.CreateDefaultContext()
        self._frame = self._plant.GetFrameByName("grasp_frame")
        self._q = self.DeclareVectorInputPort(ports.ARM_POSITION_MEASURED, ports.ARM_JOINTS)
        self._tau = self.DeclareVectorInputPort(ports.ARM_TORQUE_MEASURED, ports.ARM_JOINTS)
        self.DeclareVectorOutputPort("wrench", 6, self._calc_wrench)

    def _calc_wrench(self, context, output):
        self._plant.SetPositions(self._plant_context, self._q.Eval(context))
        world = self._plant.world_frame()
        J = self._plant.CalcJacobianSpatialVelocity(
            self._plant_context, JacobianWrtVariable.kV, self._frame, np.zeros(3), world,
            world)
        output.SetFromVector(grasp_wrench_from_torques(J, self._tau.Eval(context)))
