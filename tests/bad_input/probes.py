"""Helpers the bad-input tests share: running the command line in-process and reading its
one error line, a folder's contents before and after, small well-formed trial logs and
memorized events to spoil, forged sweep records, and drivers and fakes that stand in for
devices and trials. Imported by the tests under tests/bad_input/ and by other test modules."""

import argparse
import hashlib
import io
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import tegrasp_drake
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem
from pydrake.systems.primitives import ConstantVectorSource

from tegrasp_drake import cli
from tegrasp_drake.emulators.myrio_emulator import TactileRecordingError, load_tactile_recording
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.trial_log_file import (ARRAY_FIELDS, FORMAT_VERSION, TrialLogError,
                                                   load_trial_log)
from tegrasp_drake.sweep.records import _checksum, record_path
from tegrasp_drake.sweep.runner import run_sweep
from tegrasp_drake.tactile.sampling import samples_per_window
from tests.fake_trials import fake_trial, whole_result
from tests.trial_log_contents import edit_trial_log, write_trial_log_contents


def run_cli(argv, capfd) -> tuple[int, str]:
    """(exit code, what it printed) of `tegrasp ARGV`, run in this process."""
    try:
        code = cli.main(argv)
        message = ""
    except SystemExit as exit_:
        code, message = (1, exit_.code) if isinstance(exit_.code, str) else (exit_.code, "")
    captured = capfd.readouterr()
    return code, "\n".join(part for part in (message, captured.err, captured.out) if part)


