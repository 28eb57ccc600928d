"""Settings each within its own range that contradict another setting are refused at load,
in one line naming both: a Lift-Load cap below the grip it raises, a scripted or
corrective move faster than the arm can follow, and an object deeper than the hand takes at
its width."""

import pytest

import tegrasp_drake as T
from tegrasp_drake.rig.objects import MAX_WIDTH_M, ObjectConfig, max_depth_m
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.bad_input.probes import refusal


@pytest.mark.parametrize("overrides", [
    ["grasp.grip_force=200", "controller.lift_load.max_grip_force_n=50"],
    ["controller.lift_load.max_grip_force_n=20"],  # below the 25 N default grip
])
def test_a_lift_load_cap_below_the_grip_is_refused_naming_both_fields(overrides):
    refusal(lambda: T.LoadScenario(name="box", overrides=overrides),
            "'controller.lift_load.max_grip_force_n'", "grasp.grip_force", "loosen")


def test_a_lift_load_cap_of_zero_is_out_of_the_grippers_range():
    refusal(lambda: T.LoadScenario(name="box",
                                   overrides=["controller.lift_load.max_grip_force_n=0"]),
            "'controller.lift_load.max_grip_force_n'", "[20, 235]")


def test_a_lift_load_cap_equal_to_the_grip_loads():
    scenario = T.LoadScenario(name="box", overrides=["grasp.grip_force=100",
                                                     "controller.lift_load.max_grip_force_n=100"])
    assert scenario.controller.lift_load.max_grip_force_n == 100


@pytest.mark.parametrize("overrides, field", [
    (["grasp.reach_s=0.001"], "grasp.reach_s"),
    (["grasp.lift_s=0.02", "grasp.lift_height=0.3"], "grasp.lift_s"),
    (["grasp.place_s=0.001"], "grasp.place_s"),
    (["controller.avoid.move_s=0.01"], "controller.avoid.move_s"),
    (["controller.re_reach.move_s=0.001"], "controller.re_reach.move_s"),
])
def test_a_move_faster_than_the_arm_can_follow_is_refused_naming_its_duration(overrides,
                                                                               field):
    refusal(lambda: T.LoadScenario(name="box", controller="memorized", overrides=overrides),
            f"'{field}' is too short to move the hand", "m/s", "give it at least")


@pytest.mark.parametrize("overrides, field, controller, peak, top", [
    # 60 mm up in 0.3 s peaks at 0.375 m/s: the arm lifts the hand at most 0.222 m/s there
    (["grasp.lift_s=0.3"], "grasp.lift_s", "open_loop", "0.375", "0.222"),
    # half the stroke along y in 0.2 s peaks at 0.398 m/s: at most 0.171 m/s there
    (["controller.re_reach.move_s=0.2"], "controller.re_reach.move_s", "memorized", "0.398",
     "0.171"),
])
def test_a_move_under_the_joints_limits_times_the_reach_but_too_fast_at_the_grasp_is_refused(
        overrides, field, controller, peak, top):
    """Under 3.56 m/s (each joint at its limit times the 0.9 m reach, the bound the check
    once had) yet faster than the arm can move the hand that way at the grasp, its
    orientation held: refused in one line with the peak, the arm's top speed there and the
    shortest duration to give."""
    refusal(lambda: T.LoadScenario(name="box", controller=controller, overrides=overrides),
            f"'{field}' is too short to move the hand", f"peaks at {peak} m/s", f"({top} m/s",
            "give it at least")


def test_the_shortest_duration_a_refusal_gives_is_accepted():
    """The refusal's "give it at least T s" is a duration that loads: its bound is the
    same one the check applies."""
    import re
    message = refusal(lambda: T.LoadScenario(name="box", overrides=["grasp.reach_s=0.001"]),
                      "'grasp.reach_s'")
    shortest = re.search(r"give it at least ([0-9.]+) s", message).group(1)
    assert T.LoadScenario(name="box", overrides=[f"grasp.reach_s={shortest}"])


def test_a_zero_length_move_loads_with_a_positive_duration_only():
    """Avoid's distance may be 0 (no move); its duration must still be positive, as every
    arm move's: a move in no time is no duration the arm can follow."""
    scenario = T.LoadScenario(name="box", controller="memorized",
                              overrides=["controller.avoid.distance_m=0",
                                         "controller.avoid.move_s=0.001"])
    assert scenario.controller.avoid.move_s == 0.001
    refusal(lambda: T.LoadScenario(name="box", controller="memorized",
                                   overrides=["controller.avoid.distance_m=0",
                                              "controller.avoid.move_s=0"]),
            "field 'controller.avoid.move_s' must be positive [s]")


