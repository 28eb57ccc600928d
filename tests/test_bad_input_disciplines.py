"""The disciplines behind bad input, beside the tables of tests/test_bad_input*.py: reads
bounded before their end, runs that replace their predecessors only when complete, one
error boundary for the command line, and the public API's type checks."""

import json
import os
import pathlib
import signal
import zipfile

import numpy as np
import numpy.lib.format as npy_format
import pytest

import tegrasp_drake
from tests.runs.test_hardware_output_safety import disk_with_free_bytes
from tests.test_bad_input import assert_one_line_error, folder_contents, run_cli
from tegrasp_drake import cli
from tegrasp_drake.commands import hardware as hardware_command
from tegrasp_drake.commands import run_folder
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.rig import files
from tegrasp_drake.scenario.trial_log_file import ARRAY_FIELDS, FORMAT_VERSION
from tegrasp_drake.sweep.trial_function import trial_log_name


# --- bounded reads ------------------------------------------------------------------------

@pytest.mark.parametrize("argv", [
    ["trial", "--scenario", "/dev/zero", "--scenario-name", "x"],
    ["record-events", "--scenario", "/dev/zero", "--scenario-name", "x"],
    ["hardware", "--config", "/dev/zero"],
    ["sweep", "--spec", "/dev/zero", "--out", "sw"],
    ["transfer", "/dev/zero", "--out", "tr"],
    ["sensitivity", "/dev/zero", "--out", "se"],
])
def test_a_configuration_without_an_end_is_refused_at_its_limit(argv, tmp_path, monkeypatch,
                                                                capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, "/dev/zero", "more than 1000000 bytes")


