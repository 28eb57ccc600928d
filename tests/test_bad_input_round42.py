"""A sweep's --logs copy that cannot be written (a full disk): the trial's result is recorded
all the same, the log is named once in one error line with the OS reason, the sweep stops
and exits 1. A fake trial function and a failing write; no simulation."""

import errno
import json
import os
import types

from tegrasp_drake import cli
from tegrasp_drake.sweep import runner, trial_function
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials

_SWEEP = ["sweep", "--objects", "box", "--controllers", "open_loop", "--attempts", "1",
          "--no-progress", "--format", "svg", "--workers", "1"]


def _enospc(path):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))


def test_the_trial_function_keeps_its_result_when_its_log_cannot_be_written(
        tmp_path, monkeypatch):
    """run_trial_from_spec, its simulation replaced by a finished run whose log write fails
    with ENOSPC: the runner records the result ("ok") and names the log and the reason."""
    result = {"hold_success": True, "unload_success": False, "sim_time_s": 8.0,
              "wall_time_s": 1.0}
    finished = types.SimpleNamespace(log=types.SimpleNamespace(save=_enospc),
                                     to_dict=lambda: dict(result))
    monkeypatch.setattr(trial_function, "run_trial", lambda *args, **kwargs: finished)
    monkeypatch.setattr(trial_function, "trial_events", lambda *args: (None, None, None))
    trial = next(iter(expand_trials(SweepSpec(objects=("box",), attempts=1)))).to_dict()
    function = lambda t: trial_function.run_trial_from_spec(t, log_dir=tmp_path)  # noqa: E731
    outcome = runner.run_trial_safely(function, trial)
    assert outcome[0] == "ok", outcome[1]
    assert outcome[1]["hold_success"] is True
    path = tmp_path / trial_function.trial_log_name(trial)
    assert outcome[2] == f"{path}: {os.strerror(errno.ENOSPC)}"


def test_a_sweep_whose_logs_cannot_be_written_records_the_result_and_stops(tmp_path, capsys):
    out = tmp_path / "out"
    code = cli.main([*_SWEEP, "--trial-function", "tests.fake_trials:full_disk_fake_trial",
                     "--logs", str(tmp_path / "logs"), "--out", str(out)])
    _, error = capsys.readouterr()
    assert code == 1, error
    lines = [line for line in error.splitlines() if "error:" in line]
    assert len(lines) == 1, error
    assert f"--logs {tmp_path / 'logs'}" in lines[0] and "No space left on device" in lines[0]
    assert "Traceback" not in error and "left for the next run" in lines[0]
    records = [json.loads(path.read_text()) for path in (out / "trials").glob("*.json")]
    assert len(records) == 1, "the sweep stops at the first log it cannot write"
    assert records[0]["status"] == "ok", records[0]



def test_a_benchmark_whose_logs_cannot_be_written_says_so_once(tmp_path, capsys):
    """--benchmark --logs on a full disk: one error line naming --logs and the reason, exit 1;
    the benchmark stops at the first run that met it."""
    code = cli.main([*_SWEEP[:-2], "--benchmark", "--logs", str(tmp_path / "logs"),
                     "--trial-function", "tests.fake_trials:full_disk_fake_trial"])
    out, error = capsys.readouterr()
    assert code == 1, error
    lines = [line for line in error.splitlines() if "error:" in line]
    assert len(lines) == 1, error
    assert f"--logs {tmp_path / 'logs'}" in lines[0] and "No space left on device" in lines[0]
    assert out.count("worker(s):") == 1, out
