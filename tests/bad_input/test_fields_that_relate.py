"""Settings each within its own range that contradict another setting are refused at load,
in one line naming both: a Lift-Load cap below the grip it raises, and a scripted or
corrective move faster than the arm can follow."""

import pytest

import tegrasp_drake as T
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
