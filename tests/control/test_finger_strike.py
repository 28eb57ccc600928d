"""The taxel_aware controller's finger-strike sense: the wrench from the arm's joint
torques, which finger struck, the shift; only taxel_aware reads the torques."""

import numpy as np
import pytest
from pydrake.multibody.tree import JacobianWrtVariable

from tegrasp_drake.control.controller_config import TaxelAwareControllerConfig
from tegrasp_drake.control.finger_strike import (
    FINGER_FRONT_M, grasp_wrench_from_torques, pad_touch_shift, side_moment_nm,
    strike_force_n, strike_shift, struck_finger)
from tegrasp_drake.rig.arm_kinematics import IK_SEED, make_arm_control_plant

CONFIG = TaxelAwareControllerConfig()
STRIKE = CONFIG.taxel_aware.finger_strike
NO_CONTACT = (False, False)
BOX_WIDTH_M = 0.045
OPEN_M = 0.085


def _grasp_jacobian(q=IK_SEED):
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, q)
    world = plant.world_frame()
    return plant.CalcJacobianSpatialVelocity(context, JacobianWrtVariable.kV,
                                             plant.GetFrameByName("grasp_frame"),
                                             np.zeros(3), world, world)


def _push_at(point_G, force_W):
    """The wrench at G's origin [N m, N] of force_W [N] acting at point_G [m, from G's
    origin, world axes]."""
    return np.concatenate([np.cross(point_G, force_W), force_W])


def test_the_wrench_is_recovered_from_the_torques_that_hold_it():
    J = _grasp_jacobian()
    wrench = np.array([0.3, -0.2, 0.5, -4.0, 1.0, 2.0])
    torques = -J.T @ wrench  # the actuators balance the wrench on the arm
    np.testing.assert_allclose(grasp_wrench_from_torques(J, torques), wrench, atol=1e-9)


def test_a_push_against_the_approach_on_the_left_finger_reads_as_the_left_finger():
    """The left finger's front (+42 mm along the stroke, world +y) pushed back (-x)."""
    for y, finger in ((0.042, "left"), (-0.042, "right")):
        wrench = _push_at([0.0, y, 0.0], [-5.0, 0.0, 0.0])
        moment = side_moment_nm(wrench, np.zeros(6))
        assert strike_force_n(wrench, np.zeros(6)) == pytest.approx(5.0)
        assert struck_finger(3 * moment, NO_CONTACT, STRIKE) == finger


def test_the_baseline_is_taken_off_before_the_threshold():
    baseline = np.array([0.0, 0.1, 0.0, 0.4, 0.0, -0.3])  # the Reach's own, at its start
    assert strike_force_n(baseline, baseline) == 0.0
    pushed = baseline + _push_at([0.0, 0.042, 0.0], [-STRIKE.force_n - 0.5, 0.0, 0.0])
    assert strike_force_n(pushed, baseline) > STRIKE.force_n


def test_a_touching_pad_names_the_finger_and_a_small_moment_names_none():
    assert struck_finger(-1.0, (True, False), STRIKE) == "left"  # the taxels see it
    assert struck_finger(1.0, (False, True), STRIKE) == "right"
    assert struck_finger(0.5 * STRIKE.min_moment_nm, NO_CONTACT, STRIKE) is None
    assert struck_finger(0.5 * STRIKE.min_moment_nm, (True, True), STRIKE) is None


def test_the_shift_moves_toward_the_struck_finger_by_the_half_gap_and_the_front():
    assert FINGER_FRONT_M == pytest.approx(0.014)  # pad 4 mm, backing 10 mm
    assert strike_shift("left", OPEN_M, BOX_WIDTH_M) == pytest.approx(0.027)
    assert strike_shift("right", OPEN_M, BOX_WIDTH_M) == pytest.approx(-0.027)
    assert strike_shift(None, OPEN_M, BOX_WIDTH_M) == 0.0
    assert strike_shift("left", 0.03, BOX_WIDTH_M) == 0.0  # never away


@pytest.mark.parametrize("width_m", [0.045, 0.060])
def test_after_the_shift_both_pads_clear_wherever_the_front_met_the_face(width_m):
    """The struck (left) side's face anywhere from the pad's face to the front's back: both
    pads clear it by (opening - width - front) / 2 at least; the wide light box 25 mm along
    the stroke (face 55 mm out) was left no clearance by (opening - width) / 2."""
    shift = strike_shift("left", OPEN_M, width_m)
    for face in np.linspace(OPEN_M / 2, OPEN_M / 2 + FINGER_FRONT_M, 15):
        struck_pad = OPEN_M / 2 + shift - face
        other_pad = face - width_m + OPEN_M / 2 - shift
        least = (OPEN_M - width_m - FINGER_FRONT_M) / 2
        assert min(struck_pad, other_pad) >= least - 1e-12 and least > 0


def test_the_wide_light_box_25_mm_along_the_stroke_is_cleared_by_the_struck_pad():
    """Its face 25 + 60 / 2 = 55 mm out, behind the pad's 42.5 mm: (opening - width) / 2
    put the struck pad on it; the shift with the front clears it by 7 mm."""
    face_m = 0.025 + 0.060 / 2
    assert OPEN_M / 2 + pad_touch_shift("left", OPEN_M, 0.060) - face_m == pytest.approx(0.0)
    assert OPEN_M / 2 + strike_shift("left", OPEN_M, 0.060) - face_m == pytest.approx(0.007)


def test_a_pad_touch_shifts_by_the_half_gap():
    assert pad_touch_shift("left", OPEN_M, BOX_WIDTH_M) == pytest.approx(0.02)
    assert pad_touch_shift("right", OPEN_M, BOX_WIDTH_M) == pytest.approx(-0.02)
    assert pad_touch_shift(None, OPEN_M, BOX_WIDTH_M) == 0.0


def test_the_settings_are_given_with_set_and_checked():
    from tegrasp_drake.scenario.scenario import ConfigError, LoadScenario
    scenario = LoadScenario(overrides=["controller.name=taxel_aware",
                                       "controller.taxel_aware.finger_strike.enabled=false"])
    assert scenario.controller.taxel_aware.finger_strike.enabled is False
    with pytest.raises(ConfigError, match="finger_strike.force_n"):
        LoadScenario(overrides=["controller.taxel_aware.finger_strike.force_n=-1.0"],
                     controller="taxel_aware")
    with pytest.raises(ConfigError, match="a setting of the taxel_aware controller: select one "
                       "with --set controller.name=taxel_aware"):
        LoadScenario(overrides=["controller.taxel_aware.finger_strike.enabled=false"])


@pytest.mark.parametrize("controller,wired", [("taxel_aware", True), ("memorized", False)])
def test_only_taxel_aware_reads_the_joint_torques(controller, wired):
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    from tegrasp_drake.scenario.scenario import LoadScenario
    grasp = MakeGraspDiagram(LoadScenario(controller=controller), log=False)
    assert grasp.diagram.HasSubsystemNamed("grasp_wrench_estimator") == wired
    machine = grasp.controller.state_machine
    context = machine.GetMyContextFromRoot(grasp.diagram.CreateDefaultContext())
    assert machine.GetInputPort("grasp_wrench").HasValue(context) == wired
