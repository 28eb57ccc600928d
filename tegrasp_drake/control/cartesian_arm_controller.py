"""Cartesian arm control: X_WG_desired to `arm.desired_state` (the port the simulated
station and the Jaco driver take), by Drake's DifferentialInverseKinematicsIntegrator within
the JACO2's joint limits and a DiscreteDerivative for the velocities."""

import numpy as np
from pydrake.multibody.inverse_kinematics import (DifferentialInverseKinematicsIntegrator,
                                                  DifferentialInverseKinematicsParameters)
from pydrake.systems.primitives import DiscreteDerivative, Multiplexer

from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant
from tegrasp_drake.modelgen import jaco2_dh
from tegrasp_drake.rig.jaco_velocity_tracker import JACO2_REACH_M

JOINT_SPEED_MARGIN = 0.9  # use at most 90 % of each joint's published top speed


def jaco_joint_limits():
    """(lower, upper) position limits [rad] and speed limits [rad/s] of the six joints."""
    lower = np.array([j.lower if j.lower is not None else -np.inf for j in jaco2_dh.JOINTS])
    upper = np.array([j.upper if j.upper is not None else np.inf for j in jaco2_dh.JOINTS])
    speed = np.array([j.max_speed for j in jaco2_dh.JOINTS]) * JOINT_SPEED_MARGIN
    return lower, upper, speed


def max_hand_speed_mps() -> float:
    """The fastest [m/s] the differential IK can move the grasp frame, bounded from above:
    a joint turning at w moves the frame at w times its distance from the joint's axis, at
    most the JACO2's reach (JACO2_REACH_M, 0.9 m, Kinova's specification), and the frame's
    speed is at most the sum over the six joints, each at its limit here (90 % of the
    published 36 deg/s of joints 1-3 and 48 deg/s of joints 4-6): 3.56 m/s. A bound, not
    what every pose reaches: a move asking more is one the arm cannot follow anywhere."""
    return float(np.sum(jaco_joint_limits()[2]) * JACO2_REACH_M)


def AddCartesianArmController(builder, *, position_measured, velocity_measured,
                                 q_nominal: np.ndarray, time_step: float,
                                 name: str = "arm_controller"):
    """Adds the controller; returns (X_WG_desired input, arm.desired_state output). The integrator
    starts from the measured joint state; q_nominal [rad]: joint centering's target."""
    plant = make_arm_control_plant()
    lower, upper, speed = jaco_joint_limits()
    parameters = DifferentialInverseKinematicsParameters(6, 6)
    parameters.set_joint_position_limits((lower, upper))
    parameters.set_joint_velocity_limits((-speed, speed))
    parameters.set_nominal_joint_position(q_nominal)
    parameters.set_joint_centering_gain(0.1 * np.eye(6))
    diff_ik = builder.AddNamedSystem(
        f"{name}_diff_ik",
        DifferentialInverseKinematicsIntegrator(plant, plant.world_frame(),
                                                plant.GetFrameByName("grasp_frame"),
                                                time_step, parameters))
    robot_state = builder.AddNamedSystem(f"{name}_robot_state", Multiplexer([6, 6]))
    builder.Connect(position_measured, robot_state.get_input_port(0))
    builder.Connect(velocity_measured, robot_state.get_input_port(1))
    builder.Connect(robot_state.get_output_port(), diff_ik.GetInputPort("robot_state"))
    derivative = builder.AddNamedSystem(f"{name}_velocity", DiscreteDerivative(6, time_step))
    mux = builder.AddNamedSystem(f"{name}_desired_state", Multiplexer([6, 6]))
    builder.Connect(diff_ik.GetOutputPort("joint_positions"), derivative.get_input_port())
    builder.Connect(diff_ik.GetOutputPort("joint_positions"), mux.get_input_port(0))
    builder.Connect(derivative.get_output_port(), mux.get_input_port(1))
    return diff_ik.GetInputPort("X_AE_desired"), mux.get_output_port()
