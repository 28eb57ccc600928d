"""The Cartesian arm controller (control/cartesian_arm_controller.py): from the measured
joints it drives the joint command toward a grasp-frame pose, within the JACO2's limits,
with the velocity the command's own rate one control step late."""

import numpy as np
import pytest
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantValueSource, ConstantVectorSource, VectorLogSink

from tegrasp_drake.control.cartesian_arm_controller import (JOINT_SPEED_MARGIN,
                                                            AddCartesianArmController,
                                                            jaco_joint_limits)
from tegrasp_drake.modelgen import jaco2_dh
from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant

ARM_Q = np.array([0.3, 2.9, 1.3, -2.1, 1.4, 0.2])  # rad, away from singularities
TIME_STEP = 0.01  # s


def _grasp_pose(q) -> RigidTransform:
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, q)
    return plant.CalcRelativeTransform(context, plant.world_frame(),
                                       plant.GetFrameByName("grasp_frame"))


def _run(X_WG_desired: RigidTransform, seconds: float) -> np.ndarray:
    """(12, N) the desired state [q; v] at each control step."""
    builder = DiagramBuilder()
    q_source = builder.AddSystem(ConstantVectorSource(ARM_Q))
    v_source = builder.AddSystem(ConstantVectorSource(np.zeros(6)))
    target, desired_state = AddCartesianArmController(
        builder, position_measured=q_source.get_output_port(),
        velocity_measured=v_source.get_output_port(), q_nominal=ARM_Q, time_step=TIME_STEP)
    pose = builder.AddSystem(ConstantValueSource(AbstractValue.Make(X_WG_desired)))
    builder.Connect(pose.get_output_port(), target)
    logger = builder.AddSystem(VectorLogSink(12, TIME_STEP))
    builder.Connect(desired_state, logger.get_input_port())
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(seconds)
    return logger.FindLog(simulator.get_context()).data()


def test_joint_limits_are_the_dh_tables_with_the_speed_margin():
    lower, upper, speed = jaco_joint_limits()
    np.testing.assert_array_equal(speed, [j.max_speed * JOINT_SPEED_MARGIN
                                          for j in jaco2_dh.JOINTS])
    for j, low, high in zip(jaco2_dh.JOINTS, lower, upper):
        assert (low, high) == ((j.lower, j.upper) if j.lower is not None
                               else (-np.inf, np.inf))


def test_the_command_reaches_a_pose_a_centimetre_away_at_bounded_joint_speed():
    X_start = _grasp_pose(ARM_Q)
    X_target = RigidTransform(X_start.rotation(), X_start.translation() + [0.01, 0.0, -0.005])
    states = _run(X_target, seconds=1.0)
    q_final = states[:6, -1]
    # Differential IK converges on a reachable target: within 0.1 mm after 1 s.
    np.testing.assert_allclose(_grasp_pose(q_final).translation(), X_target.translation(),
                               rtol=0, atol=1e-4)
    np.testing.assert_allclose(_grasp_pose(q_final).rotation().matrix(),
                               X_target.rotation().matrix(), rtol=0, atol=1e-3)
    _, _, speed = jaco_joint_limits()
    assert np.all(np.abs(states[6:]) <= speed[:, None] + 1e-9)
    # The velocity is the command's rate one control step late: the derivative samples the
    # command at the same update that advances it, v_k = (q_{k-1} - q_{k-2}) / time_step.
    np.testing.assert_allclose(states[6:, 2:], np.diff(states[:6, :-1], axis=1) / TIME_STEP,
                               rtol=0, atol=1e-9)


def test_a_target_at_the_current_pose_holds_the_arm_still():
    states = _run(_grasp_pose(ARM_Q), seconds=0.3)
    np.testing.assert_allclose(states[:6] - ARM_Q[:, None], 0.0, rtol=0, atol=1e-6)


def _revolute_column(axis, point, hand=(0.0, 0.0, 0.0)):
    """A revolute joint's column of a Jacobian at `hand`: [axis; axis x (hand - point)]."""
    axis = np.asarray(axis, dtype=float)
    return np.concatenate([axis, np.cross(axis, np.subtract(hand, point))])


def _one_joint_jacobian(r):
    """Six revolute joints; the hand at the origin. Joint 1 turns about z at distance r
    behind the hand (-x), joint 6 about z through the hand: joint 1 at w with joint 6 at -w
    moves the hand along y at w r, its orientation held; the others make J invertible."""
    return np.column_stack([_revolute_column([0, 0, 1], [-r, 0, 0]),
                            _revolute_column([0, 1, 0], [-0.3, 0, 0.2]),
                            _revolute_column([0, 1, 0], [-0.1, 0, 0.4]),
                            _revolute_column([1, 0, 0], [0, 0.2, 0.1]),
                            _revolute_column([0, 1, 0], [0, 0, 0.1]),
                            _revolute_column([0, 0, 1], [0, 0, 0])])


def test_the_hand_top_speed_is_a_joint_speed_limit_times_its_distance_from_the_axis():
    """Along y only joints 1 and 6 turn, at equal and opposite rates (the orientation
    held): the slower joint's limit binds, v = w r; the linear program near a singularity
    (a joint repeated: J not invertible) finds the same."""
    from tegrasp_drake.control.cartesian_arm_controller import hand_top_speed_mps
    r, limits = 0.4, np.array([0.5, 0.9, 0.9, 0.9, 0.9, 1.0])
    J = _one_joint_jacobian(r)
    assert hand_top_speed_mps(J, [0, 2, 0], limits) == pytest.approx(0.5 * r)
    assert hand_top_speed_mps(J, [0, -1, 0], limits) == pytest.approx(0.5 * r)
    limits[5] = 0.3  # now joint 6 binds
    assert hand_top_speed_mps(J, [0, 1, 0], limits) == pytest.approx(0.3 * r)
    singular = J.copy()
    singular[:, 2] = singular[:, 1]
    assert np.linalg.matrix_rank(singular) == 5
    assert hand_top_speed_mps(singular, [0, 1, 0], limits) == pytest.approx(0.3 * r, rel=1e-6)


def test_the_hand_top_speed_at_the_grasp_pose_is_the_linear_programs():
    """At the default side grasp (the box's marker), the top speed along each axis is the
    linear program's over the joint rates within jaco_joint_limits, the orientation held:
    of order 0.1-0.2 m/s, far under the 3.56 m/s of the joints' limits times the reach."""
    from scipy.optimize import linprog
    from tegrasp_drake.control.cartesian_arm_controller import (grasp_frame_jacobian,
                                                                hand_top_speed_mps)
    from tegrasp_drake.rig.arm_kinematics import R_WG_SIDE_GRASP, solve_grasp_frame_ik
    plant = make_arm_control_plant()
    q = solve_grasp_frame_ik(plant, RigidTransform(R_WG_SIDE_GRASP, [0.718, 0.0, 0.055]))
    J = grasp_frame_jacobian(plant, plant.CreateDefaultContext(), q)
    w = jaco_joint_limits()[2]
    for d in np.eye(3):
        A = np.hstack([J, -np.concatenate([np.zeros(3), d])[:, None]])
        program = linprog(np.r_[np.zeros(6), -1.0], A_eq=A, b_eq=np.zeros(6),
                          bounds=[(-x, x) for x in w] + [(0, None)], method="highs")
        top = hand_top_speed_mps(J, d)
        assert top == pytest.approx(program.x[-1], rel=1e-6)
        assert 0.05 < top < 0.3
