"""`tegrasp sensitivity` end to end with a fake trial function: a two-point study killed
with SIGKILL mid-run and resumed gives exactly the records and report of an uninterrupted
run; a bad spec is refused in one line before anything runs."""

import shutil
import signal
import subprocess
import sys
import textwrap

from tegrasp_drake.rig import paths

from tests import killed_runs
from tests.killed_runs import environment

TIMEOUT_S = 600  # [s] a hang guard on a busy host, not a performance criterion
# The default point and the decimation's high end (its low end is the default): two points.
TWO_POINTS = """\
    parameters: [tactile.capacitive.decimation]
    events: each_point
    sweep:
      objects: [box]
      controllers: [memorized]
      attempts: 2
      base_seed: 600
    """
POINTS = ("default", "tactile_capacitive_decimation_high")
TRIALS_TOTAL = 2 * 9 * 2  # points x markers x attempts


def prepared(tmp_path, name):
    """A spec and an output folder whose points hold the package's events already (so
    nothing is recorded: the fake trial needs none)."""
    spec = tmp_path / "sensitivity.yaml"
    spec.write_text(textwrap.dedent(TWO_POINTS))
    out = tmp_path / name
    for point in POINTS:
        shutil.copytree(paths.package_events_dir(), out / "events" / point,
                        ignore=shutil.ignore_patterns("ensemble", "corrective", "prismatic"))
    return spec, out


def command(spec, out):
    return [sys.executable, "-m", "tegrasp_drake.cli", "sensitivity", str(spec), "--out",
            str(out), "--workers", "1", "--no-progress", "--trial-function",
            "tests.fake_trials:slow_fake_trial_with_events"]


def record_files(out):
    return sorted((out / "cells").glob("*/trials/*.json"))


def kill_after_some_records(spec, out, minimum):
    return killed_runs.kill_after_some_records(
        command(spec, out), lambda: record_files(out), minimum, TIMEOUT_S)


def test_a_killed_study_resumes_to_the_records_and_report_of_an_uninterrupted_run(tmp_path):
    spec, killed = prepared(tmp_path, "killed")
    count, returncode = kill_after_some_records(spec, killed, minimum=4)
    assert returncode == -signal.SIGKILL
    assert 4 <= count < TRIALS_TOTAL, "the kill must land in the middle of the study"

    resumed = subprocess.run(command(spec, killed), env=environment(), capture_output=True,
                             text=True, timeout=TIMEOUT_S)
    assert resumed.returncode == 0, resumed.stderr
    assert "recording" not in resumed.stdout
    ran_now = sum(int(line.split(" run now")[0].split()[-1])
                  for line in resumed.stdout.splitlines() if " run now" in line)
    assert ran_now == TRIALS_TOTAL - count

    _, clean = prepared(tmp_path, "clean")
    done = subprocess.run(command(spec, clean), env=environment(), capture_output=True,
                          text=True, timeout=TIMEOUT_S)
    assert done.returncode == 0, done.stderr
    a, b = record_files(killed), record_files(clean)
    assert [p.relative_to(killed) for p in a] == [p.relative_to(clean) for p in b]
    assert len(b) == TRIALS_TOTAL
    for x, y in zip(a, b):
        assert x.read_bytes() == y.read_bytes(), x.name
    assert (killed / "sensitivity.md").read_text() == (clean / "sensitivity.md").read_text()
    assert (killed / "points.json").read_text() == (clean / "points.json").read_text()
    assert (clean / "tornado.png").stat().st_size > 0


def test_a_bad_spec_is_refused_in_one_line_before_anything_runs(tmp_path):
    spec = tmp_path / "bad.yaml"
    spec.write_text("parameters: [gripper.pad_length]\n")
    out = tmp_path / "out"
    done = subprocess.run(command(spec, out), env=environment(), capture_output=True,
                          text=True, timeout=TIMEOUT_S)
    assert done.returncode == 2
    assert done.stderr.startswith(f"tegrasp: error: {spec}: field 'parameters[0]'")
    assert done.stderr.count("\n") == 1
    assert not (out / "cells").exists()