@pytest.mark.parametrize("overrides, words", [
    (["object.size=[0.3, 0.045, 0.11]"], "300.0 mm deep along the approach, more than the 85.0 mm"),
    (["object.name=crate", "object.shape=box", "object.size=[0.075, 0.08, 0.1]",
      "object.mass=0.1", "object.friction=0.5"], "75.0 mm deep along the approach"),
    (["object.name=drum", "object.shape=cylinder", "object.size=[0.08, 0.1]",
      "object.mass=0.1", "object.friction=0.5"], "80.0 mm deep along the approach"),
])
def test_an_object_deeper_than_the_hand_takes_is_refused_naming_its_size(overrides, words):
    """Grasped at its centre, an object deeper than twice the pads' reach in front of the palm
    would strike the palm: refused before it is simulated, naming the limit at its width."""
    refusal(lambda: T.LoadScenario(name="box", overrides=overrides),
            "field 'object.size'", words, "short of the palm")


def test_the_deepest_object_the_hand_takes_loads():
    """The refusal's limit is the one the check applies: an object that deep loads."""
    deepest = max_depth_m(0.08)
    scenario = T.LoadScenario(name="box", overrides=[
        "object.name=crate", "object.shape=box", f"object.size=[{deepest}, 0.08, 0.1]",
        "object.mass=0.1", "object.friction=0.5"])
    assert scenario.object.size[0] == deepest


# Rule: a sweep's trials place each object up to randomisation.placement_xy_bound_m off its
# marker along each axis and yaw it up to placement_yaw_bound_deg: the spec is refused when
# the object's fit in the open hand, or its start clearance, fails at the jitter's far end,
# though the object passes on its marker.
def _sweep_with(obj_size, grid=((0.0, 0.0),), xy_bound_m=0.002, yaw_bound_deg=0.0):
    from tegrasp_drake.sweep.spec import RandomisationConfig, SweepSpec
    return SweepSpec(objects=("crate",), controllers=("open_loop",), attempts=1,
                     grid=grid, user_objects={"crate": ObjectConfig(
                         name="crate", shape="box", size=list(obj_size), mass=0.1,
                         friction=0.5)},
                     randomisation=RandomisationConfig(placement_xy_bound_m=xy_bound_m,
                                                       placement_yaw_bound_deg=yaw_bound_deg))


def test_a_sweep_object_as_deep_as_the_hand_takes_is_refused_once_yawed():
    from tegrasp_drake.sweep.spec import validate_spec
    deepest = max_depth_m(0.06)
    validate_spec(_sweep_with([deepest, 0.06, 0.1], xy_bound_m=0.0))  # on its marker: fits
    refusal(lambda: validate_spec(_sweep_with([deepest, 0.06, 0.1], xy_bound_m=0.0,
                                              yaw_bound_deg=3.0)),
            "field 'randomisation'", "object 'crate'", "deep along the approach",
            "yawed 3 deg (the placement jitter's far end)", "short of the palm")


def test_a_sweep_object_as_wide_as_the_stroke_takes_is_refused_once_yawed():
    from tegrasp_drake.sweep.spec import validate_spec
    validate_spec(_sweep_with([0.03, MAX_WIDTH_M, 0.1], xy_bound_m=0.0))
    refusal(lambda: validate_spec(_sweep_with([0.03, MAX_WIDTH_M, 0.1], yaw_bound_deg=3.0)),
            "field 'randomisation'", "wide along the finger stroke",
            "yawed 3 deg (the placement jitter's far end)")


def test_a_sweep_shift_alone_does_not_make_an_object_too_wide_or_deep():
    """The jitter's shift moves the object off its marker, as a misplacement does: an object
    that fits the hand square fits it shifted."""
    from tegrasp_drake.sweep.spec import validate_spec
    validate_spec(_sweep_with([max_depth_m(0.06), 0.06, 0.1], xy_bound_m=0.002))
    validate_spec(_sweep_with([0.03, MAX_WIDTH_M, 0.1], xy_bound_m=0.002))


