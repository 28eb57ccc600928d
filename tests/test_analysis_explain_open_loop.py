"""analysis/explain_open_loop.py: its figure's file name is checked before its twelve trials
run, not after them."""

import concurrent.futures

import pytest

from tegrasp_drake.commands.script_output import run_script
from tests.analysis_script import load_analysis_script


def _script():
    return load_analysis_script("explain_open_loop")


def test_a_name_of_no_figure_format_is_refused_before_any_trial_runs(tmp_path, monkeypatch):
    def no_trials(*args, **kwargs):
        raise AssertionError("the trials started")
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", no_trials)
    with pytest.raises(SystemExit) as ended:
        run_script(_script().main, "explain_open_loop", [str(tmp_path / "open_loop.jpg")])
    assert ended.value.code.startswith("explain_open_loop: error: ")  # exit code 1
    assert "must end in one of .png, .pdf, .svg" in ended.value.code
    assert list(tmp_path.iterdir()) == []
