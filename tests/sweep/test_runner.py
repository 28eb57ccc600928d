"""The sweep runner on a local process pool: recording, resuming, errors, refusals."""

import fcntl
import logging
import os
import sys

import pytest

from tegrasp_drake.sweep.records import load_records, record_path
from tegrasp_drake.sweep.runner import SweepError, run_sweep
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tegrasp_drake.rig.files import UserPathError
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.commands.test_run_folder import _ended_process_id
from tests.killed_runs import killed_before_rename
from tests.fake_trials import (
    dying_fake_trial,
    failing_fake_trial,
    fake_trial,
    invalid_result_trial,
    numpy_fake_trial,
)

SMALL = SweepSpec(objects=("box",), controllers=("memorized", "open_loop"), attempts=2)


def record_texts(out_dir):
    return {p.name: p.read_bytes() for p in sorted((out_dir / "trials").iterdir())}


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """The records of one uninterrupted run of SMALL."""
    out_dir = tmp_path_factory.mktemp("uninterrupted")
    summary = run_sweep(SMALL, fake_trial, out_dir, workers=2, progress=False)
    return out_dir, summary


def test_every_trial_is_recorded_with_its_result(uninterrupted):
    out_dir, summary = uninterrupted
    trials = expand_trials(SMALL)
    assert (summary.total, summary.ran, summary.skipped) == (36, 36, 0)
    assert summary.errors == summary.unfinished == summary.corrupt == ()
    records = load_records(out_dir).records
    assert set(records) == {t.trial_id for t in trials}
    for trial in trials:
        record = records[trial.trial_id]
        assert record["status"] == "ok"
        assert record["trial"] == trial.to_dict()
        assert record["result"] == fake_trial(trial.to_dict())


def test_rerun_skips_every_finished_trial(tmp_path):
    run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    before = {p: p.stat().st_mtime_ns for p in (tmp_path / "trials").iterdir()}
    # Any trial run again would now be recorded as an error.
    summary = run_sweep(SMALL, failing_fake_trial, tmp_path, workers=2, progress=False)
    assert (summary.ran, summary.skipped, summary.errors) == (0, 36, ())
    assert {p: p.stat().st_mtime_ns for p in (tmp_path / "trials").iterdir()} == before


def test_resume_reruns_missing_corrupt_and_half_written_trials(tmp_path, uninterrupted):
    run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    ids = [t.trial_id for t in expand_trials(SMALL)]
    record_path(tmp_path, ids[0]).unlink()
    truncated = record_path(tmp_path, ids[5])
    truncated.write_bytes(truncated.read_bytes()[:40])
    stray = truncated.parent / f".{truncated.name}.x1y2abcd.{_ended_process_id()}.staging"
    stray.write_text("{")

    summary = run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    assert (summary.ran, summary.skipped) == (2, 34)
    assert summary.corrupt == (str(truncated),)
    assert not stray.exists()
    (kept,) = (tmp_path / "trials").glob(f"{truncated.name}.corrupt-*")  # set aside, not lost
    kept.unlink()
    assert record_texts(tmp_path) == record_texts(uninterrupted[0])


# Rule: a resumed sweep removes what a write of one of its records killed past its handlers
# (SIGKILL) left, and only that: an earlier version's temporary file (no writer's id: perhaps
# a live run's, and told), a live writer's staging file and one of other content stay.
def test_a_resumed_sweep_removes_a_killed_record_writes_leftover_and_keeps_the_rest(tmp_path,
                                                                                    caplog):
    run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    trial_id = expand_trials(SMALL)[0].trial_id
    path = record_path(tmp_path, trial_id)
    killed_before_rename("from tegrasp_drake.sweep.records import write_record\n"
                         f"write_record({str(tmp_path)!r}, {{'trial_id': {trial_id!r}}})")
    (left,) = path.parent.glob(f".{path.name}.*")
    dead = _ended_process_id()
    kept = {path.parent / f".{path.name}.abcd1234.tmp": b'{"format"',  # an earlier version's
            path.parent / f".{path.name}.efgh5678.{os.getpid()}.staging": b"{",  # live
            path.parent / f".{path.name}.ijkl9012.{dead}.staging": b"my notes"}  # not JSON
    for kept_path, data in kept.items():
        kept_path.write_bytes(data)
    with caplog.at_level(logging.WARNING, logger="tegrasp_drake.sweep.runner"):
        summary = run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    assert (summary.ran, summary.corrupt) == (0, ())
    assert not left.exists()
    assert all(kept_path.read_bytes() == data for kept_path, data in kept.items())
    assert "1 temporary file(s) of an earlier version" in caplog.text


def test_a_trial_that_raises_is_recorded_and_rerun_on_resume(tmp_path, uninterrupted):
    summary = run_sweep(SMALL, failing_fake_trial, tmp_path, workers=2, progress=False)
    failed = [t.trial_id for t in expand_trials(SMALL) if t.attempt == 1]
    assert sorted(summary.errors) == sorted(failed) and summary.ran == 36
    record = load_records(tmp_path).records[failed[0]]
    assert record["status"] == "error" and record["result"] is None
    assert record["error"]["type"] == "RuntimeError"
    assert "simulated divergence" in record["error"]["traceback"]

    summary = run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    assert (summary.ran, summary.skipped, summary.errors) == (18, 18, ())
    assert record_texts(tmp_path) == record_texts(uninterrupted[0])


