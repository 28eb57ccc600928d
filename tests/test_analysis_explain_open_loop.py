"""analysis/explain_open_loop.py: its figure's file name is checked before its twelve trials
run, not after them."""

import concurrent.futures
import importlib.util

import pytest

from tests.killed_runs import REPOSITORY


def _script():
    spec = importlib.util.spec_from_file_location(
        "explain_open_loop", REPOSITORY / "analysis" / "explain_open_loop.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_name_of_no_figure_format_is_refused_before_any_trial_runs(tmp_path, monkeypatch,
                                                                     capsys):
    def no_trials(*args, **kwargs):
        raise AssertionError("the trials started")
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", no_trials)
    with pytest.raises(SystemExit) as ended:
        _script().main([str(tmp_path / "open_loop.jpg")])
    assert ended.value.code == 2
    assert "must end in one of .png, .pdf, .svg" in capsys.readouterr().err.splitlines()[-1]
    assert list(tmp_path.iterdir()) == []
