"""Bad inputs the seventeenth hostile pass found, one test per rule: a run log whose bus
carried forged or damaged messages (another publisher on the LCM URL) is replayed from its
genuine messages (statuses the live run refuses are refused again, one status or transition
far in the future costs itself alone, a transition that names no mode, lies outside the run,
carries another time than when it was logged or does not follow the timeline is skipped and
said); a hangup to a sweep's process group, a second record-events into a folder, a viewer
with no standard input, a limited joint marked continuous, a replay against another object's
events, and sweeps against other events sharing a --logs folder."""

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
import types

import lcm
import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands.viewer_args import wait_for_viewer
from tegrasp_drake.events import save_memorized_events
from tegrasp_drake.hardware.device_log_messages import (RUN_INFO_CHANNEL, TACTILE_CHANNEL,
                                                        TRANSITION_CHANNEL)
from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_STATUS_CHANNEL, make_jaco_status
from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info, lcmt_tegrasp_transition
from tegrasp_drake.rig.files import held_folder
from tegrasp_drake.runs.hardware_log_reader import read_run_log
from tegrasp_drake.runs.hardware_run import transition_message
from tegrasp_drake.scenario.trial_log_writer import package_versions
from tests.runs.test_hardware_log_reader import (EVENTS, GRASP, logged_transitions,
                                                 tactile_message)
from tegrasp_drake.events.synthetic import synthetic_grasp
from tests import killed_runs
from tests.test_bad_input import assert_one_line_error, run_cli
from tests.test_bad_input_round29 import (_assert_one_interruption_line,
                                          _default_signal_dispositions)

WALL_START_US = 1_764_547_200_000_000  # [us] lcm-logger's clock at the run's start
ARM_PERIOD_US = 10_000  # the arm's status every 10 ms on its own clock, from 1 s
ZEROS = [0.0] * 6
HOME = [0.0, np.pi, np.pi, 0.0, 0.0, 0.0]  # [rad] within each joint's range (JACO_STATUS_RANGES)


def status(utime, position=HOME):
    return make_jaco_status(utime, position, ZEROS, ZEROS).encode()


def forged_transition(utime, from_mode, to_mode):
    message = lcmt_tegrasp_transition()
    message.utime, message.from_mode, message.to_mode = utime, from_mode, to_mode
    message.trigger, message.reason = "memorized_event", "forged"
    return message.encode()


