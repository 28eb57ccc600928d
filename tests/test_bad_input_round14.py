"""Bad inputs the fourteenth review found, one test per rule."""

import json
import pathlib
import shutil

import pytest

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.test_bad_input import run_cli
from tests.test_bad_input_round10 import _refused

_FAKE_TRIALS = ["--trial-function", "tests.fake_trials:fake_trial_with_events"]
_SWEEP = "sweep: {controllers: [memorized], attempts: 1, objects: [box], grid: [[0.0, 0.0]]}\n"
_ONE_WORLD = "worlds:\n  a: {scenario: memorizing_world}\ncells: [[a, a]]\n" + _SWEEP


def _transfer_out(tmp_path):
    """A one-world transfer spec and its --out with world a's events and world.json in place,
    as an earlier run left them: (spec, the world's events folder)."""
    from tegrasp_drake.transfer.matrix import LoadTransferSpec, world_assignments
    spec = tmp_path / "t.yaml"
    spec.write_text(_ONE_WORLD)
    loaded = LoadTransferSpec(spec)
    events = tmp_path / "out" / "events" / "a"
    shutil.copytree(paths.package_events_dir(), events,
                    ignore=shutil.ignore_patterns("ensemble", "corrective", "prismatic"))
    (events / "world.json").write_text(json.dumps(
        list(world_assignments(loaded.worlds["a"]) + loaded.sweep.scenario_overrides)))
    return spec, events


def _one_line_refusal(code, message, *words):
    assert code == 1, message
    assert message.startswith("tegrasp: error: ") and "internal error" not in message, message
    assert message.count("\n") == 0, message
    for word in words:
        assert word in message, message


# Rule: a run's own state files in its --out (a transfer's world.json and events index, a
# sensitivity study's points.json) are read with a bound and checked for their shape; a
# damaged one is refused in one line naming it (exit 1, bad input), a folder in its place
# too, before anything is recorded or run.
@pytest.mark.parametrize("damage", ["truncated", "not_a_list", "folder", "too_large"])
def test_a_damaged_world_json_in_a_transfer_out_is_refused_naming_it(tmp_path, capfd, damage):
    spec, events = _transfer_out(tmp_path)
    marker = events / "world.json"
    if damage == "truncated":
        marker.write_text('{"x": [1,')
    elif damage == "not_a_list":
        marker.write_text('{"x": 1}')
    elif damage == "folder":
        marker.unlink()
        marker.mkdir()
    else:
        with open(marker, "wb") as sparse:
            sparse.truncate(400 * 2**20)
    code, message = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                             "--workers", "1", "--no-progress", *_FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(marker))
    assert not (tmp_path / "out" / "cells").exists()


def test_a_file_where_a_worlds_events_folder_belongs_is_refused_naming_it(tmp_path, capfd):
    spec, events = _transfer_out(tmp_path)
    shutil.rmtree(events)
    events.write_text("not a folder")
    code, message = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                             "--workers", "1", "--no-progress", *_FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(events), "not a folder")


@pytest.mark.parametrize("text", ['[{"object": ', "{}"])
def test_a_damaged_events_index_in_a_transfer_out_is_bad_input(tmp_path, capfd, text):
    spec, events = _transfer_out(tmp_path)
    (events / "index.json").write_text(text)
    code, message = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                             "--workers", "1", "--no-progress", *_FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(events / "index.json"))


