"""Logs that cannot be written: a full disk, a device or an unwritable path as the log, a
logger that stops mid-run. The run says so once in one line with the OS reason and stops as
a fault, keeps its result (and an earlier run's log beside, not under, the new one), and
does not blame a worker; sweeps with other settings or events keep their own logs."""

import errno
import json
import os
import pathlib
import types

import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands import hardware as hardware_command
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.sweep import runner, trial_function
from tegrasp_drake.sweep.runner import SweepSummary, summary_text
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tegrasp_drake.sweep.trial_function import trial_log_name
from tests.bad_input.probes import (assert_one_line_error, earlier_run_of, folder_contents,
                                    run_cli)
from tests.fake_trials import whole_result
from tests.runs.test_hardware_output_safety import disk_with_free_bytes
from tests.runs.earlier_hardware_run import EARLIER_LOG, EARLIER_RESULT


def test_a_hardware_run_whose_devices_do_not_come_up_keeps_the_earlier_log(tmp_path,
                                                                           monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (tmp_path / "old.lcmlog").write_bytes(EARLIER_LOG)
    (tmp_path / "old.result.json").write_text(EARLIER_RESULT.replace("run.lcmlog", "old.lcmlog"))
    code = cli.main(["hardware", "--config", "hw.yaml", "--config-set",
                     "tactile.port=/dev/no_such_port", "--config-set",
                     "gripper.port=/dev/no_such_gripper_port", "--config-set", "ready_timeout=1.5",
                     "--config-set", "scheduling=normal", "--log", "old.lcmlog",
                     "--overwrite", "--controller", "heuristic"])
    captured = capfd.readouterr()
    assert code == 1, captured
    assert "tegrasp: error:" in captured.err and "error" not in captured.out  # on stderr
    assert (tmp_path / "old.lcmlog").read_bytes() == EARLIER_LOG
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hw.yaml", "old.lcmlog",
                                                          "old.result.json"]


def test_a_hardware_run_commits_its_log_and_result_together(tmp_path):
    log, result = tmp_path / "run.lcmlog", tmp_path / "run.result.json"
    log.write_bytes(b"earlier")
    staged = tmp_path / ".run.lcmlog.1.staging"
    staged.write_bytes(b"this run")
    hardware_command.commit_hardware_run(staged, log, result, {"log": str(log)})
    assert log.read_bytes() == b"this run" and json.loads(result.read_text())["log"] == str(log)
    assert not staged.exists()


def test_an_unfinished_hardware_runs_log_is_kept_beside_not_over_the_earlier(tmp_path):
    log = tmp_path / "run.lcmlog"
    log.write_bytes(b"earlier")
    staged = tmp_path / ".run.lcmlog.1.staging"
    staged.write_bytes(b"half a run")
    kept, replaced = hardware_command.keep_incomplete_log(staged, log)
    assert kept.name == "run.incomplete.lcmlog" and not replaced
    assert kept.read_bytes() == b"half a run" and log.read_bytes() == b"earlier"


def test_a_log_on_a_full_disk_is_a_problem_that_names_it(tmp_path, monkeypatch):
    from tegrasp_drake.runs import hardware_run
    writer = hardware_run.BusLogWriter(f"udpm://239.255.76.67:{7700 + os.getpid() % 100}?ttl=0",
                                       tmp_path / "run.lcmlog")
    try:
        assert writer.problem() is None
        disk_with_free_bytes(monkeypatch, 40_960)
        assert "the disk holding it has less than 1 MB free" in writer.problem()
    finally:
        writer.close()


