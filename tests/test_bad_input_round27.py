"""Bad inputs the fourteenth hostile pass found in sweep records, one test per rule."""

import json

import pytest

from tegrasp_drake.sweep.records import _checksum, load_records, record_path
from tegrasp_drake.sweep.runner import run_sweep
from tegrasp_drake.sweep.spec import SweepSpec
from tests.fake_trials import fake_trial

ONE_TRIAL = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1,
                      grid=((0.0, 0.0),))


def _forge(folder, edit):
    """Runs ONE_TRIAL into `folder`, then rewrites its record's result with `edit` and a
    checksum that matches, as a hand edit would; returns the record's path."""
    summary = run_sweep(ONE_TRIAL, fake_trial, folder, workers=1, progress=False)
    path = record_path(folder, summary.trial_ids[0])
    record = json.loads(path.read_text())
    edit(record["result"])
    del record["checksum"]
    record["checksum"] = _checksum(record)
    path.write_text(json.dumps(record))
    return path


def _set(**fields):
    return lambda result: result.update(fields)


@pytest.mark.parametrize("edit, field", [
    (_set(hold_success="yes"), "hold_success"),
    (_set(final_mode="Exploded"), "Exploded"),
    (_set(final_tilt_deg=720.0), "final_tilt_deg"),
    (lambda result: result["transitions"][0].update(t=-3.0), "field 't'"),
])
def test_a_record_whose_result_is_out_of_range_is_corrupt_and_runs_again(
        tmp_path, edit, field):
    path = _forge(tmp_path, edit)
    loaded = load_records(tmp_path)
    assert loaded.records == {}
    assert field in loaded.corrupt[path] and "'result'" in loaded.corrupt[path]
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.skipped, summary.corrupt) == (1, 0, (str(path),))
    assert list(tmp_path.glob("trials/*.corrupt-*"))  # kept aside, not lost
    assert load_records(tmp_path).corrupt == {}


def _failed(result):
    """The result of a trial that failed in Load, with a reason of 50000 characters."""
    result["transitions"][1:] = [{"t": 2.0, "from": "Load", "to": "Failed", "trigger": "timer",
                                  "reason": "no Load-Lift event"}]
    result.update(final_mode="Failed", hold_success=False, unload_success=False,
                  released=False, failure="x" * 50000)


@pytest.mark.parametrize("edit, field", [
    (_set(hold_success=False, unload_success=True), "'unload_success' is true"),
    (lambda result: result["detection_latency_s"].update({"reach->load": 1e300}),
     "detection_latency_s.reach->load"),
    (lambda result: result["transitions"][0].update(t=9.0), "transitions[0].t"),
    (_set(physical_events={"reach_load": 50.0}), "physical_events.reach_load"),
    (_set(hold_time_s=9.0), "hold_time_s"),
    (_failed, "'failure' must be at most"),
])
def test_a_record_whose_result_contradicts_itself_is_corrupt(tmp_path, edit, field):
    path = _forge(tmp_path, edit)
    loaded = load_records(tmp_path)
    assert loaded.records == {}
    assert field in loaded.corrupt[path]


def unload_without_hold_trial(trial):
    """fake_trial's result, unloaded without a hold: no trial run produces it."""
    return {**fake_trial(trial), "hold_success": False, "unload_success": True}


def test_a_trial_function_result_the_records_would_refuse_is_an_error_not_a_record(tmp_path):
    summary = run_sweep(ONE_TRIAL, unload_without_hold_trial, tmp_path, workers=1,
                        progress=False)
    record = load_records(tmp_path).records[summary.errors[0]]
    assert record["error"]["type"] == "InvalidResult"
    assert "'unload_success' is true" in record["error"]["message"]


def forge_record(folder, spec, trial_id, edit):
    """Runs `spec` with fake trials into `folder`, then rewrites the record of `trial_id`
    (None: the first trial's) with `edit` (given the whole record, its result included) and a
    checksum that matches, as a hand edit would; returns its path."""
    summary = run_sweep(spec, fake_trial, folder, workers=1, progress=False)
    path = record_path(folder, trial_id or summary.trial_ids[0])
    record = json.loads(path.read_text())
    edit(record)
    del record["checksum"]
    record["checksum"] = _checksum(record)
    path.write_text(json.dumps(record))
    return path


def _forge_record(folder, edit):
    return forge_record(folder, ONE_TRIAL, None, edit)


# Rule: a record is its trial's: a result naming another seed, controller or object, or a
# record holding both a result and an error, is corrupt (kept aside, its trial run again).
@pytest.mark.parametrize("edit, words", [
    (lambda r: r["result"].update(seed=r["trial"]["seed"] + 1), "result's seed"),
    (lambda r: r["result"].update(controller="heuristic"), "result's controller"),
    (lambda r: r["result"].update(object="thin_cylinder"), "result's object"),
    (lambda r: r.update(status="error", error={"type": "RuntimeError", "message": "x"}),
     "an error and no result"),
    (lambda r: r["trial"].update(trial_id="heuristic/box/m00/a0"), "trial_id"),
])
def test_a_record_of_another_trial_is_corrupt_and_runs_again(tmp_path, edit, words):
    path = _forge_record(tmp_path, edit)
    loaded = load_records(tmp_path)
    assert loaded.records == {} and words in loaded.corrupt[path], loaded.corrupt
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.skipped) == (1, 0)


# Rule: a FIFO or a device link in a record's place is a record that cannot be read: named in
# one warning, kept aside as NAME.corrupt-PID (the entry itself), and its trial runs again.
@pytest.mark.parametrize("make", [
    lambda path: __import__("os").mkfifo(path),
    lambda path: path.symlink_to("/dev/zero"),
], ids=["fifo", "device-link"])
def test_a_record_that_is_no_file_is_kept_aside_with_a_warning(tmp_path, caplog, make):
    import logging
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    path = record_path(tmp_path, summary.trial_ids[0])
    path.unlink()
    make(path)
    with caplog.at_level(logging.WARNING):
        summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.skipped) == (1, 0)
    assert any(path.name in message and "kept as" in message for message in caplog.messages)
    (kept,) = list(path.parent.glob(f"{path.name}.corrupt-*"))
    assert kept.is_symlink() or not kept.is_file()
    assert path.is_file() and load_records(tmp_path).corrupt == {}