@pytest.mark.parametrize("text", ["[1,2", "[1,2]", '{"default": [1]}'])
def test_a_damaged_points_json_in_a_sensitivity_out_is_refused_naming_it(tmp_path, capfd,
                                                                          text):
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.position_loop_hz]\n" + _SWEEP)
    out = tmp_path / "out"
    out.mkdir()
    (out / "points.json").write_text(text)
    code, message = run_cli(["sensitivity", str(spec), "--out", str(out), "--workers", "1",
                             "--no-progress", *_FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(out / "points.json"))
    assert not (out / "cells").exists()


# Rule: a transfer spec's worlds are all checked when it is loaded, one no cell uses too.
def test_a_transfer_world_no_cell_uses_is_checked_like_the_others(tmp_path, monkeypatch):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    monkeypatch.chdir(tmp_path)
    spec = pathlib.Path("t.yaml")
    spec.write_text("worlds:\n  a: {scenario: memorizing_world}\n"
                    "  b: {scenario: faithful_world, overrides: [grasp.grip_force=-5.0]}\n"
                    "cells: [[a, a]]\n" + _SWEEP)
    with pytest.raises(ConfigError) as refused:
        LoadTransferSpec(spec)
    # One line naming the spec, the world and the setting at fault; of the preset's own
    # assignments only their count (the package's path, which the line names, varies).
    message = str(refused.value).replace(str(paths.scenarios_file()), "SCENARIOS")
    assert "\n" not in message and len(message) < 400, message
    for word in (str(spec), "worlds.b", "--set grasp.grip_force=-5.0", "4 other --set"):
        assert word in message, message
    assert "gripper.model" not in message, message


# Rule: a transfer matrix or a sensitivity study is one run: its trials (cells x each cell's
# sweep) and event recordings together are bounded as a sweep's trials are, refused with
# the cost before any world is checked or anything recorded.
def _no_world_checked(monkeypatch):
    from tegrasp_drake.transfer import matrix

    def checked(spec, running):
        raise AssertionError(f"world {running} checked before the size was")
    monkeypatch.setattr(matrix, "running_sweep", checked)


def test_a_sensitivity_study_of_too_many_trials_is_refused_with_its_cost(tmp_path,
                                                                         monkeypatch):
    from tegrasp_drake.sensitivity.study import (LoadSensitivitySpec, latin_hypercube,
                                                 run_sensitivity)
    from tests.fake_trials import fake_trial_with_events
    spec_file = tmp_path / "s.yaml"
    spec_file.write_text("parameters: [gripper.position_loop_hz]\n")
    spec = LoadSensitivitySpec(spec_file)
    points = latin_hypercube(spec, 1000)
    _no_world_checked(monkeypatch)
    _refused(lambda: run_sensitivity(spec, points, fake_trial_with_events, tmp_path / "out",
                                     workers=1, progress=False),
             "1001 cells x 243 trials", "core-hours", "100000")
    assert not (tmp_path / "out").exists()


def test_a_transfer_matrix_of_too_many_trials_is_refused_with_its_cost(tmp_path, monkeypatch):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    names = [f"w{k}" for k in range(21)]
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n" + "".join(f"  {n}: {{scenario: memorizing_world}}\n"
                                          for n in names)
                    + f"cells: {{memorize_in: [{', '.join(names)}], run_in: "
                      f"[{', '.join(names)}]}}\n")
    _no_world_checked(monkeypatch)
    _refused(lambda: LoadTransferSpec(spec), str(spec), "441 cells x 243 trials", "core-hours")


# Rule: a relative XDG_DATA_HOME is invalid (XDG Base Directory spec) and ignored, with a
# warning, not a folder below wherever the command runs.
def test_a_relative_xdg_data_home_is_ignored(monkeypatch, tmp_path, caplog):
    monkeypatch.delenv(paths.EVENTS_ENV, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.setenv("XDG_DATA_HOME", "relative/dir")
    monkeypatch.setattr(paths, "_IGNORED_DATA_HOMES", set())  # warned once per process
    assert paths.user_events_dir() == tmp_path / "home" / ".local" / "share" / "tegrasp" / (
        "events")
    assert "relative/dir" in caplog.text and "not an absolute path" in caplog.text


# Rule: a run log's TEGRASP_RUN_INFO that is there but does not decode is named as corrupt,
# not as absent.
def test_a_corrupt_run_info_message_is_named_corrupt_not_absent(tmp_path):
    import lcm
    import numpy as np
    from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL, TACTILE_CHANNEL
    from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info
    from tegrasp_drake.runs.hardware_log_reader import RunLogError
    from tegrasp_drake.runs.hardware_log_replay import replay_run_log
    from tests.runs.test_hardware_log_reader import tactile_message
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name, info.versions_json = "memorized", "box", "{}"
    garbage = np.random.default_rng(650).bytes(len(info.encode()))
    path = tmp_path / "garbage_info.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(0, RUN_INFO_CHANNEL, garbage)
    for k in range(3):
        log.write_event(k + 1, TACTILE_CHANNEL,
                        tactile_message(0.001 * k, [0.0, 0.0], [0.0, 0.0]).encode())
    log.close()
    with pytest.raises(RunLogError) as refused:
        replay_run_log(path)
    message = str(refused.value)
    assert str(path) in message and RUN_INFO_CHANNEL in message and "corrupt" in message
    assert "has no" not in message and "\n" not in message