def test_a_sweep_marker_just_clear_of_the_start_pose_is_refused_once_jittered():
    """The object's marker moved toward the hand's start until the un-jittered check just
    passes: the jitter's 2 mm toward the hand puts the hand inside it."""
    from tegrasp_drake.sweep.spec import validate_spec
    size = T.LoadScenario(name="box").object.size  # the crate is the built-in box's size

    def clear(dx):
        try:
            T.LoadScenario(name="box", overrides=[f"placement.offset=[{dx},0.0]"])
            return True
        except ConfigError:
            return False
    inside, outside = -0.2, 0.0  # the object under the hand's body, and on its marker
    assert not clear(inside) and clear(outside)
    while outside - inside > 1e-5:
        middle = (inside + outside) / 2
        inside, outside = (inside, middle) if clear(middle) else (middle, outside)
    marker = ((round(outside + 0.0005, 4), 0.0),)  # half a millimetre clear of the hand
    validate_spec(_sweep_with(size, grid=marker, xy_bound_m=0.0))
    refusal(lambda: validate_spec(_sweep_with(size, grid=marker)),
            "object 'crate' at marker", "placement jitter", "'arm.initial_gripper_xyz'",
            "inside the object 'crate'", "+-2 mm of placement jitter")


# Rule: a pose of the grasp the arm cannot take is refused at load, naming the fields that
# place it: a move out of the JACO2's reach (the hand speed check found no joint angles for
# it), and a start pose in the table or with the object already within the open hand.
@pytest.mark.parametrize("overrides", [
    ["placement.expected_xy=[0.0,0.0]"],  # the object at the arm's base
    ["placement.expected_xy=[0.1,0.0]"],
    ["arm.initial_gripper_xyz=[0.0,0.0,0.145]"],  # the hand at the arm's base
])
@pytest.mark.parametrize("controller", ["memorized", "open_loop"])
def test_a_move_out_of_the_arms_reach_is_refused_naming_the_fields_that_place_it(
        overrides, controller):
    refusal(lambda: T.LoadScenario(name="box", controller=controller, overrides=overrides),
            "'arm.initial_gripper_xyz', 'placement.expected_xy', 'grasp.grasp_height'",
            "the Reach phase", "out of the JACO2's reach")


@pytest.mark.parametrize("start", ["[0.69,0.0,0.0]", "[0.69,0.0,0.03]", "[0.65,0.1,0.037]"])
def test_a_start_pose_in_the_table_is_refused(start):
    refusal(lambda: T.LoadScenario(name="box", overrides=[f"arm.initial_gripper_xyz={start}"]),
            "'arm.initial_gripper_xyz'", "into the table top")


@pytest.mark.parametrize("overrides", [
    ["arm.initial_gripper_xyz=[0.72,0.03,0.055]"],  # a finger through the box's side
    ["arm.initial_gripper_xyz=[0.75,0.0,0.055]"],  # the palm through its front
    ["arm.initial_gripper_xyz=[0.69,0.0,0.145]", "placement.offset=[-0.1,0.0]"],  # the body
])
def test_a_start_pose_with_the_hand_inside_the_object_is_refused(overrides):
    refusal(lambda: T.LoadScenario(name="box", overrides=overrides),
            "'arm.initial_gripper_xyz'", "a finger inside the object 'box'",
            "placement.expected_xy + placement.offset")


@pytest.mark.parametrize("name", ["box", "thick_cylinder", "thin_cylinder"])
def test_a_start_with_the_open_pads_about_the_object_loads(name):
    # the station's squeeze tests start here: the object between the open pads, 20 mm or
    # more from each
    T.LoadScenario(name=name, overrides=["arm.initial_gripper_xyz=[0.72,0.0,0.055]"])


@pytest.mark.parametrize("name", ["box", "thick_cylinder", "thin_cylinder"])
def test_the_default_start_is_clear_of_the_table_and_each_object(name):
    assert T.LoadScenario(name=name).arm.initial_gripper_xyz == [0.69, 0.0, 0.145]
    # just above the tallest object (120 mm): the fingers 10 mm thick about the grasp axis
    T.LoadScenario(name=name, overrides=["arm.initial_gripper_xyz=[0.69,0.0,0.131]"])


def test_the_command_line_refuses_an_object_at_the_arms_base_before_simulating(tmp_path,
                                                                              capfd):
    from tests.bad_input.probes import assert_one_line_error, run_cli
    code, text = run_cli(["trial", "--out", str(tmp_path / "run"), "--set",
                          "placement.expected_xy=[0.0,0.0]"], capfd)
    assert_one_line_error(code, text, "'placement.expected_xy'", "out of the JACO2's reach")
    assert code == 1 and not (tmp_path / "run").exists(), text


def test_a_sweep_grid_putting_the_object_into_the_hand_is_refused(tmp_path, capfd):
    from tests.bad_input.probes import assert_one_line_error, run_cli
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[-0.1, 0.0]]\n")
    code, text = run_cli(["sweep", "--dry-run", "--spec", str(spec), "--out",
                          str(tmp_path / "out")], capfd)
    assert_one_line_error(code, text, "'arm.initial_gripper_xyz'", "inside the object")
    assert code == 2, text  # a spec whose trial is refused is a spec refused, not missing events
