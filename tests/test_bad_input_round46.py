"""Bad inputs the eighteenth hostile pass found, one test per rule: a trial function whose
result names another trial's seed, controller, object or offset is recorded as an invalid
result when it runs (before, it was written as a finished record, which every later read
refused as corrupt)."""

import pytest

from tegrasp_drake.sweep.records import load_records
from tegrasp_drake.sweep.runner import run_sweep, run_trial_safely
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tests.fake_trials import fake_trial

SPEC = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1, base_seed=650)


def _first_trial() -> dict:
    return expand_trials(SPEC)[0].to_dict()


@pytest.mark.parametrize("field, value", [("seed", 1), ("controller", "heuristic"),
                                          ("object", "thin_cylinder"),
                                          ("offset_m", [0.0123, -0.0045])])
def test_a_result_that_names_another_trial_is_an_invalid_result(field, value):
    trial = _first_trial()
    status, error, _ = run_trial_safely(lambda t: dict(fake_trial(t), **{field: value}), trial)
    assert status == "error" and error["type"] == "InvalidResult", error
    assert f"its result's {field}" in error["message"]


def test_such_a_result_is_recorded_as_an_error_not_as_a_corrupt_record(tmp_path):
    summary = run_sweep(SPEC, seed_of_another_trial, tmp_path, workers=1, progress=False)
    records = load_records(tmp_path)
    assert not records.corrupt, records.corrupt
    assert len(records.records) == len(summary.trial_ids) == len(summary.errors)
    assert {record["status"] for record in records.records.values()} == {"error"}
    assert {record["error"]["type"] for record in records.records.values()} == {"InvalidResult"}


def seed_of_another_trial(trial):
    """A trial function that reports the next trial's seed (module level: it is pickled)."""
    return dict(fake_trial(trial), seed=trial["seed"] + 1)
