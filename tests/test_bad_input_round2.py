"""Bad inputs a hostile tester found past the first disciplines, each as the class it belongs
to: Drake's own config sections checked like ours, list lengths, a null the user writes,
fields that relate (grasp height, filters against their rates), files that are not regular,
a run folder two runs share, outputs that would overwrite the run's own files. Each stops
with one line naming the input and what to do, a non-zero exit, and nothing lost."""

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import tegrasp_drake
from tests.test_bad_input import (_trial_log, assert_one_line_error, folder_contents as _contents,
                            run_cli, run_probe)
from tegrasp_drake.commands import run_folder
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.rig import files
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario


def _write(name, text):
    return lambda folder: (folder / name).write_text(text)


DRAKE_SECTION_PROBES = [  # (--set assignment, words the one error line holds)
    ("plant_config.contact_model=foo", "field 'plant_config.contact_model' must be one of"),
    ("simulator_config.integration_scheme=bogus",
     "field 'simulator_config.integration_scheme' must be one of"),
    ("plant_config.contact_surface_representation=sphere",
     "field 'plant_config.contact_surface_representation' must be one of 'triangle'"),
    ("plant_config.discrete_contact_approximation=exact",
     "field 'plant_config.discrete_contact_approximation' must be one of"),
    ("plant_config.penetration_allowance=-1.0",
     "field 'plant_config.penetration_allowance' must lie in (0, "),
    ("plant_config.stiction_tolerance=0.0", "field 'plant_config.stiction_tolerance' must lie in"),
    ("plant_config.sap_near_rigid_threshold=-3.0",
     "field 'plant_config.sap_near_rigid_threshold' must lie in [0, "),
    ("simulator_config.start_time=100.0", "field 'simulator_config.start_time' must lie in"),
    ("simulator_config.target_realtime_rate=-1.0",
     "field 'simulator_config.target_realtime_rate' must lie in [0, "),
    ("simulator_config.max_step_size=0.0", "field 'simulator_config.max_step_size' must lie in"),
    ("simulator_config.accuracy=5.0", "field 'simulator_config.accuracy' must lie in (0, 1]"),
]

RELATED_FIELD_PROBES = [
    ("controller.lift_load.slip_band_hz=900.0", "field 'controller.lift_load.slip_band_hz' must lie below half"),
    ("grasp.grasp_height=0.5", "field 'grasp.grasp_height' must lie within the object's height"),
    ("object.mass=~", "field 'object.mass' is null"),
    ("object.friction=~", "field 'object.friction' is null"),
    ("object.color=[0.1,0.2,0.3]", "field 'object.color' must be [r, g, b, a]"),
    ("object.color=[2.0,0.0,0.0,1.0]", "field 'object.color[0]' must lie in [0, 1]"),
    ("object.file=mine.sdf", "field 'object.file' is for your own object"),
]


@pytest.mark.parametrize("assignment, words", DRAKE_SECTION_PROBES + RELATED_FIELD_PROBES,
                         ids=[p[0] for p in DRAKE_SECTION_PROBES + RELATED_FIELD_PROBES])
def test_a_bad_setting_stops_the_trial_with_one_line(assignment, words, tmp_path, monkeypatch,
                                                      capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["trial", "--set", assignment, "--out", "run"], capfd)
    assert_one_line_error(code, text, words, f"--set {assignment}")
    assert not (tmp_path / "run").exists()


def test_a_sweep_refuses_a_bad_drake_setting_up_front(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "heuristic",
                          "--attempts", "1", "--out", "sw", "--set",
                          "plant_config.contact_model=foo"], capfd)
    assert_one_line_error(code, text, "field 'plant_config.contact_model' must be one of")
    assert not (tmp_path / "sw").exists()


def test_a_transfer_world_with_a_bad_drake_setting_is_refused_up_front(tmp_path, monkeypatch,
                                                                        capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.yaml").write_text(
        "worlds:\n"
        "  ideal: {scenario: memorizing_world}\n"
        "  xovsim: {scenario: memorizing_world, overrides: [plant_config.contact_model=foo]}\n"
        "cells: {memorize_in: [ideal], run_in: [ideal, xovsim]}\n"
        "sweep: {controllers: [memorized], attempts: 1, base_seed: 600}\n")
    code, text = run_cli(["transfer", "spec.yaml", "--out", "tr"], capfd)
    assert_one_line_error(code, text, "worlds.xovsim",
                          "field 'plant_config.contact_model' must be one of")
    assert not (tmp_path / "tr").exists()


