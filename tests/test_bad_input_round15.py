"""Bad inputs the fifteenth review found, one test per rule."""

import sys

import pytest

from tegrasp_drake import cli
from tests.test_bad_input_round10 import _refused  # noqa: F401  (the rules below reuse it)


# Rule: a setting a command cannot use stops it before it does any work. `--scheduler` is
# checked whole (its address, the Dask extra, whether the scheduler answers) by the runner
# arguments' check that sweep, transfer and sensitivity share, so transfer and sensitivity
# refuse it before recording any world's events, as sweep refuses it before any trial.
@pytest.mark.parametrize("command, spec", [
    ("transfer", "analysis/transfer_matrix.yaml"),
    ("sensitivity", "analysis/sensitivity.yaml"),
])
@pytest.mark.parametrize("cause, words", [("no extra", "tegrasp-drake[dask]"),
                                          ("no answer", "cannot reach the Dask scheduler")])
def test_a_scheduler_that_cannot_work_is_refused_before_any_event_is_recorded(
        tmp_path, monkeypatch, capsys, command, spec, cause, words):
    from tegrasp_drake.sweep import runner
    from tegrasp_drake.transfer import matrix

    def no_recording(*args, **kwargs):
        raise AssertionError("events recorded before --scheduler was checked")

    monkeypatch.setattr(matrix, "record_world_events", no_recording)
    if cause == "no extra":
        monkeypatch.setitem(sys.modules, "distributed", None)  # as if it were not installed
    else:
        pytest.importorskip("distributed", reason="the optional 'dask' extra is not installed")
        monkeypatch.setattr(runner, "DASK_CONNECT_TIMEOUT_S", 1.0)
    code = cli.main([command, spec, "--workers", "1", "--no-progress",
                     "--scheduler", "tcp://127.0.0.1:1", "--out", str(tmp_path / "out")])
    error = capsys.readouterr().err
    assert code == 2, error
    assert error.count("\n") == 1 and words in error, error
    assert not (tmp_path / "out").exists()
