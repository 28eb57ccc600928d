"""Fixed-input tests of the control package's LeafSystems that no other test drives:
GraspWrenchEstimator (statics against a finite-difference Jacobian), HeuristicEventDetector
(each transition's thresholds) and ScriptedGraspSource (the minimum-jerk script at known
times)."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix

from tegrasp_drake.control.controller_config import HeuristicTriggerConfig
from tegrasp_drake.control.grasp_wrench_estimator import GraspWrenchEstimator
from tegrasp_drake.control.heuristic_event_detector import HeuristicEventDetector
from tegrasp_drake.control.scripted_grasp import PHASES, ScriptSegment, ScriptedGraspSource
from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant

# GraspWrenchEstimator --------------------------------------------------------------------

ARM_Q = np.array([0.3, 2.9, 1.3, -2.1, 1.4, 0.2])  # rad, away from singularities


def _grasp_frame_motion(q: np.ndarray, step: float = 1e-6) -> np.ndarray:
    """(6, 6): column i is G's spatial velocity [w; v] in world per unit velocity of joint i,
    from central differences of G's pose (the plant's kinematics, not its Jacobian)."""
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    frame = plant.GetFrameByName("grasp_frame")

    def pose(q_at):
        plant.SetPositions(context, q_at)
        return plant.CalcRelativeTransform(context, plant.world_frame(), frame)

    columns = []
    for i in range(6):
        dq = np.zeros(6)
        dq[i] = step
        X_plus, X_minus = pose(q + dq), pose(q - dq)
        R_delta = (X_plus.rotation() @ X_minus.rotation().inverse()).ToAngleAxis()
        w = R_delta.axis() * R_delta.angle() / (2 * step)
        v = (X_plus.translation() - X_minus.translation()) / (2 * step)
        columns.append(np.concatenate([w, v]))
    return np.array(columns).T


def test_grasp_wrench_is_the_wrench_whose_virtual_work_the_joint_torques_balance():
    # Statics: joint torques tau hold a wrench w on the arm at G when tau = -J^T w (the
    # virtual work of w over any joint motion is cancelled by the joints'). Pick w, make tau
    # from the finite-difference motion of G, and the estimator must give w back.
    wrench = np.array([0.2, -0.5, 0.1, 3.0, -4.0, 12.0])  # [N m, N]
    torques = -_grasp_frame_motion(ARM_Q).T @ wrench
    estimator = GraspWrenchEstimator()
    context = estimator.CreateDefaultContext()
    estimator.GetInputPort("arm.position_measured").FixValue(context, ARM_Q)
    estimator.GetInputPort("arm.torque_measured").FixValue(context, torques)
    # Central differences of step 1e-6 rad: truncation about 1e-12, rounding about 1e-10
    # relative, on torques of about 10 N m.
    np.testing.assert_allclose(estimator.GetOutputPort("wrench").Eval(context), wrench,
                               rtol=0, atol=1e-6)


def test_grasp_wrench_is_zero_without_joint_torque():
    estimator = GraspWrenchEstimator()
    context = estimator.CreateDefaultContext()
    estimator.GetInputPort("arm.position_measured").FixValue(context, ARM_Q)
    estimator.GetInputPort("arm.torque_measured").FixValue(context, np.zeros(6))
    np.testing.assert_array_equal(estimator.GetOutputPort("wrench").Eval(context), np.zeros(6))


# HeuristicEventDetector ------------------------------------------------------------------

TRIGGERS = HeuristicTriggerConfig(contact_force_n=1.0, grip_fraction=0.9, place_ra_mps2=3.0)
GRIP_N = 20.0  # Load-Lift level: 0.9 * 20 = 18 N per finger


def _detect(channels, expected: int) -> tuple[np.ndarray, float, float]:
    detector = HeuristicEventDetector(TRIGGERS, grip_force_n=GRIP_N)
    context = detector.CreateDefaultContext()
    detector.GetInputPort("channels").FixValue(context, channels)
    detector.GetInputPort("expected_event").FixValue(context, [expected])
    return (detector.GetOutputPort("scores").Eval(context),
            detector.GetOutputPort("match").Eval(context)[0],
            detector.GetOutputPort("scored_event").Eval(context)[0])


@pytest.mark.parametrize("channels, expected, scores, match", [
    # reach_load (0): both SA above 1 N.
    ([1.5, 2.0, 9.0, 9.0], 0, [1.5, 2.0, 0.0, 0.0], 1.0),
    ([1.5, 0.8, 9.0, 9.0], 0, [1.5, 0.8, 0.0, 0.0], 0.0),  # one finger only
    # load_lift (1): both SA above 18 N.
    ([19.8, 18.9, 0.0, 0.0], 1, [1.1, 1.05, 0.0, 0.0], 1.0),
    ([19.8, 17.1, 0.0, 0.0], 1, [1.1, 0.95, 0.0, 0.0], 0.0),
    # place_unload (2): either RA above 3 m/s^2; SA is ignored.
    ([50.0, 50.0, 0.6, 4.5], 2, [0.0, 0.0, 0.2, 1.5], 1.0),
    ([50.0, 50.0, 2.4, 1.5], 2, [0.0, 0.0, 0.8, 0.5], 0.0),
    # no event expected: no scores, no match, whatever the channels.
    ([50.0, 50.0, 9.0, 9.0], -1, [0.0, 0.0, 0.0, 0.0], 0.0),
])
def test_heuristic_scores_are_channels_over_thresholds_and_match_follows_the_rule(
        channels, expected, scores, match):
    got_scores, got_match, scored = _detect(channels, expected)
    np.testing.assert_allclose(got_scores, scores, rtol=1e-12, atol=0)
    assert (got_match, scored) == (match, expected)


def test_heuristic_detector_rejects_an_unknown_event_index():
    with pytest.raises(ValueError, match="expected_event 3 is not -1 or 0..2"):
        _detect([0.0, 0.0, 0.0, 0.0], 3)


# ScriptedGraspSource ---------------------------------------------------------------------

R_START = RotationMatrix(RollPitchYaw(0.0, math.pi / 2, 0.0))
R_END = R_START @ RotationMatrix.MakeZRotation(0.6)  # 0.6 rad about the start's z
START = RigidTransform(R_START, [0.69, 0.0, 0.145])
GRASP = RigidTransform(R_END, [0.70, 0.02, 0.055])
OPEN, CLOSED = (3.0, 0.0, 0.0), (230.0, 0.0, 0.0)
SEGMENTS = [ScriptSegment("settle", 0.0, 0.3, START, START, OPEN),
            ScriptSegment("reach", 0.3, 2.3, START, GRASP, OPEN),
            ScriptSegment("load", 2.3, 3.3, GRASP, GRASP, CLOSED)]


def _script_at(t: float):
    source = ScriptedGraspSource(SEGMENTS)
    context = source.CreateDefaultContext()
    context.SetTime(t)
    return (source.GetOutputPort("X_WG_desired").Eval(context),
            source.GetOutputPort("gripper_command").Eval(context),
            source.GetOutputPort("phase").Eval(context)[0])


@pytest.mark.parametrize("t, s, command, phase", [
    (0.1, 0.0, OPEN, "settle"),
    (0.3, 0.0, OPEN, "reach"),
    # tau = 0.25: s = 10/64 - 15/256 + 6/1024 = 0.103515625
    (0.8, 0.103515625, OPEN, "reach"),
    (1.3, 0.5, OPEN, "reach"),  # tau = 0.5: the minimum-jerk midpoint
    (2.5, 1.0, CLOSED, "load"),
    (9.0, 1.0, CLOSED, "done"),  # after the last segment: its end, phase done
])
def test_script_plays_the_minimum_jerk_move_and_the_phase_command(t, s, command, phase):
    X, got_command, got_phase = _script_at(t)
    np.testing.assert_allclose(X.translation(),
                               (1 - s) * START.translation() + s * GRASP.translation(),
                               rtol=0, atol=1e-12)
    # Both orientations share the approach; the slerp turns s * 0.6 rad about it.
    R_relative = R_START.inverse() @ X.rotation()
    np.testing.assert_allclose(R_relative.matrix(),
                               RotationMatrix.MakeZRotation(s * 0.6).matrix(), rtol=0,
                               atol=1e-12)
    np.testing.assert_array_equal(got_command, command)
    assert got_phase == PHASES.index(phase)

