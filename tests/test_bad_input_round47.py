"""Bad inputs the nineteenth hostile pass found, one test per rule: a sweep stopped by a log it
could not write does not blame a dead worker; a watchdog timeout no longer than two of its
device's updates is refused naming the field; every `--events DIR` is checked to be a
folder; a scheduler address with a path is refused as an address; a YAML nested too deeply,
a trial log whose metadata is not an object and a results folder whose `trials` is a file
are said as such; a numpy array in a public dataclass's list field is refused naming it."""

import os
import pathlib

import numpy as np
import pytest

from tegrasp_drake import SweepSpec
from tegrasp_drake.hardware.config import HardwareStationConfig, watchdog_timeouts_problem
from tegrasp_drake.scenario.trial_log_file import (ARRAY_FIELDS, TrialLog, TrialLogError,
                                                   load_trial_log)
from tegrasp_drake.sweep.runner import SweepSummary, summary_text
from tests.test_bad_input import assert_one_line_error, run_cli


def test_trials_left_by_an_unwritten_log_are_not_blamed_on_a_worker():
    summary = SweepSummary(out_dir=pathlib.Path("o"), total=3, skipped=0, ran=1, errors=(),
                           unfinished=("a", "b"), corrupt=(), backend="processes:1",
                           wall_time_s=1.0, unwritten_log="L/x.npz: No space left on device")
    text = summary_text(summary)
    assert "worker" not in text and "could not be written" in text, text
    died = summary_text(SweepSummary(**{**summary.__dict__, "unwritten_log": None}))
    assert "a worker died" in died


@pytest.mark.parametrize("device, least", [("arm", "0.02"), ("gripper", "0.01"),
                                           ("tactile", "0.002")])
def test_a_watchdog_timeout_within_two_device_updates_is_refused(device, least):
    config = HardwareStationConfig()
    assert watchdog_timeouts_problem(config) is None  # the defaults
    setattr(config.watchdog, f"{device}_timeout", 1e-9)
    problem = watchdog_timeouts_problem(config)
    assert f"field 'watchdog.{device}_timeout'" in problem
    assert f"give more than {least} s" in problem


def test_a_config_with_such_a_timeout_is_one_line(tmp_path, capfd):
    config = tmp_path / "hw.yaml"
    config.write_text("arm: {lcm_url: 'udpm://239.255.76.67:7667?ttl=0'}\n"
                      "gripper: {port: /dev/null}\ntactile: {port: /dev/zero}\n"
                      "watchdog: {arm_timeout: 1.0e-9}\n")
    code, text = run_cli(["hardware", "--config", str(config)], capfd)
    assert_one_line_error(code, text, "field 'watchdog.arm_timeout'", "give more than 0.02 s")


@pytest.mark.parametrize("command", [["trial"], ["plot", "events"],
                                     ["replay", "run.lcmlog"], ["sweep", "--dry-run"]])
@pytest.mark.parametrize("kind", ["file", "pipe"])
def test_events_that_are_not_a_folder_are_said_so_by_every_command(command, kind, tmp_path,
                                                                   monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    events = tmp_path / "events"
    if kind == "file":
        events.write_text("")
    else:
        os.mkfifo(events)
    code, text = run_cli(command + ["--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}: is a ",
                          "not a folder; give a folder of memorized events")


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:8786/../x", "tcp://127.0.0.1:8786?a=1",
                                     "tcp://me@127.0.0.1:8786"])
def test_a_scheduler_address_with_more_than_host_and_port_is_not_an_address(address, tmp_path,
                                                                           capfd):
    code, text = run_cli(["sweep", "--scheduler", address, "--out", str(tmp_path / "o")],
                         capfd)
    assert_one_line_error(code, text, "beside PROTOCOL://HOST:PORT",
                          "give tcp://127.0.0.1:8786")


def test_yaml_nested_too_deeply_says_the_limit_and_what_to_give(tmp_path, capfd):
    scenario = tmp_path / "deep.yaml"
    scenario.write_text("mine: " + "[" * 5000 + "]" * 5000 + "\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, "nests deeper than Python's recursion limit",
                          "give a flat mapping of its fields")


def test_a_trial_log_whose_metadata_is_a_list_is_not_a_trial_log(tmp_path):
    saved = TrialLog(**{name: np.zeros(2) for name in ARRAY_FIELDS}, meta={}).save(
        tmp_path / "saved.npz")
    with np.load(saved) as data:
        arrays = {name: data[name] for name in data.files}
    arrays["meta"] = np.array("[1, 2]")  # the metadata's JSON text: a list
    path = tmp_path / "trial.npz"
    np.savez(path, **arrays)
    with pytest.raises(TrialLogError, match="its metadata is a JSON list, not the object a "
                                            "trial log holds; it is not a trial log"):
        load_trial_log(path)


def test_a_results_folder_whose_trials_is_a_file_says_so(tmp_path, capfd):
    (tmp_path / "trials").write_text("")
    code, text = run_cli(["plot", "latency", str(tmp_path)], capfd)
    assert_one_line_error(code, text, f"{tmp_path / 'trials'} is not a folder of trial records")


@pytest.mark.parametrize("field, value", [("grid", np.array([[0.0, 0.0]])),
                                          ("objects", np.array(["box"]))])
def test_a_numpy_array_in_a_list_field_is_refused_naming_it(field, value):
    with pytest.raises(TypeError, match=f"SweepSpec: field '{field}' must be a list or tuple, "
                                        f"got numpy.ndarray; give {field}={field}.tolist()"):
        SweepSpec(**{field: value})
