"""Cartesian arm control: X_WG_desired to `arm.desired_state` (the port the simulated
station and the Jaco driver take), by Drake's DifferentialInverseKinematicsIntegrator within
the JACO2's joint limits and a DiscreteDerivative for the velocities; and the fastest that
IK can move the hand along a move (move_top_speeds_mps) and the shortest minimum-jerk
move it follows (shortest_move_s), which a scenario's moves are checked against at load and
the state machine's run-time moves are stretched to (followable_move_s)."""

import math

import functools

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.tree import JacobianWrtVariable
from pydrake.multibody.inverse_kinematics import (DifferentialInverseKinematicsIntegrator,
                                                  DifferentialInverseKinematicsParameters)
from pydrake.systems.primitives import DiscreteDerivative, Multiplexer
from scipy.optimize import linprog

from tegrasp_drake.control.motion_profiles import minimum_jerk_slope
from tegrasp_drake.rig.arm_kinematics import (R_WG_SIDE_GRASP, UnreachablePoseError,
                                              make_arm_control_plant, solve_grasp_frame_ik)
from tegrasp_drake.modelgen import jaco2_dh

JOINT_SPEED_MARGIN = 0.9  # use at most 90 % of each joint's published top speed


def jaco_joint_limits():
    """(lower, upper) position limits [rad] and speed limits [rad/s] of the six joints."""
    lower = np.array([j.lower if j.lower is not None else -np.inf for j in jaco2_dh.JOINTS])
    upper = np.array([j.upper if j.upper is not None else np.inf for j in jaco2_dh.JOINTS])
    speed = np.array([j.max_speed for j in jaco2_dh.JOINTS]) * JOINT_SPEED_MARGIN
    return lower, upper, speed


def grasp_frame_jacobian(plant, context, q: np.ndarray) -> np.ndarray:
    """J(q): the grasp frame's spatial velocity in the world ([angular; translational]) per
    joint speed [rad/s], of `plant` (make_arm_control_plant) at joint angles q [rad]."""
    plant.SetPositions(context, q)
    return plant.CalcJacobianSpatialVelocity(
        context, JacobianWrtVariable.kV, plant.GetFrameByName("grasp_frame"),
        [0.0, 0.0, 0.0], plant.world_frame(), plant.world_frame())


def hand_top_speed_mps(J: np.ndarray, direction, speed_limits=None) -> float:
    """The fastest [m/s] the differential IK can move the grasp frame along `direction`
    (world, any length) with its orientation held (as the IK holds it), J the frame's
    Jacobian (grasp_frame_jacobian): the largest v with J qdot = [0 angular; v d] for some
    |qdot_i| at most the joints' speed limits (default jaco_joint_limits', 90 % of the
    published), a linear program over (qdot, v). Where J is invertible qdot = v J^-1 [0; d]
    is the only solution and the program's optimum is the least of w_i / |(J^-1 [0; d])_i|
    (the joint reaching its limit first), taken directly; it is solved (linprog) only near a
    singularity."""
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    w = jaco_joint_limits()[2] if speed_limits is None else np.asarray(speed_limits, float)
    twist = np.concatenate([np.zeros(3), d])
    if np.linalg.cond(J) < 1e8:
        rates = np.abs(np.linalg.solve(J, twist))
        return float(np.min(w[rates > 0] / rates[rates > 0])) if np.any(rates > 0) else np.inf
    result = linprog(np.r_[np.zeros(len(w)), -1.0], A_eq=np.hstack([J, -twist[:, None]]),
                     b_eq=np.zeros(6), bounds=[(-x, x) for x in w] + [(0.0, None)],
                     method="highs")
    if result.status == 3:  # unbounded: the hand moves that way with no joint turning
        return np.inf
    return float(result.x[-1]) if result.success else 0.0


@functools.lru_cache(maxsize=1)
def _speed_plant():
    return make_arm_control_plant()  # one, read through a context per call


MOVE_SAMPLES = 11  # poses along a straight move, its start and end among them


@functools.lru_cache(maxsize=1024)
def _move_top_speeds(start: tuple, end: tuple, directions: tuple) -> tuple | None:
    plant = _speed_plant()
    context = plant.CreateDefaultContext()
    q = _start_joints(start)  # as the station solves it; the rest followed from there
    if q is None:
        return None
    tops = []
    for i, tau in enumerate(np.linspace(0.0, 1.0, MOVE_SAMPLES)):
        if i:
            q = _follow(plant, context, q, np.add(start, tau * np.subtract(end, start)))
            if q is None:
                return None
        J = grasp_frame_jacobian(plant, context, q)
        tops.append((float(tau), min(hand_top_speed_mps(J, d) for d in directions)))
    return tuple(tops)


