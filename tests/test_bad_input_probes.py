"""More bad inputs, as a table beside tests/test_bad_input.py: each stops
before anything runs with one line naming the input and what to do, a non-zero exit, and
every file that was there before left as it was."""

import os
import pathlib
import signal

import numpy as np
import pytest

from tests.test_bad_input import assert_one_line_error, folder_contents as _contents, run_probe
from tegrasp_drake.events.event_file import INDEX_FILE, MemorizedEventError
from tegrasp_drake.events.events_folder import load_memorized_events, save_memorized_events
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.figures import figure_files
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.tactile.sampling import samples_per_window

OWN_BOX = ["--set", "object.shape=box", "--set", "object.size=[0.04,0.04,0.1]",
           "--set", "object.mass=0.1", "--set", "object.friction=0.5"]


def _write(name, text):
    return lambda folder: (folder / name).write_text(text)


def _nested_aliases(folder):
    lines = ["a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]"]
    lines += [f"a{k}: &a{k} [{', '.join([f'*a{k - 1}'] * 10)}]" for k in range(1, 7)]
    (folder / "bomb.yaml").write_text("\n".join(lines) + "\nmine: {object: {name: box}}\n")


def _large_scenario(folder):
    (folder / "big.yaml").write_text("mine: {object: {name: box}}\n"
                                     + "".join(f"k{k}: {'x' * 60}\n" for k in range(20_000)))