# Rule: a trial asks for the free space its files take before it simulates (the probe
# `tegrasp hardware` asks for its log's, rig.files.free_space_problem), so a full disk refuses
# it in one line rather than ending three minutes of simulation; an earlier run is kept.
@pytest.mark.parametrize("earlier", [False, True])
def test_a_trial_on_a_disk_too_full_for_its_files_is_refused_before_it_simulates(
        earlier, tmp_path, monkeypatch, capfd):
    from tegrasp_drake.runs import trial as trial_module
    out = tmp_path / "run"
    if earlier:
        earlier_run_of(out)
    before = folder_contents(tmp_path)
    disk_with_free_bytes(monkeypatch, 40_960)
    monkeypatch.setattr(trial_module, "run_trial", lambda *a, **k: pytest.fail("it simulated"))
    code, text = run_cli(["trial", "--out", str(out), *(["--overwrite"] * earlier)], capfd)
    assert_one_line_error(code, text, f"--out {out}", "40 kB free", "MB for its files")
    assert code == 1
    assert folder_contents(tmp_path) == before
    assert out.exists() == earlier


def test_a_log_that_stops_recording_stops_the_run_as_a_fault():
    from tegrasp_drake.runs.hardware_run import RunReporter

    class Port:
        def Eval(self, context):
            return []

    class Station:
        def GetOutputPort(self, name):
            return Port()

        def GetMyContextFromRoot(self, context):
            return context

    class Grasp:
        def transitions(self, context):
            return []

    class Context:
        def get_time(self):
            return 1.0

    class Bus:
        def Publish(self, channel, data):
            pass

    lines = []
    reporter = RunReporter(diagram=None, station=Station(), grasp=Grasp(), drake_lcm=Bus(),
                           out=lines.append, log_problem=lambda: "the LCM log x stopped")
    status = reporter(Context())
    assert status.severity() == status.Severity.kReachedTermination
    assert reporter.log_fault == "the LCM log x stopped"
    assert "FAULT" in lines[0]


def test_sweeps_with_other_settings_keep_their_own_logs():
    first = {"trial_id": "memorized/box/m00/a0", "seed": 600}
    second = dict(first, seed=601)
    assert trial_log_name(first) != trial_log_name(second)
    assert trial_log_name(first).startswith("memorized.box.m00.a0.")
    assert trial_log_name(first) == trial_log_name(dict(first))


def test_an_unwritable_log_is_named_as_such_not_as_the_lcm_url(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", "/dev/full/run.lcmlog",
                          "--controller", "heuristic"], capfd)
    assert_one_line_error(code, text, "--log /dev/full/run.lcmlog", "not a folder")


def test_a_log_that_stops_is_reported_once_by_the_run_and_named_by_its_closing_error():
    from types import SimpleNamespace

    from tegrasp_drake.runs.hardware_run import RunReporter
    station = SimpleNamespace(GetOutputPort=lambda name: SimpleNamespace(Eval=lambda c: []),
                              GetMyContextFromRoot=lambda context: context)
    lines = []
    reporter = RunReporter(diagram=None, station=station,
                           grasp=SimpleNamespace(transitions=lambda context: []),
                           drake_lcm=SimpleNamespace(Publish=lambda channel, data: None),
                           out=lines.append, log_problem=lambda: "the LCM log x stopped")
    reporter(SimpleNamespace(get_time=lambda: 1.0))
    assert reporter.log_fault == "the LCM log x stopped"  # the closing error's words
    assert len(lines) == 1 and "FAULT" in lines[0] and "log x" not in lines[0]


def _long_log(folder, contents=None):
    """A --log of 211 characters (a 200-character folder name), holding `contents` if given
    (EARLIER_LOG: an earlier run's, its result beside it)."""
    log = pathlib.Path("d" * 200) / "run.lcmlog"
    (folder / log.parent).mkdir()
    if contents is not None:
        (folder / log).write_bytes(contents)
    if contents == EARLIER_LOG:
        (folder / log.parent / "run.result.json").write_text(EARLIER_RESULT)
    return str(log)


