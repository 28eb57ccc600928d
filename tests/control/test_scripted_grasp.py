"""The open-loop grasp script's segments: their times in range and in order."""

import pytest
from pydrake.math import RigidTransform

from tegrasp_drake.control.scripted_grasp import (PHASES, ScriptSegment, plan_scripted_grasp,
                                                  sample_plan)
from tegrasp_drake.rig.ranges import unranged_numeric_fields
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, grasp_plan

OPEN = (3.0, 0.0, 0.0)


def _segment(t_start: float, t_end: float) -> ScriptSegment:
    return ScriptSegment("reach", t_start, t_end, RigidTransform(), RigidTransform(), OPEN)


def test_every_numeric_field_of_a_segment_declares_its_range():
    assert unranged_numeric_fields(ScriptSegment) == []


@pytest.mark.parametrize("t_start, t_end, words", [
    (-0.5, 1.0, "field 't_start' must be at least 0 s"),
    (0.0, float("nan"), "field 't_end' must be a finite number"),
    (2.0, 1.0, "field 't_end' must not be before t_start = 2 s"),
])
def test_a_segment_out_of_range_or_order_is_refused_naming_the_field(t_start, t_end, words):
    with pytest.raises(ConfigError) as refused:
        _segment(t_start, t_end)
    message = str(refused.value)
    assert "\n" not in message and message.startswith("ScriptSegment: ")
    assert words in message, message


def test_a_phase_of_no_time_is_planned_and_passed_over():
    """grasp.settle_s and grasp.hold_s may be 0: their segments start and end together."""
    plan = grasp_plan(LoadScenario(overrides=["grasp.settle_s=0", "grasp.hold_s=0"]))
    segments = plan_scripted_grasp(plan)
    settle, hold = segments[PHASES.index("settle")], segments[PHASES.index("hold")]
    assert settle.t_start == settle.t_end == 0.0 and hold.t_start == hold.t_end
    assert PHASES[sample_plan(segments, 0.0)[2]] == "reach"
    assert PHASES[sample_plan(segments, hold.t_start)[2]] == "place"