@pytest.mark.parametrize("change, words", [
    (lambda s: setattr(s.plant_config, "stiction_tolerance", 0.0),
     "field 'plant_config.stiction_tolerance' must lie in"),
    (lambda s: setattr(s.plant_config, "contact_model", "foo"),
     "field 'plant_config.contact_model' must be one of"),
    (lambda s: setattr(s.simulator_config, "start_time", 100.0),
     "field 'simulator_config.start_time' must lie in"),
    (lambda s: setattr(s.placement, "offset", [0.0, 0.0, 0.0]),
     "field 'placement.offset' must hold 2 numbers [m], got 3 elements"),
    (lambda s: setattr(s.placement, "expected_xy", [0.7]),
     "field 'placement.expected_xy' must hold 2 numbers"),
    (lambda s: setattr(s.disturbance, "hit_force_n", [0.0, 1.0]),
     "field 'disturbance.hit_force_n' must hold 3 numbers"),
    (lambda s: setattr(s.arm, "initial_gripper_xyz", [0.7, 0.0]),
     "field 'arm.initial_gripper_xyz' must hold 3 numbers"),
], ids=["stiction 0", "contact model", "start time", "offset of 3", "xy of 1", "hit of 2",
        "start xyz of 2"])
def test_the_builder_refuses_a_config_changed_after_loading(change, words):
    """A Scenario changed in Python is checked by the same validator when a builder gets it:
    a ConfigError, never Drake's abort (SystemExit) or numpy's broadcast error."""
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    scenario = LoadScenario()
    change(scenario)
    with pytest.raises(ConfigError, match=r"^MakeGraspDiagram: scenario: " + _escape(words)):
        MakeGraspDiagram(scenario)


def _escape(words):
    import re
    return re.escape(words)


def test_a_colour_on_a_built_in_object_is_honoured():
    scenario = LoadScenario(overrides=["object.color=[0.1,0.2,0.3,1.0]"])
    assert scenario.object.color == [0.1, 0.2, 0.3, 1.0]
    assert scenario.object.mass == LoadScenario().object.mass  # the rest is the built-in's


def test_a_high_pass_is_checked_against_the_rate_it_runs_at():
    """The film's charge amplifier is integrated at vibration.internal_rate_hz (20 kHz): a
    600 Hz corner is a valid filter there, even with RA sampled at 1 kHz. The accelerometer's
    high-pass runs on its 1 kHz samples: above 500 Hz it is refused."""
    assert LoadScenario(overrides=["vibration.highpass_cutoff_hz=600.0"])
    with pytest.raises(ConfigError, match="field 'vibration.highpass_cutoff_hz' must lie below "
                                          "500 Hz, half the vibration.sample_rate_hz"):
        LoadScenario(overrides=["vibration.highpass_cutoff_hz=600.0",
                                "vibration.transducer=accelerometer"])


# --- files that are not regular files ---------------------------------------------------------

def _fifo(folder):
    os.mkfifo(folder / "f.yaml")