def write_log(path, forged_at=None, forged=()):
    """A run's log (the synthetic grasp at 1 kHz, its transitions, an arm status every
    10 ms) with the (channel, data) messages `forged` written after tactile tick
    `forged_at`, as another publisher on the bus would have them logged."""
    trial = synthetic_grasp(GRASP)
    log = lcm.EventLog(str(path), "w", overwrite=True)
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name = "memorized", "box"
    info.versions_json = json.dumps(package_versions())
    now = [0.0]  # [s] the run's time as lcm-logger receives each message

    def write(channel, data):
        log.write_event(WALL_START_US + round(now[0] * 1e6), channel, data)
    write(RUN_INFO_CHANNEL, info.encode())
    transitions = iter(logged_transitions())
    pending = next(transitions, None)
    for k, t in enumerate(trial.t_ra):
        now[0] = t
        sa = trial.sa[min(np.searchsorted(trial.t_sa, t, side="right") - 1, len(trial.sa) - 1)]
        write(TACTILE_CHANNEL, tactile_message(t, sa, trial.ra[k]).encode())
        if k % 10 == 0:
            write(JACO_STATUS_CHANNEL, status(1_000_000 + k // 10 * ARM_PERIOD_US))
        if pending is not None and pending["t"] <= t:
            write(TRANSITION_CHANNEL, transition_message(pending).encode())
            pending = next(transitions, None)
        if k == forged_at:
            for channel, data in forged:
                write(channel, data)
    log.close()
    return path


@pytest.fixture(scope="module")
def genuine(tmp_path_factory):
    return read_run_log(write_log(tmp_path_factory.mktemp("genuine") / "run.lcmlog"))


def test_statuses_the_live_run_refuses_are_refused_again_and_do_not_order_the_rest(
        genuine, tmp_path):
    nan = make_jaco_status(2**40, [float("nan")] + HOME[1:], ZEROS, ZEROS).encode()
    log = read_run_log(write_log(tmp_path / "run.lcmlog", forged_at=100,
                                 forged=[(JACO_STATUS_CHANNEL, nan)] * 3))
    assert len(log.arm_status) == len(genuine.arm_status)
    assert any("live run refuses (not finite 3" in words for words in log.damage)


def test_one_status_far_in_the_future_costs_itself_alone(genuine, tmp_path):
    log = read_run_log(write_log(tmp_path / "run.lcmlog", forged_at=100,
                                 forged=[(JACO_STATUS_CHANNEL, status(2**62))]))
    assert len(log.arm_status) == len(genuine.arm_status)
    assert any(f"1 message(s) on {JACO_STATUS_CHANNEL}" in words for words in log.damage)


@pytest.mark.parametrize("utime, from_mode, to_mode, wrong", [
    (100, "Banana", "Kiwi", "are no transition a controller makes (the first: unknown mode"),
    (-5, "Reach", "Load", "are no transition a controller makes"),
    (3_000_000_000, "Reach", "Load", "lie outside the run's tactile stream's time span"),
    (100_000, "Reach", "Load", "carry a time more than 1 s from the run's when they were "
                               "logged (the first: Reach -> Load at 0.1 s, logged at 1.5 s"),
    (2**62, "Reach", "Done", "lie outside the run's tactile stream's time span"),
    # At 1.5 s the run is in Load (Reach -> Load at 1.1 s, Load -> Lift at 1.9 s).
    (1_500_000, "Lift", "Hold", "do not leave the mode the timeline is in (the first: Lift "
                                "-> Hold at 1.5 s, in Load"),
])
def test_a_forged_transition_is_skipped_and_said_and_the_timeline_kept(
        genuine, tmp_path, capfd, utime, from_mode, to_mode, wrong):
    path = write_log(tmp_path / "run.lcmlog", forged_at=1500,
                     forged=[(TRANSITION_CHANNEL, forged_transition(utime, from_mode, to_mode))])
    log = read_run_log(path)
    assert log.transitions == genuine.transitions
    assert any(f"1 message(s) on {TRANSITION_CHANNEL} {wrong}" in words
               for words in log.damage)
    save_memorized_events(tmp_path / "events", EVENTS.values())
    assert cli.main(["replay", str(path), "--events", str(tmp_path / "events")]) == 3
    out, err = capfd.readouterr()
    assert "damaged log" in err and "Traceback" not in err
    printed = [line.split("]", 1)[1].split("(")[0].strip() for line in out.splitlines()
               if " -> " in line]
    assert printed == [f"{t['from']} -> {t['to']}" for t in genuine.transitions]


def test_a_hangup_sent_to_a_sweeps_process_group_is_one_line(tmp_path):
    """A terminal that closes sends SIGHUP to the whole process group, the pool's helper
    processes too; multiprocessing's resource tracker died of it and, relaunched during the
    clean-up, printed a traceback for each semaphore it had not seen."""
    started = tmp_path / "started"
    started.mkdir()
    process = subprocess.Popen(
        [sys.executable, "-m", "tegrasp_drake", "sweep", "--objects", "box", "--controllers",
         "open_loop", "--attempts", "2", "--workers", "2", "--out", str(tmp_path / "out"),
         "--trial-function", "tests.fake_trials:started_fake_trial", "--no-progress"],
        env={**killed_runs.environment(), "FAKE_TRIALS_STARTED": str(started)},
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True,
        preexec_fn=_default_signal_dispositions)
    try:
        deadline = time.monotonic() + 300.0
        while len(list(started.iterdir())) < 2:  # both workers are in a trial
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.1)
        os.killpg(process.pid, signal.SIGHUP)
        _, err = process.communicate(timeout=300)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
    _assert_one_interruption_line(process.returncode, err, "SIGHUP")
    assert "resource_tracker" not in err and "leak" not in err, err


def test_record_events_into_a_folder_another_recording_holds_is_refused_at_once(tmp_path,
                                                                                capfd):
    """Two record-events into one folder: the second replaced the first's events when both
    saved; now it is refused before it simulates, as a second run into an --out is."""
    events = tmp_path / "events"
    events.mkdir()
    with held_folder(events):  # the first recording, still running
        code, text = run_cli(["record-events", "--object", "box", "--set", "random_seed=620",
                              "--events", str(events), "-q"], capfd)
    assert_one_line_error(code, text, f"--events {events}: another run is recording events "
                                      "there now")
    assert list(events.iterdir()) == []


class _Viewer:
    def web_url(self):
        return "http://localhost:7000"


@pytest.mark.parametrize("stdin", [None, "hung up"])
def test_the_viewer_closes_when_there_is_no_standard_input_to_wait_on(monkeypatch, capsys,
                                                                      stdin):
    """`tegrasp trial --meshcat 0<&-` ran the trial, then stopped with exit 70 waiting for
    Enter on a standard input Python had set to None."""
    class HungUp:
        def readline(self):
            raise OSError(5, "Input/output error")
    monkeypatch.setattr(sys, "stdin", None if stdin is None else HungUp())
    wait_for_viewer(types.SimpleNamespace(meshcat=True), _Viewer())
    assert capsys.readouterr().err.count("\n") == 1


@pytest.mark.parametrize("flags, joint", [("[true,true,false,true,true,true]", 2),
                                          ("[true,false,true,true,true,true]", 3)])
def test_a_limited_joint_marked_continuous_is_refused_in_both_configs(tmp_path, flags, joint):
    """The tracker wraps a continuous joint's error into [-pi, pi): on the JACO2's joints 2
    and 3, which have stops, that drives an error past half a turn through the stop."""
    from tegrasp_drake.hardware.config import LoadHardwareConfig
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    words = f"marks joint {joint} continuous, but the JACO2's joint {joint} turns only"
    with pytest.raises(ConfigError, match=words):
        LoadScenario(name="box", overrides=[f"arm.tracker.continuous_joints={flags}"])
    config = tmp_path / "hardware.yaml"
    config.write_text(f"arm: {{tracker: {{continuous_joints: {flags}}}}}\n")
    with pytest.raises(ConfigError, match="field 'arm.tracker.continuous_joints' " + words):
        LoadHardwareConfig(config)


def test_a_replay_against_another_objects_events_says_whose_run_it_was(genuine, capfd):
    """`replay --object thin_cylinder` of a box run named the log's object thin_cylinder."""
    code = cli.main(["replay", str(genuine.path), "--object", "thin_cylinder"])
    out, err = capfd.readouterr()
    assert code == 0, err
    assert "the run was of the object 'box'" in err and err.count("\n") == 1
    assert "object thin_cylinder's events (the run's object: box)" in out


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


def test_write_config_says_which_ports_are_defaults_not_emulated_devices():
    """`emulate jaco --write-config` wrote the default gripper and tactile ports without a
    word; a run on that config opens them."""
    from tegrasp_drake.commands.emulate import config_written_line
    from tegrasp_drake.emulators.launcher import Emulators, hardware_config_for
    line = config_written_line(Emulators(lcm_url="memq://", out=lambda text: None), "hw.yaml")
    assert "gripper.port /dev/" in line and "tactile.port /dev/" in line
    assert "the defaults, for devices not emulated here" in line and "\n" not in line
    devices = {"gripper": {"port": "/dev/pts/7"}}  # the robotiq emulator's, as it records it
    robotiq = types.SimpleNamespace(devices=devices,
                                    hardware_config=lambda: hardware_config_for(devices))
    line = config_written_line(robotiq, "hw.yaml")
    assert "gripper.port" not in line and "tactile.port /dev/" in line