@functools.lru_cache(maxsize=256)
def _start_joints(start: tuple) -> np.ndarray | None:
    try:
        return solve_grasp_frame_ik(_speed_plant(), RigidTransform(R_WG_SIDE_GRASP, start))
    except UnreachablePoseError:
        return None


def _follow(plant, context, q, p_WG, iterations=30):
    """Joint angles near q [rad] putting the grasp frame at p_WG [m] in the side grasp's
    orientation (Newton's method from q, the branch the differential IK stays on); None if
    it does not converge (out of reach)."""
    frame = plant.GetFrameByName("grasp_frame")
    q = np.array(q, dtype=float)
    for _ in range(iterations):
        plant.SetPositions(context, q)
        X = plant.CalcRelativeTransform(context, plant.world_frame(), frame)
        turn = (R_WG_SIDE_GRASP @ X.rotation().inverse()).ToAngleAxis()
        error = np.concatenate([turn.angle() * turn.axis(), p_WG - X.translation()])
        if np.linalg.norm(error) < 1e-10:
            return q
        q = q + np.linalg.lstsq(grasp_frame_jacobian(plant, context, q), error,
                                rcond=None)[0]
    return None


def move_top_speeds_mps(start_xyz, end_xyz, directions=None) -> tuple | None:
    """((tau, top speed [m/s]), ...) along a straight move of the grasp frame, in the side
    grasp's orientation, from start_xyz to end_xyz [m, world]: at MOVE_SAMPLES poses evenly
    along it (tau 0 to 1), the fastest the differential IK can move the hand there
    (hand_top_speed_mps, the least over `directions`, world; default the move's own), the
    arm's joints at the start as the station solves them and followed along the move as
    the IK follows it. The top speed changes along a move (toward the start pose the wrist
    nears its singularity); a move the arm follows asks at each pose at most its top speed
    there. None when the arm cannot put the hand at a pose of the move. Cached per move:
    scenarios load thousands of times, most alike."""
    key = lambda xyz: tuple(round(float(v), 7) for v in xyz)
    if directions is None:
        step = np.subtract(end_xyz, start_xyz, dtype=float)
        if not np.any(step):
            return None
        directions = (step / np.linalg.norm(step),)
    return _move_top_speeds(key(start_xyz), key(end_xyz), tuple(key(d) for d in directions))


def shortest_move_s(start_xyz, end_xyz) -> tuple[float, float] | None:
    """(shortest duration [s], top speed where it binds [m/s]) of a minimum-jerk straight
    move of the grasp frame from start_xyz to end_xyz [m, world]: the least T for which the
    speed the move asks at each pose move_top_speeds_mps samples, 30 tau^2 (1 - tau)^2 d / T
    (minimum_jerk_slope), is at most the arm's top speed there (the joints at 90 % of their
    published top speeds, JOINT_SPEED_MARGIN). (0, inf) for a move of no length; None when
    the arm cannot put the hand at a pose of the move. The one rule both the scenario's
    load-time check and the state machine's run-time moves (followable_move_s) apply."""
    distance = float(np.linalg.norm(np.subtract(end_xyz, start_xyz, dtype=float)))
    if distance <= 0.0:
        return 0.0, math.inf
    tops = move_top_speeds_mps(start_xyz, end_xyz)
    if tops is None:
        return None
    shortest, binding = 0.0, math.inf
    for tau, top in tops:
        needed = distance * minimum_jerk_slope(tau) / top
        if needed > shortest:
            shortest, binding = needed, top
    return shortest, binding


def followable_move_s(start_xyz, end_xyz, move_s: float) -> tuple[float, str]:
    """(duration [s], note) of a move the state machine decides at run time (Avoid along a
    hit's push, a Re-Reach's shift), whose direction no load-time check could know:
    move_s [s], the configured duration, stretched to the shortest the arm follows along
    it (shortest_move_s) rounded up to the millisecond when that is longer. note: "" when
    move_s stands, else why it was stretched; a move the arm cannot reach keeps move_s
    (it lags whatever its duration) and says so. Once per corrective move, a few ms."""
    found = shortest_move_s(start_xyz, end_xyz)
    if found is None:
        return move_s, (f"out of the JACO2's reach in the side grasp: kept at "
                        f"{move_s:g} s")
    shortest, binding = found
    needed = math.ceil(shortest * 1000.0 - 1e-9) / 1000.0
    if needed <= move_s:
        return move_s, ""
    distance = float(np.linalg.norm(np.subtract(end_xyz, start_xyz, dtype=float)))
    return needed, (f"{distance * 1000:.0f} mm stretched from {move_s:g} s to {needed:g} s, "
                    f"the shortest the JACO2 follows that way (its top hand speed "
                    f"{binding:.3g} m/s where it binds)")


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
