"""One comparison of a result's offset with where its trial put the object, within
OFFSET_TOLERANCE_M, read by a sweep's records and by its trial logs' check alike."""

from tegrasp_drake.scenario import object_placement
from tegrasp_drake.scenario.object_placement import OFFSET_TOLERANCE_M, result_offset_problem
from tegrasp_drake.sweep import records, trial_function


def test_an_offset_within_the_tolerance_is_its_trials():
    assert result_offset_problem([0.01, -0.02], [0.01 + OFFSET_TOLERANCE_M / 2, -0.02]) is None


def test_an_offset_past_the_tolerance_or_of_another_length_is_named_with_both():
    problem = result_offset_problem([0.01, 0.0], [0.01 + 2 * OFFSET_TOLERANCE_M, 0.0])
    assert problem.startswith("[0.01, 0.0] m is not [0.0100000020"), problem
    assert result_offset_problem([0.01], [0.01, 0.0]).startswith("[0.01] m is not")


def test_the_sweeps_records_and_log_check_use_the_one_comparison():
    assert records.result_offset_problem is object_placement.result_offset_problem
    assert trial_function.result_offset_problem is object_placement.result_offset_problem
    assert not hasattr(records, "OFFSET_TOLERANCE_M")