def test_a_result_without_the_success_booleans_is_an_error(tmp_path):
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1,
                     grid=((0.0, 0.0),))
    summary = run_sweep(spec, invalid_result_trial, tmp_path, workers=1, progress=False)
    record = load_records(tmp_path).records[summary.errors[0]]
    assert record["error"]["type"] == "InvalidResult"
    assert "hold_success" in record["error"]["message"]


def test_numpy_results_are_stored_as_plain_json(tmp_path, uninterrupted):
    summary = run_sweep(SMALL, numpy_fake_trial, tmp_path, workers=2, progress=False)
    assert summary.errors == ()
    assert record_texts(tmp_path) == record_texts(uninterrupted[0])


def test_a_dead_worker_leaves_trials_unfinished_for_the_next_run(tmp_path, uninterrupted):
    summary = run_sweep(SMALL, dying_fake_trial, tmp_path, workers=2, progress=False)
    assert "memorized/box/m11/a0" in summary.unfinished
    assert summary.ran + len(summary.unfinished) == 36
    records = load_records(tmp_path).records
    assert not set(summary.unfinished) & set(records)

    summary = run_sweep(SMALL, fake_trial, tmp_path, workers=2, progress=False)
    assert summary.unfinished == ()
    assert record_texts(tmp_path) == record_texts(uninterrupted[0])


def test_a_folder_of_a_different_sweep_is_refused(tmp_path):
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1)
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    before = record_texts(tmp_path)
    with pytest.raises(SweepError, match="other settings"):
        run_sweep(SweepSpec(objects=("box",), controllers=("memorized",), attempts=1,
                            base_seed=5), fake_trial, tmp_path, workers=1, progress=False)
    assert record_texts(tmp_path) == before


def test_a_sweep_already_writing_the_folder_is_refused(tmp_path):
    held = os.open(tmp_path, os.O_RDONLY | os.O_DIRECTORY)  # as another run holds it
    try:
        fcntl.flock(held, fcntl.LOCK_EX)
        with pytest.raises(UserPathError, match="another run .* is writing there now"):
            run_sweep(SMALL, fake_trial, tmp_path, workers=1, progress=False)
    finally:
        os.close(held)
    assert not (tmp_path / "trials").exists()


def test_bad_input_stops_before_anything_runs(tmp_path):
    out_dir = tmp_path / "out"
    with pytest.raises(ConfigError, match="unknown object 'teapot'"):
        run_sweep(SweepSpec(objects=("teapot",)), fake_trial, out_dir, progress=False)
    with pytest.raises(ConfigError, match="empty"):
        run_sweep(SweepSpec(grid=()), fake_trial, out_dir, progress=False)
    with pytest.raises(SweepError, match="module-level"):
        run_sweep(SMALL, lambda trial: fake_trial(trial), out_dir, progress=False)
    with pytest.raises(ValueError, match="argument 'workers' must be at least 1"):
        run_sweep(SMALL, fake_trial, out_dir, workers=0, progress=False)
    assert not out_dir.exists()


def test_progress_bar_reports_to_stderr(tmp_path, capsys):
    pytest.importorskip("tqdm", reason="tqdm, a main dependency, is not installed")
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1)
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=True)
    assert "9/9" in capsys.readouterr().err


def test_a_missing_progress_bar_library_is_reported_up_front(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # import tqdm now raises ImportError
    with pytest.raises(SweepError, match="tqdm"):
        run_sweep(SMALL, fake_trial, tmp_path / "out", progress=True)
    assert not (tmp_path / "out").exists()


def test_a_scheduler_without_the_dask_extra_is_reported(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # as if not installed
    with pytest.raises(SweepError, match=r"tegrasp-drake\[dask\]"):
        run_sweep(SMALL, fake_trial, tmp_path, scheduler="tcp://127.0.0.1:8786",
                  progress=False)
    assert not (tmp_path / "trials").exists()


def test_explicit_workers_the_memory_cannot_hold_are_refused(tmp_path, monkeypatch):
    from tegrasp_drake.sweep import runner
    monkeypatch.setattr(runner, "available_memory_bytes",
                        lambda: 3.5 * runner.WORKER_MEMORY_BYTES)
    with pytest.raises(SweepError, match=r"--workers 100000: 36 worker processes .* give at "
                                         r"most 3"):
        run_sweep(SMALL, fake_trial, tmp_path, workers=100000, progress=False)
    assert not (tmp_path / "trials").exists() or not any((tmp_path / "trials").iterdir())


def test_the_pool_never_exceeds_the_trials_nor_by_default_the_memory(monkeypatch):
    from tegrasp_drake.sweep import runner
    monkeypatch.setattr(runner, "available_memory_bytes",
                        lambda: 2.5 * runner.WORKER_MEMORY_BYTES)
    monkeypatch.setattr(runner, "default_workers", lambda: 8)
    assert runner.pool_size(2, 1) == 1
    assert runner.pool_size(None, 100) == 2