def _user_folder(folder):
    (folder / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (folder / "mine").mkdir()
    (folder / "mine" / "notes.txt").write_text("the user's own file")


def _html_over_own_result(folder):
    (folder / "o").mkdir()


def _trial_log_with(path, meta=None, **arrays):
    """A small trial log (test_bad_input's) with `meta` merged into its metadata."""
    _trial_log(path, **arrays)
    with np.load(path) as data:
        contents = {name: data[name] for name in data.files}
    contents["meta"] = np.array(json.dumps({**json.loads(str(contents["meta"])),
                                            **(meta or {})}))
    np.savez_compressed(path, **contents)
    return path


def _log(name, meta=None, **arrays):
    return lambda folder: _trial_log_with(folder / name, meta, **arrays)


BIG = "x" * 300_000

PROBES = [  # (name, files made first, argv, words the one error line holds)
    ("5 FIFO scenario", _fifo, ["trial", "--scenario", "f.yaml", "--scenario-name", "x"],
     ["f.yaml: cannot read the scenario file: it is a named pipe (FIFO), not a file"]),
    ("5 FIFO hardware config", _fifo, ["hardware", "--config", "f.yaml"],
     ["f.yaml: cannot read the hardware config: it is a named pipe (FIFO)"]),
    ("5 FIFO sweep spec", _fifo, ["sweep", "--spec", "f.yaml", "--out", "sw"],
     ["f.yaml", "named pipe (FIFO)"]),
    ("11 FIFO trial log", _fifo, ["plot", "trial", "f.yaml", "--out", "x.png"],
     ["trial log 'f.yaml' is a named pipe (FIFO), not a file"]),
    ("11 replay a FIFO", _fifo, ["replay", "f.yaml"], ["'f.yaml' is a named pipe (FIFO)"]),
    ("11 replay a folder", _html_over_own_result, ["replay", "o"], ["'o' is a folder"]),
    ("11 plot /dev/zero", None, ["plot", "trial", "/dev/zero", "--out", "x.png"],
     ["trial log '/dev/zero' is a device, not a file"]),
    ("5 emulate on an LCM URL that does not open", None,
     ["emulate", "jaco", "--lcm-url", "garbage://nowhere"],
     ["--lcm-url 'garbage://nowhere' is not a bus other processes share", "garbage://"]),
    ("6 --html over the run's result", _html_over_own_result,
     ["trial", "--out", "o", "--html", "o/result.json"],
     ["--html o/result.json is one of the run's own files in o (result.json)"]),
    ("6 --html over the run's figure", _html_over_own_result,
     ["trial", "--out", "o", "--html", "o/states.html"], ["one of the run's own files"]),
    ("7 sweep --scheduler not a URL", None,
     ["sweep", "--scheduler", "notaurl", "--objects", "box", "--controllers", "heuristic",
      "--attempts", "1", "--out", "sw"], ["--scheduler 'notaurl' is not a scheduler address"]),
    ("7 sweep --out a file", _write("afile", "x"),
     ["sweep", "--objects", "box", "--controllers", "heuristic", "--attempts", "1",
      "--out", "afile"], ["--out afile: afile is not a folder"]),
    ("7 transfer --out empty", None, ["transfer", "spec.yaml", "--out", ""], ["--out '' is empty"]),
    ("7 demo --out empty", None, ["demo", "--out", ""], ["--out '' is empty"]),
    ("7 trial --out empty", None, ["trial", "--out", ""], ["--out '' is empty"]),
    ("8 transitions not a list", _log("t.npz", {"transitions": "garbage"}),
     ["plot", "trial", "t.npz", "--out", "x.png"], ["meta 'transitions' must be a list"]),
    ("8 transition without 'from'", _log("t.npz", {"transitions": [{"t": "x"}]}),
     ["plot", "trial", "t.npz", "--out", "x.png"], ["meta 'transitions[0]'"]),
    ("8 transition without 'from', timed", _log("t.npz", {"transitions": [{"t": 1.0}]}),
     ["plot", "trial", "t.npz", "--out", "x.png"], ["meta 'transitions[0]' lacks the field"]),
    ("8 phase start not a time", _log("t.npz", {"phase_starts": {"Reach": "soon"}}),
     ["plot", "trial", "t.npz", "--out", "x.png"], ["meta 'phase_starts' must map"]),
    ("8 no mode names", _log("t.npz", {"mode_names": []}),
     ["plot", "trial", "t.npz", "--out", "x.png"], ["meta 'mode_names' must be the modes' labels"]),
    ("8 phase index 1e9", _log("t.npz", phase=np.full(11, 1e9)),
     ["plot", "trial", "t.npz", "--out", "x.png"], ["'phase' must hold indices 0 to"]),
    ("8 myRIO streams no NaN", _log("t.npz", channels=np.full((101, 4), np.nan)),
     ["emulate", "myrio", "--trial", "t.npz"],
     ["the arrays ['channels'] hold NaN or infinite values"]),
    ("9 hardware --log a folder of the user's files", _user_folder,
     ["hardware", "--config", "hw.yaml", "--log", "mine", "--overwrite"],
     ["--log mine is a folder where a file belongs"]),
    ("11 a 300 kB --set value", None, ["trial", "--set", f"object.name={BIG}"],
     ["--set object.name=xxxx", "(300000 characters)"]),
    ("11 a 300 kB --set key", None, ["trial", "--set", f"{BIG}=1"], ["(300000 characters)"]),
    ("11 a 300 kB --set number", None, ["trial", "--set", f"random_seed={BIG}"],
     ["field 'random_seed' must be an integer"]),
]


@pytest.mark.parametrize("make, argv, expected", [probe[1:] for probe in PROBES],
                         ids=[probe[0] for probe in PROBES])
def test_a_probe_stops_with_one_line_and_loses_nothing(make, argv, expected, tmp_path,
                                                       monkeypatch, capfd):
    before, entries, code, text = run_probe(make, argv, tmp_path, monkeypatch, capfd)
    assert_one_line_error(code, text, *expected)
    assert len(text) < 1200  # an echoed value is cut (typed_yaml.MAX_MESSAGE_CHARS)
    after = _contents(tmp_path)
    assert {name: after.get(name) for name in before} == before  # nothing lost or changed
    assert sorted(tmp_path.iterdir()) == entries  # nothing made


def test_a_fifo_is_refused_without_blocking(tmp_path):
    """In a child process with a time limit: a regression blocks in open(), not the suite."""
    fifo = tmp_path / "f.yaml"
    os.mkfifo(fifo)
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake", "trial", "--scenario",
                           str(fifo), "--scenario-name", "x"], capture_output=True, text=True,
                          timeout=600, cwd=tmp_path)
    assert done.returncode == 1
    assert "named pipe (FIFO)" in done.stderr