# Rule: `tegrasp hardware` echoes a --log (and the files beside it) cut to about 80
# characters, saying how long it was, in every refusal: the user's typo is not echoed whole.
@pytest.mark.parametrize("make, words", [
    (lambda folder: "a" * 300, "cannot be used (File name too long)"),
    (lambda folder: _long_log(folder, b"a trial's notes"), "exists and is not an LCM log"),
    (lambda folder: _long_log(folder, EARLIER_LOG), "already holds a run's log"),
], ids=["name-too-long", "not-an-lcm-log", "an-earlier-run"])
def test_a_long_hardware_log_is_echoed_cut_to_about_80_characters(make, words, tmp_path,
                                                                  monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    log = make(tmp_path)
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", log], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, words,
                          f"{log[:50]}...{log[-30:]} ({len(log)} characters)")
    assert log not in text and len(text) < 250, text


# Rule: one path rule for an output file: what --overwrite could never replace (a device, a
# folder) is refused as such first; only a regular file is said to hold an earlier run.
def test_a_device_as_the_hardware_log_is_refused_as_a_device(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", "/dev/null"], capfd)
    assert code == 1 and "\n" not in text.strip(), text
    assert "--log /dev/null is a device, not a file" in text and "overwrite" not in text, text

_SWEEP = ["sweep", "--objects", "box", "--controllers", "open_loop", "--attempts", "1",
          "--no-progress", "--format", "svg", "--workers", "1"]


def _enospc(path):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))


def test_the_trial_function_keeps_its_result_when_its_log_cannot_be_written(
        tmp_path, monkeypatch):
    """run_trial_from_spec, its simulation replaced by a finished run whose log write fails
    with ENOSPC: the runner records the result ("ok") and names the log and the reason."""
    trial = next(iter(expand_trials(SweepSpec(objects=("box",), attempts=1)))).to_dict()
    result = whole_result(trial, hold_success=True, sim_time_s=8.0, wall_time_s=1.0)
    finished = types.SimpleNamespace(log=types.SimpleNamespace(save=_enospc),
                                     to_dict=lambda: dict(result))
    monkeypatch.setattr(trial_function, "run_trial", lambda *args, **kwargs: finished)
    monkeypatch.setattr(trial_function, "trial_events", lambda *args: (None, None, None))
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
    code = cli.main([*_SWEEP[:-4], "--benchmark", "--logs", str(tmp_path / "logs"),
                     "--trial-function", "tests.fake_trials:full_disk_fake_trial"])
    out, error = capsys.readouterr()
    assert code == 1, error
    lines = [line for line in error.splitlines() if "error:" in line]
    assert len(lines) == 1, error
    assert f"--logs {tmp_path / 'logs'}" in lines[0] and "No space left on device" in lines[0]
    assert out.count("worker(s):") == 1, out


def test_sweeps_against_other_events_keep_their_own_logs():
    """Two sweeps of one spec and seed, one against other memorized events (--events), on one
    --logs folder: the second replaced the first's logs. A trial's log is named for what it
    matched against too, as its record says ("events")."""
    from tegrasp_drake.sweep.trial_function import trial_log_name
    trial = {"trial_id": "memorized/box/m00/a0", "seed": 620}
    mine, theirs = ({"folder": None, "sha256": digit * 64} for digit in "ab")
    names = {trial_log_name(trial), trial_log_name(trial, mine), trial_log_name(trial, theirs)}
    assert len(names) == 3
    assert trial_log_name(trial, dict(mine, folder="/elsewhere")) == trial_log_name(trial, mine)


def test_trials_left_by_an_unwritten_log_are_not_blamed_on_a_worker():
    summary = SweepSummary(out_dir=pathlib.Path("o"), total=3, skipped=0, ran=1, errors=(),
                           unfinished=("a", "b"), corrupt=(), backend="processes:1",
                           wall_time_s=1.0, unwritten_log="L/x.npz: No space left on device")
    text = summary_text(summary)
    assert "worker" not in text and "could not be written" in text, text
    died = summary_text(SweepSummary(**{**summary.__dict__, "unwritten_log": None}))
    assert "a worker died" in died
