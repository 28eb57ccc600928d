"""Bad inputs the eighteenth hostile pass found, one test per rule: a trial function whose
result names another trial's seed, controller, object or offset is recorded as an invalid
result when it runs (before, it was written as a finished record, which every later read
refused as corrupt); a Dask scheduler that goes away during a sweep is one line and exit 1
(before: distributed's tracebacks, and its trials counted as left by dead workers)."""

import contextlib
import re
import subprocess
import sys
import time

import pytest

from tegrasp_drake.sweep.records import load_records
from tegrasp_drake.sweep.runner import run_sweep, run_trial_safely
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tests import killed_runs
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


def _scheduler_process(log_path):
    """`dask scheduler` on a free port, and its address (from its log)."""
    with open(log_path, "w") as log:  # the scheduler holds its own copy of the file
        process = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
             "--port", "0", "--no-dashboard"], stdout=log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 300.0
    while True:
        address = re.search(r"Scheduler at:\s*(tcp://\S+)", log_path.read_text())
        if address:
            return process, address.group(1)
        assert process.poll() is None and time.monotonic() < deadline, log_path.read_text()
        time.sleep(0.2)


def test_a_scheduler_that_goes_away_mid_sweep_is_one_line_and_its_trials_kept(tmp_path):
    pytest.importorskip("distributed", reason="the optional 'dask' extra is not installed")
    scheduler, address = _scheduler_process(tmp_path / "scheduler.log")
    worker = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nworkers", "1",
         "--nthreads", "1", "--no-dashboard"], env=killed_runs.environment(),
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = tmp_path / "out"
    sweep = subprocess.Popen(
        [sys.executable, "-m", "tegrasp_drake", "sweep", "--scheduler", address, "--out",
         str(out), "--trial-function", "tests.fake_trials:slow_fake_trial", "--no-progress"],
        env=killed_runs.environment(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        text=True)
    try:
        deadline = time.monotonic() + 300.0
        while len(list((out / "trials").glob("*.json"))) < 3:  # trials are being recorded
            assert sweep.poll() is None and time.monotonic() < deadline, sweep.communicate()
            time.sleep(0.1)
        scheduler.kill()
        text, err = sweep.communicate(timeout=600)
    finally:
        for process in (sweep, worker, scheduler):
            with contextlib.suppress(ProcessLookupError):
                process.kill()
            process.wait()
    assert sweep.returncode == 1, err
    assert text == "" and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    finished = re.search(r"lost the Dask scheduler at \S+ after (\d+) of 243 trials", err)
    assert finished, err
    records = load_records(out)
    assert not records.corrupt and len(records.records) == int(finished.group(1)), err