def folder_contents(folder: pathlib.Path) -> dict:
    """Every regular file under `folder` (relative path -> sha256): what a refused command
    must leave as it was."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and not p.is_symlink()}


def run_probe(make, argv, folder: pathlib.Path, monkeypatch, capfd):
    """Runs `tegrasp ARGV` in `folder`, after `make(folder)` (when given) laid out its
    hostile inputs; returns (the folder's files before, its entries before, exit code,
    what it printed)."""
    monkeypatch.chdir(folder)
    if make:
        make(folder)
    before, entries = folder_contents(folder), sorted(folder.iterdir())
    code, text = run_cli(argv, capfd)
    return before, entries, code, text


def assert_probe_refused(make, argv, expected, folder: pathlib.Path, monkeypatch, capfd):
    """Runs a probe (run_probe) and asserts its one-line error naming `expected` and that no
    file it found was lost or changed; returns (its entries before, what it printed)."""
    before, entries, code, text = run_probe(make, argv, folder, monkeypatch, capfd)
    assert_one_line_error(code, text, *expected)
    after = folder_contents(folder)
    assert {name: after.get(name) for name in before} == before  # nothing lost or changed
    return entries, text


def assert_one_line_error(code, text, *expected):
    assert code != 0, text
    assert "Traceback" not in text, text
    error_lines = [line for line in text.splitlines() if "error" in line]
    assert len(error_lines) == 1, text
    assert len(text.strip().splitlines()) == 1, text  # nothing else printed
    for words in expected:
        assert words in error_lines[0], text


def edit_json(path, change):
    data = json.loads(path.read_text())
    change(data)
    path.write_text(json.dumps(data))


def trial_log(path, **changes):
    """A small well-formed trial log (the arrays' shapes as TrialLog.save writes them, each
    time base at its logger's period for the default scenario: 108 Hz, 1 kHz, 10 ms)."""
    n_sa, n_ra, n_slow = 11, 101, 11
    arrays = {"t_sa": np.arange(n_sa) / 108.0, "taxels": np.ones((n_sa, 24)),
              "true_taxels": np.ones((n_sa, 24)), "t_ra": np.linspace(0, 0.1, n_ra),
              "channels": np.ones((n_ra, 4)), "pad_acceleration": np.zeros((n_ra, 6)),
              "t_slow": np.linspace(0, 0.1, n_slow), "arm_q": np.zeros((n_slow, 6)),
              "arm_q_desired": np.zeros((n_slow, 6)), "gripper_command": np.zeros((n_slow, 3)),
              "gripper_status": np.zeros((n_slow, 8)), "phase": np.zeros(n_slow),
              "object_state": np.zeros((n_slow, 13))}
    arrays["object_state"][:, 0] = 1.0  # the identity orientation, a unit quaternion
    for name in ("arm_q", "arm_q_desired"):  # joints 2 and 3 within the JACO2's limits
        arrays[name][:, 1:3] = [3.0, 1.0]
    assert set(arrays) == set(ARRAY_FIELDS)
    arrays.update(changes)
    if "channels" not in changes:  # Eq. 1-2 of the taxels and accelerations, as logged
        try:
            arrays["channels"] = channels_of(arrays)
        except (IndexError, ValueError, TypeError):  # a probe's malformed array: refused anyway
            pass
    # every trial log names its controller (trial_log_file.REQUIRED_META_FIELDS): the
    # default scenario's
    meta = {"format_version": FORMAT_VERSION, "controller": "memorized"}
    return write_trial_log_contents(path, {"meta": meta, **arrays})


def memorized_events(object_name="mine", sa_rate_hz=108.0, seed=0):
    rng = np.random.default_rng(seed)

    def window(rate):
        values = rng.uniform(0.1, 1.0, (2, samples_per_window(0.5, rate)))
        return values / values.max(axis=1, keepdims=True)
    return [MemorizedEvent(object_name=object_name, transition=transition,
                           sa=window(sa_rate_hz), ra=window(1000.0), sa_rate_hz=sa_rate_hz,
                           ra_rate_hz=1000.0, transition_time_s=1.0 + k)  # in grasp order
            for k, transition in enumerate(REQUIRED_TRANSITIONS)]


def channels_of(arrays) -> np.ndarray:
    """A log's channels as its loggers record them: each pad's taxel sum (Eq. 1) held from the
    first taxel sample at or after each RA time (past the last one: the last), and the size of
    each pad's acceleration (Eq. 2)."""
    t_sa, t_ra = np.asarray(arrays["t_sa"]), np.asarray(arrays["t_ra"])
    rows = np.minimum(np.searchsorted(t_sa, t_ra - 1e-9, side="left"), len(t_sa) - 1)
    taxels, axes = np.asarray(arrays["taxels"]), np.asarray(arrays["pad_acceleration"])
    scale = np.maximum(np.abs(axes).max(axis=1, initial=0.0), 1e-300)[:, None]
    with np.errstate(over="ignore"):  # a probe's 1e300 (its range refuses it first)
        return np.column_stack([taxels[rows, :12].sum(axis=1), taxels[rows, 12:].sum(axis=1),
                                scale[:, 0] * np.linalg.norm(axes[:, :3] / scale, axis=1),
                                scale[:, 0] * np.linalg.norm(axes[:, 3:] / scale, axis=1)])


def logged_phases(meta: dict, t_slow) -> np.ndarray:
    """The 'phase' samples at `t_slow` [s] a writer logs for `meta`'s timeline: the Mode of
    its last transition at or before each sample (Reach before the first), or the index of
    the last phase of 'phases' started by then ('phase_starts'); zeros without either."""
    from tegrasp_drake.control.grasp_modes import Mode
    t_slow = np.asarray(t_slow, dtype=float)
    phase = np.zeros(len(t_slow))
    if meta.get("transitions"):
        for entry in meta["transitions"]:
            phase[t_slow >= entry["t"]] = float(Mode.from_label(entry["to"]))
    elif meta.get("phases") and meta.get("phase_starts"):
        for k, name in enumerate(meta["phases"]):
            if name in meta["phase_starts"]:
                phase[t_slow >= meta["phase_starts"][name]] = float(k)
    return phase


def trial_log_with(path, meta=None, **arrays):
    """A small trial log (trial_log's) with `meta` merged into its metadata, its 'phase' (when
    not given) that of `meta`'s timeline (logged_phases)."""
    if "phase" not in arrays and isinstance(meta, dict):
        try:
            arrays["phase"] = logged_phases(meta, arrays.get("t_slow", np.linspace(0, 0.1, 11)))
        except (TypeError, ValueError, KeyError, AttributeError):  # a probe's malformed meta
            pass
    trial_log(path, **arrays)
    return edit_trial_log(path, path, lambda stored: stored.update(meta or {}))

def denied_for(paths, real):
    """`real` (a reader whose first argument is a path: os.lstat, os.open, os.scandir,
    read_bounded), raising EACCES for `paths`: another user's files, as root (who ignores
    modes) cannot make them; every other path read as before."""
    def call(path=".", *args, **kwargs):
        if str(path) in {str(p) for p in paths}:
            raise PermissionError(13, "Permission denied", str(path))
        return real(path, *args, **kwargs)
    return call


def deny_reading(monkeypatch, module, name: str, *paths) -> None:
    """Makes the reader `module.name` refuse `paths` for permission (denied_for)."""
    monkeypatch.setattr(module, name, denied_for(paths, getattr(module, name)))


def finished_fake_sweep(out, capfd) -> list[str]:
    """The command line of a one-trial sweep (box, open_loop, the fake trial) into `out`,
    run once to its end: a results folder holding one finished record."""
    argv = ["sweep", "--objects", "box", "--controllers", "open_loop", "--attempts", "1",
            "--out", str(out), "--workers", "1", "--no-progress",
            "--trial-function", "tests.fake_trials:fake_trial"]
    assert run_cli(argv, capfd)[0] == 0
    return argv


SEED = 604


def one_line_of(error) -> str:
    text = str(error)
    assert "\n" not in text and text.strip(), text
    return text


def one_error_line(text: str) -> list[str]:
    return [line for line in text.splitlines() if "error:" in line]


def parser_of_one_command(func):
    """A command line whose one command `say` runs `func`."""
    parser = argparse.ArgumentParser(prog="tegrasp")
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("say").set_defaults(func=func)
    return parser


def tegrasp_in_child_process(argv, **environment):
    """`python -m tegrasp_drake ARGV` in a child process with `environment` changed."""
    env = {**os.environ, **environment}
    return subprocess.run([sys.executable, "-m", "tegrasp_drake", *argv], env=env,
                          capture_output=True, text=True, timeout=600)


def verbose_command(func):
    """A command line whose one command `say` (with -v/-q) runs `func`."""
    import argparse
    from tegrasp_drake.commands.verbosity import add_verbosity_arguments
    parser = argparse.ArgumentParser(prog="tegrasp")
    say = parser.add_subparsers(dest="command", required=True).add_parser("say")
    add_verbosity_arguments(say)
    say.set_defaults(func=func)
    return parser


def logs_and_prints(args):
    import logging
    for step in range(3):
        logging.getLogger("tegrasp_drake.say").info("step %d", step)
    print("said")
    return 0


def refusal(call, *words) -> str:
    """The one-line ConfigError of `call()`, which names each of `words`."""
    with pytest.raises(ConfigError) as refused:
        call()
    message = str(refused.value)
    # Its length without the checkout's folder, which a clone's path makes as long as it is.
    words_only = message.replace(str(pathlib.Path(tegrasp_drake.__file__).parent), "")
    assert "\n" not in message and len(words_only) < 400, message
    for word in words:
        assert word in message, message
    return message


class RefusingTerminal(io.StringIO):
    """A terminal that takes the first `accepted` writes, then refuses with `error`."""

    def __init__(self, error: Exception, accepted: int = 0):
        super().__init__()
        self._error, self._accepted = error, accepted

    def isatty(self):
        return True

    def write(self, text):
        if self._accepted <= 0:
            raise self._error
        self._accepted -= 1
        return super().write(text)

FAKE_TRIALS = ["--trial-function", "tests.fake_trials:fake_trial_with_events"]

BOX_SWEEP = "sweep: {controllers: [memorized], attempts: 1, objects: [box], grid: [[0.0, 0.0]]}\n"

ONE_WORLD = "worlds:\n  a: {scenario: memorizing_world}\ncells: [[a, a]]\n" + BOX_SWEEP


def transfer_out(tmp_path):
    """A one-world transfer spec and its --out with world a's events and world.json in place,
    as an earlier run left them: (spec, the world's events folder)."""
    from tegrasp_drake.transfer.matrix import LoadTransferSpec, world_assignments
    spec = tmp_path / "t.yaml"
    spec.write_text(ONE_WORLD)
    loaded = LoadTransferSpec(spec)
    events = tmp_path / "out" / "events" / "a"
    shutil.copytree(paths.package_events_dir(), events,
                    ignore=shutil.ignore_patterns("ensemble", "corrective", "prismatic"))
    (events / "world.json").write_text(json.dumps(
        list(world_assignments(loaded.worlds["a"]) + loaded.sweep.scenario_overrides)))
    return spec, events


def events_copy_with_index(tmp_path, entries=None) -> pathlib.Path:
    """A copy of the package's events folder; `entries` (a function of the index's entries)
    rewrites the index."""
    folder = tmp_path / "events"
    shutil.copytree(package_events_dir(), folder)
    if entries is not None:
        index = json.loads((folder / "index.json").read_text())
        index["events"] = entries(index["events"])
        (folder / "index.json").write_text(json.dumps(index))
    return folder


def sweep_with_events(tmp_path, out, events, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [memorized]\nattempts: 1\nbase_seed: 641\n"
                    "grid: [[0, 0], [0, 0.005]]\n")
    return run_cli(["sweep", "--spec", str(spec), "--out", str(out), "--events", str(events),
                    "--workers", "1", "--no-progress",
                    "--trial-function", "tests.fake_trials:fake_memorized_trial"], capfd)

USER_OBJECT = ["--set", "object.name=mine", "--set", "object.shape=file",
                "--set", "object.size=[0.04,0.04,0.1]", "--set", "object.mass=0.1",
                "--set", "object.friction=0.5", "--set", "random_seed=640"]


def sdf_model_file(tmp_path, link_contents: str, name: str = "object.sdf"):
    """An SDF file of one model of one link holding `link_contents` (after its inertia)."""
    file = tmp_path / name
    file.write_text('<?xml version="1.0"?><sdf version="1.9"><model name="mine">'
                    '<link name="body"><inertial><mass>0.1</mass></inertial>'
                    f"{link_contents}</link></model></sdf>")
    return file


def mesh_collision(uri: str) -> str:
    return f'<collision name="c"><geometry><mesh><uri>{uri}</uri></mesh></geometry></collision>'


def refused_log(tmp_path, meta=None, **arrays) -> str:
    path = trial_log_with(tmp_path / "trial.npz", meta, **arrays)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert str(path) in message and "\n" not in message, message
    return message


def spoiled(shape, column, value):
    array = np.zeros(shape)
    array[:, column] = value
    return array

ZERO = [0.0] * 6


def jaco_driver_on_memq(q):
    """(lcm, driver, simulator, the status receiver's context): the Jaco LCM driver on an
    in-process bus, its tracker held at joint angles `q` [rad], initialized."""
    lcm = DrakeLcm("memq://")
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    driver = AddJacoLcmDriver(builder, lcm=lcm)
    source = builder.AddSystem(ConstantVectorSource(np.concatenate([q, ZERO])))
    builder.Connect(source.get_output_port(), driver.tracker.GetInputPort("desired_state"))
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    return (lcm, driver, simulator,
            driver.status_receiver.GetMyContextFromRoot(simulator.get_context()))


def no_recording(monkeypatch):
    """An object's recordings (paper events, ensemble) replaced by a failure: the tests below
    must stop before any simulation."""
    from tegrasp_drake.recording import ensemble_events, paper_events

    def recorded(*args, **kwargs):
        raise AssertionError("an object's events were recorded")
    monkeypatch.setattr(paper_events, "record_events", recorded)
    monkeypatch.setattr(ensemble_events, "record_object_ensemble", recorded)


def forge_record(folder, spec, trial_id, edit):
    """Runs `spec` with fake trials into `folder`, then rewrites the record of `trial_id`
    (None: the first trial's) with `edit` (given the whole record, its result included) and a
    checksum that matches, as a hand edit would; returns its path."""
    summary = run_sweep(spec, fake_trial, folder, workers=1, progress=False)
    path = record_path(folder, trial_id or summary.trial_ids[0])
    record = json.loads(path.read_text())
    edit(record)
    del record["checksum"]
    record["checksum"] = _checksum(record)
    path.write_text(json.dumps(record))
    return path


def log_refusal(path, expected):
    """Both readers of a trial log refuse `path` in one line naming it and `expected`."""
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert str(path) in message and expected in message and "\n" not in message, message
    with pytest.raises(TactileRecordingError) as refused:
        load_tactile_recording(path)
    message = str(refused.value)
    assert str(path) in message and expected in message and "\n" not in message, message


def refused_meta(tmp_path, meta, expected):
    path = trial_log_with(tmp_path / "trial.npz", meta)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert str(path) in message and expected in message and "\n" not in message, message


def assert_one_interruption_line(code, text, name):
    assert "Traceback" not in text and "At:" not in text, text
    assert code == 128 + signal.Signals[name].value, (code, text)
    assert text.strip().splitlines()[-1] == (
        f"tegrasp: interrupted ({name}); the run's unfinished files were removed"), text


# A stored scenario as runs/trial.py logs it (the defaults: capacitive taxels, the PVDF film).
SCENARIO = "random_seed: 600\nobject:\n  name: box\n"


def result_refused(data, expected):
    """TrialResult's JSON form, `data` over a whole result's defaults (whole_result), is refused
    (result.json, a sweep record, a trial log's stored result all read it so) with one line
    naming `expected`."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ValueError) as refused:
        TrialResult.from_dict(whole_result(**data))
    message = str(refused.value)
    assert expected in message and "\n" not in message, message


def logged_transition(t, from_mode, to_mode, scores=None, trigger="memorized_event"):
    entry = {"t": t, "from": from_mode, "to": to_mode, "trigger": trigger,
             "reason": "event"}
    return {**entry, "scores": scores} if scores is not None else entry


# A controller trial's metadata as runs/trial.py writes it, on the small log (0 to 0.1 s).
TIMELINE = [logged_transition(0.02, "Reach", "Load", [0.9, 0.8, 0.7, 0.95]),
            logged_transition(0.05, "Load", "Lift", [0.9, 0.8, 0.7, 0.95])]

RESULT = whole_result(**{"object": "box", "controller": "memorized", "seed": 600,
                         "hold_success": False, "final_mode": "Lift", "hold_time_s": 0.0,
                         "transitions": TIMELINE, "corrective_actions": [], "sim_time_s": 0.1})

META = {"scenario": SCENARIO, "controller": "memorized", "transitions": TIMELINE,
        "phase_starts": {"Load": 0.02, "Lift": 0.05}, "result": RESULT}


def meta_refused(tmp_path, meta, expected):
    log_refusal(trial_log_with(tmp_path / "trial.npz", meta), expected)

HANG_GUARD_S = 30.0     # a guard against a hang on a busy host, not a criterion


def wait_for(condition, what):
    deadline = time.monotonic() + HANG_GUARD_S
    while not condition():
        assert time.monotonic() < deadline, f"no {what} within {HANG_GUARD_S} s"
        time.sleep(0.01)

SEEDED_SWEEP = ("sweep: {controllers: [memorized], attempts: 1, objects: [box], "
                "grid: [[0.0, 0.0]], base_seed: 640}\n")


def earlier_run_of(folder, *names):
    """`folder` holding an earlier run as a run leaves it: trial.npz (a small trial log with
    its result and checksum: META's), each of `names` a real figure (save_figure) and
    result.json, the log's result recording them under the result's fields."""
    from tegrasp_drake.figures.figure_files import new_figure, save_figure
    from tegrasp_drake.figures.trial_figures import TRIAL_FIGURE_KEYS
    folder.mkdir(parents=True, exist_ok=True)
    result = earlier_result_of(folder)
    trial_log_with(folder / "trial.npz", META)
    for name in names:
        save_figure(new_figure(1, 1), folder / name)
        result[TRIAL_FIGURE_KEYS[name.split(".")[0]]] = str(folder / name)
    (folder / "result.json").write_text(json.dumps(result))
    return folder




def earlier_result_of(folder) -> dict:
    """The result.json an earlier run into `folder` wrote, of the log earlier_run_of writes
    (META's result, naming the folder's trial.npz as its log)."""
    return {**META["result"], "log": str(folder / "trial.npz"),
            "result": str(folder / "result.json")}


def earlier_run_file(folder, name: str):
    """`folder` holding one file of an earlier run (earlier_run_of's trial.npz or its
    result.json), as a run left it."""
    folder.mkdir(parents=True, exist_ok=True)
    if name == "trial.npz":
        trial_log_with(folder / name, META)
    else:
        (folder / name).write_text(json.dumps(earlier_result_of(folder)))
    return folder
