"""Every script of analysis/ given a path that cannot be what it asks for (a junk file where a
folder, trial log or results page belongs; a path under a file where it writes) ends with one
line on stderr and a non-zero exit code, never a Python traceback, never success on nothing."""

import os
import subprocess
import sys

import pytest

from tests.analysis_script import ANALYSIS

# The scripts that take no file or folder from the user, and why they are not run here.
NO_USER_PATHS = {"measure_finger_strike": "takes no arguments; its scenes are built in"}


def script_arguments(junk, under_junk) -> dict[str, list[str]]:
    """Each script's arguments: `junk` (a regular file of non-UTF-8 bytes) for what it reads,
    `under_junk` (a path below that file, which no folder can hold) for what it writes."""
    j, u = str(junk), str(under_junk)
    return {
        "check_rule_engine_equivalence": ["--base", "HEAD", "--out", u],
        "choose_corrective_thresholds": [j, j, u],
        "choose_ensemble_thresholds": [j, u],
        "compare_geometry": [u, j, j],
        "compare_hands": [u, j, j],
        "compare_ra_transients": [u + ".png"],
        "corrective_feasibility": [j, j, j],
        "detection_quality": [u, j],
        "explain_open_loop": [u + ".png"],
        "grip_rise": [j],
        "hold_creep": [j, j],
        "judge_corrective_triggers": [u],
        "linkage_figure": [u + ".png"],
        "make_corrective_test_windows": [j, j],
        "make_success_maps": [j],
        "make_table1": [j],
        "measure_load_lift": ["--events", j],
        "record_corrective_events": [u],
        "record_ensemble_events": [u],
        "rejudge_from_logs": [j, j, u],
        "roc_from_sweep_logs": [j, u],
        "transfer_diagnosis": [j, j],
        "transfer_matrix": [j, j],
        "update_results_page": [j],
        "weak_stimuli": [j, j],
    }


SCRIPTS = sorted(path.stem for path in ANALYSIS.glob("*.py"))


def run_script(name: str, arguments: list[str], cwd) -> subprocess.CompletedProcess:
    """analysis/`name`.py run as a user runs it, from `cwd` (not the repository)."""
    environment = dict(os.environ, PYTHONPATH=str(ANALYSIS.parent), MPLBACKEND="Agg")
    return subprocess.run([sys.executable, str(ANALYSIS / f"{name}.py"), *arguments],
                          cwd=cwd, env=environment, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=600)


def test_every_script_is_listed():
    arguments = script_arguments("junk", "junk/x")
    assert sorted(set(arguments) | set(NO_USER_PATHS)) == SCRIPTS
    assert not set(arguments) & set(NO_USER_PATHS)


@pytest.mark.parametrize("name", sorted(script_arguments("junk", "junk/x")))
def test_script_refuses_a_junk_path_in_one_line(name, tmp_path):
    junk = tmp_path / "junk"
    junk.write_bytes(b"\xff\xfe\x00junk\x80" * 64)
    done = run_script(name, script_arguments(junk, junk / "x")[name], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode != 0, (done.stdout, done.stderr)
    assert "Traceback" not in done.stderr and "internal error" not in done.stderr, done.stderr
    assert len(lines) == 1, done.stderr
