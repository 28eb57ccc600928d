"""GraspPlan: the grasp script placed for the expected object, its numbers in range."""

import dataclasses

import pytest

from tegrasp_drake.control.machine_state import GraspPlan
from tegrasp_drake.rig.ranges import unranged_numeric_fields
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, grasp_plan


def test_every_numeric_field_of_a_plan_declares_its_range():
    assert unranged_numeric_fields(GraspPlan) == []


@pytest.mark.parametrize("fields, words", [
    ({"hold_s": -1.0}, "field 'hold_s' must lie in [0, 60] s"),
    ({"reach_s": 0.0}, "field 'reach_s' must lie in (0, 30] s"),
    ({"grip_force": 1e4}, "field 'grip_force' must lie in [20, 235] N"),
    ({"object_width": float("nan")}, "field 'object_width' must be a finite number"),
    ({"object_height": 0.0}, "field 'object_height' must lie in [0.005, 0.5] m"),
    ({"start_xyz": (0.69, 0.0, 5.0)}, "field 'start_xyz[2]' must lie in [-0.9, 0.9] m"),
    ({"object_xy": (0.72, float("inf"))}, "field 'object_xy[1]' must be a finite number"),
    ({"place_offset": (0.0, 0.0, 0.0)}, "field 'place_offset' must hold 2 numbers [m]"),
])
def test_a_plan_with_a_value_out_of_its_range_is_refused_naming_the_field(fields, words):
    plan = grasp_plan(LoadScenario())
    with pytest.raises(ConfigError) as refused:
        dataclasses.replace(plan, **fields)
    message = str(refused.value)
    assert "\n" not in message and message.startswith("GraspPlan: ")
    assert words in message, message


def test_a_wide_object_on_the_farthest_marker_is_planned():
    """The grasp frame's target lies beyond the marker by the pads' offset (a 70 mm box: the
    linkage's open pads sit behind the grasp frame), so past the marker's 0.9 m range. The
    arm stretched that far moves the hand at most 0.127 m/s on the way: the Reach and the
    Retract to the start are given the 3.5 s they then take."""
    scenario = LoadScenario(overrides=[
        "placement.expected_xy=[0.9, 0.0]", "grasp.reach_s=3.5", "grasp.retract_s=3.5", "object.name=wide_box", "object.shape=box",
        "object.size=[0.07, 0.07, 0.1]", "object.mass=0.1", "object.friction=0.5"])
    assert grasp_plan(scenario).object_xy[0] > 0.9