def _hardware_result(folder):
    (folder / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (folder / "run.result.json").write_text("an earlier result")


def _earlier_run(folder):
    (folder / "run").mkdir()
    (folder / "run" / "result.json").write_text("an earlier result")
    (folder / "run" / "trial.npz").write_text("an earlier log")
    (folder / "replay").mkdir()


def _symlink_loop(folder):
    (folder / "loop").symlink_to("loop")


def _corrupt_sweep_record(folder):
    (folder / "sweep" / "trials").mkdir(parents=True)
    (folder / "sweep" / "trials" / "memorized.box.m00.a0.json").write_text('{"trial_id": ')


PROBES = [  # (name, files made first, argv, words the one error line holds)
    ("1 hardware result beside --log", _hardware_result,
     ["hardware", "--config", "hw.yaml", "--log", "run.lcmlog"],
     ["run.result.json already holds a run's result", "--overwrite"]),
    ("2 --set unclosed list", None, ["trial", "--set", "placement.offset=[0.0,0.015"],
     ["--set 'placement.offset=[0.0,0.015'", "not valid YAML", "quote"]),
    ("2 --set mapping in a name", None, ["trial", "--set", "object.name=a: b"],
     ["--set 'object.name=a: b'", "not valid YAML", "object.name='a: b'"]),
    ("2 --set undefined alias", None, ["trial", "--set", "random_seed=*foo"],
     ["--set 'random_seed=*foo'", "undefined alias 'foo'"]),
    ("2 --set python tag", None,
     ["trial", "--set", "random_seed=!!python/object/apply:os.system [touch hacked]"],
     ["Python object tag", "never loaded"]),
    ("3 sweep --logs FILE", _write("afile", "x"),
     ["sweep", "--logs", "afile", "--objects", "box", "--controllers", "heuristic",
      "--attempts", "1", "--out", "sweep"], ["--logs afile", "not a folder"]),
    ("5 emulate --write-config over a user's file", _write("hw.yaml", "port: mine\n"),
     ["emulate", "robotiq", "--write-config", "hw.yaml"],
     ["--write-config hw.yaml exists and was not written by `tegrasp emulate`"]),
    ("6 seed 2^32", None, ["trial", "--set", "random_seed=4294967296"],
     ["field 'random_seed' must lie in [0, 4294967295]", "32-bit"]),
    ("6 negative seed", None, ["trial", "--set", "random_seed=-1"],
     ["field 'random_seed' must lie in"]),
    ("6 seed 2^64", None, ["trial", "--set", "random_seed=18446744073709551616"],
     ["field 'random_seed' must lie in"]),
    ("7 negative taxel noise", None, ["trial", "--set", "tactile.noise_std_n=-0.01"],
     ["field 'tactile.noise_std_n' must be zero (no noise) or positive"]),
    ("7 negative film noise", None, ["trial", "--set", "vibration.noise_std_mps2=-0.05"],
     ["field 'vibration.noise_std_mps2' must be zero (no noise) or positive"]),
    ("7 mode frequency 0", None, ["trial", "--set", "vibration.film.mode_frequency_hz=0"],
     ["field 'vibration.film.mode_frequency_hz' must lie in [50, "]),
    ("7 hit after the trial", None, ["trial", "--set", "disturbance.hit_time_s=100"],
     ["field 'disturbance.hit_time_s' must come before the grasp's script ends"]),
    ("9 --overwrite with a bad --html", _earlier_run,
     ["trial", "--out", "run", "--overwrite", "--html", "replay"],
     ["--html replay is a folder"]),
    ("10 object name with /", None, ["record-events", "--set", "object.name=my/box", *OWN_BOX],
     ["field 'object.name' 'my/box' must be letters, digits"]),
    ("10 --out a file", _write("afile", "x"), ["trial", "--out", "afile"],
     ["--out afile: afile is not a folder"]),
    ("10 --out /dev/full", None, ["trial", "--out", "/dev/full"],
     ["--out /dev/full: /dev/full is not a folder"]),
    ("10 events folder a symlink loop", _symlink_loop,
     ["record-events", "--object", "box", "--events", "loop"], ["--events loop"]),
    ("10 time step 0.1 s", None, ["trial", "--set", "plant_config.time_step=0.1"],
     ["field 'plant_config.time_step' must lie in [0.0001, 0.001] s"]),
    ("10 time step 1e-7 s", None, ["trial", "--set", "plant_config.time_step=0.0000001"],
     ["field 'plant_config.time_step' must lie in"]),
    ("10 a 1e6 N hit", None, ["trial", "--set", "disturbance.hit_force_n=[0.0,1000000.0,0.0]"],
     ["field 'disturbance.hit_force_n' must be at most 100 N"]),
    ("10 mode mass 0", None, ["trial", "--set", "vibration.film.mode_mass_kg=0"],
     ["field 'vibration.film.mode_mass_kg' must lie in [0.001, 1] kg"]),
    ("10 taxel rate 0.001 Hz", None, ["trial", "--set", "tactile.sample_rate_hz=0.001"],
     ["field 'tactile.sample_rate_hz' must lie in [16, 20000] Hz"]),
    ("10 taxel rate 1e6 Hz", None, ["trial", "--set", "tactile.sample_rate_hz=1000000.0"],
     ["field 'tactile.sample_rate_hz' must lie in [16, 20000] Hz"]),
    ("10 scalar scenario with --set", _write("sc.yaml", "mine: 5\n"),
     ["trial", "--scenario", "sc.yaml", "--scenario-name", "mine", "--set", "random_seed=1"],
     ["sc.yaml: scenario 'mine' must be a mapping of fields, got int 5"]),
    ("10 sweep --attempts 100000000", None, ["sweep", "--attempts", "100000000", "--out", "sw"],
     ["field 'attempts'", "a sweep is at most 1000000 trials even confirmed"]),
    ("record-events --ensemble-runs 99", None,
     ["record-events", "--ensemble-runs", "99", "--set", "object.name=mine", *OWN_BOX],
     ["--ensemble-runs 99: give 0 (none) to 50 ideal grasps"]),
    ("also --inject-fault 0x10", None, ["emulate", "robotiq", "--inject-fault", "0x10@3"],
     ["--inject-fault '0x10@3'", "4 bits"]),
    ("also --inject-fault 0 (no fault)", None, ["emulate", "robotiq", "--inject-fault", "0@3"],
     ["--inject-fault '0@3'", "0x0 being no fault; give a CODE from 0x1 to 0xf"]),
    ("also duplicate keys", _write("dup.yaml", "mine:\n  random_seed: 1\n  random_seed: 2\n"),
     ["trial", "--scenario", "dup.yaml", "--scenario-name", "mine"],
     ["dup.yaml: key 'random_seed' appears twice (line 2, column 3 and line 3, column 3)"]),
    ("also nested aliases", _nested_aliases,
     ["trial", "--scenario", "bomb.yaml", "--scenario-name", "mine"],
     ["bomb.yaml: the YAML's aliases expand to more than 100000 values"]),
    ("also a 1.3 MB scenario", _large_scenario,
     ["trial", "--scenario", "big.yaml", "--scenario-name", "mine"],
     ["big.yaml:", "bytes of YAML; a configuration is at most 1000000 bytes"]),
    ("also plot table1 with a corrupt record", _corrupt_sweep_record,
     ["plot", "table1", "sweep", "--out", "table1.png"],
     ["1 corrupt trial record(s) in sweep", "memorized.box.m00.a0.json"]),
]


@pytest.mark.parametrize("make, argv, expected", [probe[1:] for probe in PROBES],
                         ids=[probe[0] for probe in PROBES])
def test_a_probe_stops_with_one_line_and_loses_nothing(make, argv, expected, tmp_path,
                                                       monkeypatch, capfd):
    before, _, code, text = run_probe(make, argv, tmp_path, monkeypatch, capfd)
    assert_one_line_error(code, text, *expected)
    after = _contents(tmp_path)
    assert {name: after.get(name) for name in before} == before  # nothing lost or changed
    assert not (tmp_path / "hacked").exists()


# --- all or nothing: an object's events, a figure ------------------------------------------

def _events(object_name="mine", sa_rate_hz=108.0, seed=0):
    rng = np.random.default_rng(seed)

    def window(rate):
        values = rng.uniform(0.1, 1.0, (2, samples_per_window(0.5, rate)))
        return values / values.max(axis=1, keepdims=True)
    return [MemorizedEvent(object_name=object_name, transition=transition,
                           sa=window(sa_rate_hz), ra=window(1000.0), sa_rate_hz=sa_rate_hz,
                           ra_rate_hz=1000.0) for transition in REQUIRED_TRANSITIONS]


@pytest.fixture
def python_sigint_handler():
    """Python's own Ctrl-C handler for the test, whatever an earlier test in this process
    left installed (the emulator and hardware tests install their own)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_ctrl_c_while_events_are_replaced_leaves_them_all_new(tmp_path, monkeypatch,
                                                              python_sigint_handler):
    """Probe 8: the SIGINT comes during the renames; it is held until the index is in."""
    save_memorized_events(tmp_path, _events(seed=1))
    real_replace, interrupted = os.replace, []

    def replace_then_interrupt(source, target):
        if not interrupted:
            interrupted.append(target)
            os.kill(os.getpid(), signal.SIGINT)
        real_replace(source, target)
    monkeypatch.setattr(os, "replace", replace_then_interrupt)
    new = _events(seed=2)
    with pytest.raises(KeyboardInterrupt):
        save_memorized_events(tmp_path, new)
    monkeypatch.setattr(os, "replace", real_replace)
    loaded = load_memorized_events(tmp_path, "mine")
    for event in new:
        np.testing.assert_array_equal(loaded[event.transition].sa, event.sa)
    assert not list(tmp_path.rglob("*.tmp"))


def test_a_failed_staging_leaves_the_old_events_whole(tmp_path, monkeypatch):
    old = _events(seed=1)
    save_memorized_events(tmp_path, old)
    before = _contents(tmp_path)
    from tegrasp_drake.events import events_folder
    real_stage, calls = events_folder.staged_file, []

    def stage_until_the_disk_is_full(path, data, **options):
        calls.append(path)
        if len(calls) == 3:
            raise OSError(28, "No space left on device")
        return real_stage(path, data, **options)
    monkeypatch.setattr(events_folder, "staged_file", stage_until_the_disk_is_full)
    with pytest.raises(OSError):
        save_memorized_events(tmp_path, _events(seed=2))
    assert _contents(tmp_path) == before


def test_events_of_one_object_with_different_rates_are_refused(tmp_path):
    mixed = _events(sa_rate_hz=108.0)[:2] + _events(sa_rate_hz=1000.0)[2:]
    save_memorized_events(tmp_path, mixed)
    with pytest.raises(MemorizedEventError, match="different windows or rates"):
        load_memorized_events(tmp_path, "mine")
    assert (tmp_path / INDEX_FILE).is_file()


def test_a_figure_on_a_full_disk_leaves_the_old_figure_whole(tmp_path):
    """Probe 9: savefig fails part-way; the earlier figure stays, no temporary is left."""
    old = tmp_path / "fig.png"
    old.write_bytes(b"an earlier figure")

    class FullDiskFigure:
        def savefig(self, path, **kwargs):
            pathlib.Path(path).write_bytes(b"half")
            raise OSError(28, "No space left on device")
    with pytest.raises(OSError):
        figure_files.save_figure(FullDiskFigure(), old)
    assert old.read_bytes() == b"an earlier figure"
    assert [p.name for p in tmp_path.iterdir()] == ["fig.png"]