def test_a_binary_scenario_file_is_one_line(tmp_path, capfd):
    scenario = tmp_path / "binary.yaml"
    scenario.write_bytes(b"mine:\n  object: \xff\xfe\x00\x01\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario), "not UTF-8 text")


def _log_declaring(path, declared_shape, stored_bytes: int):
    """A small .npz with every trial-log array, whose 't_sa' header declares
    `declared_shape` float64 values over `stored_bytes` bytes of zeros."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in ("meta", *ARRAY_FIELDS):
            with archive.open(name + ".npy", "w", force_zip64=True) as member:
                if name == "meta":
                    npy_format.write_array(member, np.array(json.dumps(
                        {"format_version": FORMAT_VERSION})))
                    continue
                shape = declared_shape if name == "t_sa" else (2,)
                npy_format.write_array_header_1_0(
                    member, {"descr": "<f8", "fortran_order": False, "shape": shape})
                member.write(bytes(stored_bytes if name == "t_sa" else 16))
    return path


@pytest.fixture
def no_array_is_read(monkeypatch):
    """Fails the test if numpy is asked to read (and so allocate) any array."""
    def refuse(*args, **kwargs):
        raise AssertionError("an array was read before its header was checked")
    monkeypatch.setattr(npy_format, "read_array", refuse)


@pytest.mark.parametrize("argv", [["plot", "trial", "LOG", "--out", "x.png"],
                                  ["emulate", "myrio", "--trial", "LOG"]])
def test_a_trial_log_declaring_a_huge_array_is_refused_from_its_header(
        argv, tmp_path, monkeypatch, capfd, no_array_is_read):
    """A 4 GiB array declared over 40 kB of data: np.load would allocate 4 GiB first."""
    monkeypatch.chdir(tmp_path)
    log = _log_declaring(tmp_path / "trial.npz", (2**29,), 40_000)
    code, text = run_cli([str(log) if a == "LOG" else a for a in argv], capfd)
    assert_one_line_error(code, text, "trial.npz", "'t_sa' declares (536870912,) float64")


def test_arrays_over_the_limit_are_refused_before_they_are_read(tmp_path, no_array_is_read):
    from tegrasp_drake.rig.npz_headers import NpzHeaderError, checked_npz_arrays
    log = _log_declaring(tmp_path / "trial.npz", (5_000,), 40_000)
    with pytest.raises(NpzHeaderError, match="more than the 1000 this reads"):
        checked_npz_arrays(log, ("t_sa",), max_bytes=1000)


def test_more_workers_than_cores_is_refused_unless_asked_for(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.sweep import runner
    monkeypatch.setattr(runner, "default_workers", lambda: 2)
    code, text = run_cli(["sweep", "--workers", "54", "--out", str(tmp_path / "sw")], capfd)
    assert_one_line_error(code, text, "--workers 54", "2 core(s)", "--oversubscribe")
    assert not (tmp_path / "sw").exists()


def test_an_empty_sweep_spec_is_refused_not_run_as_the_paper_experiment(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "sw")], capfd)
    assert_one_line_error(code, text, str(spec), "the sweep spec is empty")
    assert not (tmp_path / "sw").exists()


# --- files and runs -------------------------------------------------------------------------

@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_written_files_honour_the_umask(umask, mode, tmp_path):
    previous = os.umask(umask)
    try:
        written = files.write_atomically(tmp_path / "a.json", "{}",
                                         start=files.JSON_OBJECT_START)
        with files.temporary_sibling(tmp_path / "b.png", start=b"\x89PNG") as temporary:
            temporary.write_bytes(b"figure")
    finally:
        os.umask(previous)
    assert written.stat().st_mode & 0o777 == mode
    assert (tmp_path / "b.png").stat().st_mode & 0o777 == mode


def test_read_bounded_stops_at_its_limit_on_an_endless_file():
    with pytest.raises(files.InputTooLargeError):
        files.read_bounded("/dev/zero", 4096)
    assert files.read_bounded("/dev/null", 4096) == b""


@pytest.mark.parametrize("signal_number", [signal.SIGTERM, signal.SIGHUP])
def test_sigterm_and_sighup_remove_a_runs_staging_folder(signal_number, tmp_path):
    # The signal's default disposition, as a terminal's process has it (a suite started
    # under nohup inherits SIGHUP ignored, which termination_interrupts leaves alone).
    inherited = signal.signal(signal_number, signal.SIG_DFL)
    try:
        with pytest.raises(KeyboardInterrupt, match=signal.Signals(signal_number).name):
            with files.termination_interrupts():
                with run_folder.staged_run(tmp_path) as stage:
                    (stage / "trial.npz").write_bytes(b"half a log")
                    os.kill(os.getpid(), signal_number)
        assert list(tmp_path.iterdir()) == []
        assert signal.getsignal(signal_number) == signal.SIG_DFL
    finally:
        signal.signal(signal_number, inherited)


def test_cli_main_reports_a_sigterm_as_an_interruption(monkeypatch, capfd):
    from tegrasp_drake.commands import plot

    def terminated(args):
        os.kill(os.getpid(), signal.SIGTERM)
    monkeypatch.setattr(plot, "run", terminated)
    code, text = run_cli(["plot", "table1", "nowhere"], capfd)
    assert code == 128 + signal.SIGTERM
    assert text.strip() == ("tegrasp: interrupted (SIGTERM); the run's unfinished files were "
                            "removed")


def test_an_overwritten_run_keeps_none_of_the_earlier_runs_figures(tmp_path):
    folder = tmp_path / "run"
    folder.mkdir()
    for name in ("trial.npz", "states.png", "signals.png"):
        (folder / name).write_bytes(b"earlier")
    (folder / "notes.txt").write_text("the user's own file")
    (folder / "result.json").write_text(json.dumps(
        {"log": str(folder / "trial.npz"), "figure": str(folder / "states.png"),
         "signals_figure": str(folder / "signals.png"), "result": str(folder / "result.json")}))
    with run_folder.staged_run(folder) as stage:
        for name in ("trial.npz", "states.svg", "signals.svg"):
            (stage / name).write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz"),
                                              "figure": str(stage / "states.svg")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "notes.txt", "result.json", "signals.svg", "states.svg", "trial.npz"]
    assert (folder / "trial.npz").read_bytes() == b"new"


def test_a_hardware_run_whose_devices_do_not_come_up_keeps_the_earlier_log(tmp_path,
                                                                           monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (tmp_path / "old.lcmlog").write_bytes(b"an earlier run's log")
    code = cli.main(["hardware", "--config", "hw.yaml", "--config-set",
                     "tactile.port=/dev/no_such_port", "--config-set",
                     "gripper.port=/dev/no_such_gripper_port", "--config-set", "ready_timeout=1",
                     "--config-set", "scheduling=normal", "--log", "old.lcmlog",
                     "--overwrite", "--controller", "heuristic"])
    captured = capfd.readouterr()
    assert code == 1, captured
    assert "tegrasp: error:" in captured.err and "error" not in captured.out  # on stderr
    assert (tmp_path / "old.lcmlog").read_bytes() == b"an earlier run's log"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hw.yaml", "old.lcmlog"]


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


def test_a_bus_inside_the_process_is_said_not_to_be_logged(tmp_path):
    from tegrasp_drake.runs import hardware_run
    writer = hardware_run.BusLogWriter("memq://", tmp_path / "run.lcmlog")
    assert "lives inside this process" in writer.unrecorded
    assert writer.problem() is None and writer.close() == 0
    assert not (tmp_path / "run.lcmlog").exists()


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


def test_record_events_does_not_record_another_object_under_an_objects_name(tmp_path,
                                                                          capfd):
    (tmp_path / "events").mkdir()
    code, text = run_cli(["record-events", "--object", "thin_cylinder", "--set",
                          "object.name=box", "--events", str(tmp_path / "events")], capfd)
    assert_one_line_error(code, text, "--object thin_cylinder", "would record the object 'box'")
    code, text = run_cli(["record-events", "--object", "thin_cylinder", "--scenario-name",
                          "box", "--events", str(tmp_path / "events")], capfd)
    assert_one_line_error(code, text, "give one or the other")
    assert list((tmp_path / "events").iterdir()) == []


# Rule: a trial asks for the free space its files take before it simulates (the probe
# `tegrasp hardware` asks for its log's, rig.files.free_space_problem), so a full disk refuses
# it in one line rather than ending three minutes of simulation; an earlier run is kept.
@pytest.mark.parametrize("earlier", [False, True])
def test_a_trial_on_a_disk_too_full_for_its_files_is_refused_before_it_simulates(
        earlier, tmp_path, monkeypatch, capfd):
    from tegrasp_drake.runs import trial as trial_module
    out = tmp_path / "run"
    if earlier:
        out.mkdir()
        (out / "result.json").write_text('{"earlier": true}\n')
    before = folder_contents(tmp_path)
    disk_with_free_bytes(monkeypatch, 40_960)
    monkeypatch.setattr(trial_module, "run_trial", lambda *a, **k: pytest.fail("it simulated"))
    code, text = run_cli(["trial", "--out", str(out), *(["--overwrite"] * earlier)], capfd)
    assert_one_line_error(code, text, f"--out {out}", "40 kB free", "MB for its files")
    assert code == 1
    assert folder_contents(tmp_path) == before
    assert out.exists() == earlier


# --- the command line's error boundary --------------------------------------------------------

def test_an_unforeseen_exception_is_one_line_with_its_traceback_in_a_file(monkeypatch, capfd):
    from tegrasp_drake.commands import plot

    def broken(args):
        raise RuntimeError("something no check foresaw\nsecond line")
    monkeypatch.setattr(plot, "run", broken)
    code, text = run_cli(["plot", "table1", "nowhere"], capfd)
    assert code == cli.EXIT_INTERNAL_ERROR
    assert len(text.strip().splitlines()) == 1, text
    assert "tegrasp: internal error: RuntimeError: something no check foresaw" in text
    assert "(-v shows it)" in text
    where = text.split("traceback in ")[1].split(" ")[0].rstrip(";")
    assert "Traceback" in pathlib.Path(where).read_text()
    os.unlink(where)
    code, text = run_cli(["plot", "table1", "nowhere", "-v"], capfd)
    assert code == cli.EXIT_INTERNAL_ERROR and "Traceback" in text
    os.unlink(text.split("traceback in ")[1].split(" ")[0].rstrip(";"))


def test_a_deeply_nested_index_is_one_line(tmp_path, capfd):
    events = tmp_path / "events"
    events.mkdir()
    (events / "index.json").write_text("[" * 100_000 + "]" * 100_000)
    code, text = run_cli(["trial", "--events", str(events)], capfd)
    assert_one_line_error(code, text, "index.json")


def test_an_unreadable_event_file_is_one_line(tmp_path, capfd):
    import shutil
    from tegrasp_drake.rig import paths
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events,
                    ignore=shutil.ignore_patterns("__init__.py", "__pycache__"))
    (events / "box" / "load_lift.json").unlink()
    (events / "box" / "load_lift.json").mkdir()  # a folder where the file should be
    code, text = run_cli(["trial", "--events", str(events)], capfd)
    assert_one_line_error(code, text, "load_lift.json")


def test_an_unwritable_log_is_named_as_such_not_as_the_lcm_url(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", "/dev/full/run.lcmlog",
                          "--controller", "heuristic"], capfd)
    assert_one_line_error(code, text, "--log /dev/full/run.lcmlog", "not a folder")


@pytest.mark.parametrize("duration", ["-5", "0", "nan", "1e7"])
def test_a_hardware_duration_out_of_range_is_a_usage_error(duration, tmp_path, capfd):
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--duration", duration], capfd)
    assert code == 2 and "--duration" in text and "Traceback" not in text


# --- the public API's boundary -------------------------------------------------------------------

PUBLIC_FUNCTIONS = [name for name in tegrasp_drake.__all__
                    if callable(getattr(tegrasp_drake, name))
                    and not isinstance(getattr(tegrasp_drake, name), type)]


@pytest.mark.parametrize("name", PUBLIC_FUNCTIONS)
def test_every_public_function_checks_every_argument(name):
    import inspect
    import typing
    function = getattr(tegrasp_drake, name)
    assert getattr(function, "__checked_arguments__", False), f"{name} lacks @public_api"
    hints = typing.get_type_hints(function)
    unannotated = [p for p in inspect.signature(function).parameters if p not in hints]
    assert not unannotated, f"{name}: annotate {unannotated} (typing.Any if any value goes)"


@pytest.mark.parametrize("call, words", [
    (lambda: tegrasp_drake.LoadScenario(name=None),
     "LoadScenario: argument 'name' must be str, got NoneType None"),
    (lambda: tegrasp_drake.LoadScenario(overrides="object.mass=1"),
     "argument 'overrides' must be a sequence of str (not a single string)"),
    (lambda: tegrasp_drake.MakeStation(None), "MakeStation: argument 'scenario' must be Scenario"),
    (lambda: tegrasp_drake.run_trial("box"), "run_trial: argument 'scenario' must be Scenario"),
    (lambda: tegrasp_drake.load_trial_log(None), "load_trial_log: argument 'path' must be str"),
    (lambda: tegrasp_drake.load_memorized_events("events", 5),
     "argument 'object_name' must be str, got int 5"),
    (lambda: tegrasp_drake.write_reports("out", "memorized/box/m00/a0"),
     "argument 'trial_ids' must be a sequence of str"),
])
def test_a_wrong_argument_is_named_at_the_call(call, words):
    with pytest.raises(TypeError) as error:
        call()
    assert words in str(error.value)


def test_record_events_with_object_and_set_records_that_object_with_the_setting():
    import argparse
    from tegrasp_drake.commands.record_events import _scenarios_to_record
    args = argparse.Namespace(object=["thin_cylinder"], scenario=None, scenario_name=None,
                              overrides=["random_seed=603"])
    (name, scenario), = _scenarios_to_record(args)
    assert name == "thin_cylinder" and scenario.object.name == "thin_cylinder"
    assert scenario.random_seed == 603