def test_read_bounded_refuses_what_is_not_a_file_before_reading(tmp_path):
    os.mkfifo(tmp_path / "fifo")
    for path, words in ((tmp_path / "fifo", "named pipe"), (tmp_path, "folder")):
        with pytest.raises(files.NotAFileError, match=words):
            files.read_bounded(path, 4096)
    with pytest.raises(files.InputTooLargeError):  # the documented devices, as before
        files.read_bounded("/dev/zero", 4096)
    assert files.read_bounded("/dev/null", 4096) == b""
    assert files.file_problem(tmp_path / "none") == "does not exist"
    assert files.file_problem(tmp_path / "fifo").startswith("is a named pipe")


# --- one run per run folder -------------------------------------------------------------------

def test_a_second_run_into_a_folder_being_written_is_refused(tmp_path, monkeypatch, capfd):
    """The first run holds the folder (staged_run's flock) while it simulates; a second
    `tegrasp trial --out` into it stops with one line before it simulates, and the first
    run's files are its own."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "same").mkdir()
    with run_folder.staged_run(tmp_path / "same") as stage:
        (stage / "trial.npz").write_bytes(b"the first run's log")
        with pytest.raises(run_folder.RunFolderError, match="another run is writing there"):
            with run_folder.staged_run(tmp_path / "same"):
                pass
        code, text = run_cli(["trial", "--out", "same", "--overwrite"], capfd)
        assert_one_line_error(code, text, "--out same: another run is writing there now")
        assert (stage / "trial.npz").read_bytes() == b"the first run's log"
    with run_folder.staged_run(tmp_path / "same"):  # released when the first run ends
        pass


# --- permissions -------------------------------------------------------------------------------

@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600)])
def test_sweep_records_honour_the_umask(umask, mode, tmp_path):
    from tegrasp_drake.sweep.records import make_record, write_record
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    trial = expand_trials(SweepSpec(objects=("box",), attempts=1))[0].to_dict()
    error = {"type": "RuntimeError", "message": "diverged", "traceback": "Traceback ..."}
    previous = os.umask(umask)
    try:
        path = write_record(tmp_path, make_record(trial, error=error))
    finally:
        os.umask(previous)
    assert path.stat().st_mode & 0o777 == mode


def test_only_rig_files_makes_temporary_files():
    """Every writer goes through rig/files.py, which gives a file the mode the umask gives
    (mkstemp alone makes it 0600). The one other: the private traceback file of the command
    line and the analysis scripts (commands/error_boundary.py)."""
    package = pathlib.Path(tegrasp_drake.__file__).parent
    users = sorted(str(p.relative_to(package)) for p in package.rglob("*.py")
                   if "mkstemp(" in p.read_text(encoding="utf-8"))
    assert users == ["commands/error_boundary.py", "rig/files.py"]
