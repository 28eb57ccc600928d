"""Files given where another kind belongs: a named pipe, a device, a folder or the run's own
files as a scenario, config, log or output, trial-log metadata of the wrong form, values too
long to echo. The table below gives each a row: it stops with one line naming the input,
and every file that was there before is left as it was."""

import os

import numpy as np
import pytest

from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tests.bad_input.probes import (assert_one_line_error, assert_probe_refused, run_cli,
                                    trial_log_with)


def _write(name, text):
    return lambda folder: (folder / name).write_text(text)


# --- files that are not regular files ---------------------------------------------------------

def _fifo(folder):
    os.mkfifo(folder / "f.yaml")


def _user_folder(folder):
    (folder / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (folder / "mine").mkdir()
    (folder / "mine" / "notes.txt").write_text("the user's own file")


def _html_over_own_result(folder):
    (folder / "o").mkdir()


def _log(name, meta=None, **arrays):
    return lambda folder: trial_log_with(folder / name, meta, **arrays)

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
      "--attempts", "1", "--out", "sw"],
     ["argument --scheduler: 'notaurl': it has no port", "give tcp://HOST:PORT"]),
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
    ("12 --out a name past NAME_MAX", None, ["trial", "-q", "--out", "a" * 300],
     ["(300 characters)' is too long for the file system", "give a shorter one"]),
    ("12 --out a path past PATH_MAX", None, ["trial", "-q", "--out", "/".join(["d"] * 3000)],
     ["(5999 characters)' is too long for the file system"]),
    ("12 --scenario a name past NAME_MAX", None,
     ["trial", "-q", "--scenario", "a" * 300 + ".yaml", "--scenario-name", "x"],
     ["(305 characters)' is too long for the file system"]),
]


@pytest.mark.parametrize("make, argv, expected", [probe[1:] for probe in PROBES],
                         ids=[probe[0] for probe in PROBES])
def test_a_probe_stops_with_one_line_and_loses_nothing(make, argv, expected, tmp_path,
                                                       monkeypatch, capfd):
    entries, text = assert_probe_refused(make, argv, expected, tmp_path, monkeypatch, capfd)
    assert len(text) < 1200  # an echoed value is cut (typed_yaml.MAX_MESSAGE_CHARS)
    assert sorted(tmp_path.iterdir()) == entries  # nothing made


def test_a_log_given_to_plot_events_is_refused(tmp_path, capfd):
    code, text = run_cli(["plot", "events", "trial.npz", "--out", str(tmp_path / "x.png")],
                         capfd)
    assert_one_line_error(code, text, "takes no LOG", "--events DIR")


# Rule: an extra positional argument is a command line that does not parse: a usage error
# (exit 2, the --help pointer), before any output is checked, as argparse's own.
def test_an_extra_argument_to_plot_events_is_a_usage_error(tmp_path, capfd):
    code, text = run_cli(["plot", "events", "EXTRA_ARG", "--out", str(tmp_path / "x.png")],
                         capfd)
    assert code == 2, text
    assert_one_line_error(code, text, "takes no LOG", "'EXTRA_ARG'", "--events DIR",
                          "(see tegrasp plot --help)")
    assert list(tmp_path.iterdir()) == []
