"""A hardware run's LCM log read by `tegrasp replay`: receive times that jump or go back,
event numbers that do not increase, TEGRASP_RUN_INFO messages that are corrupt, differ or
contradict the run, taxel forces no taxel reads, pad accelerations past the RA transducer's
full scale, device times that go back, tactile silences past the watchdog's timeout (never
stepped through by the replay), forged statuses and transitions from
another publisher are named as damage (exit code 3) or skipped and said, never trusted in
silence; what real runs show (small swaps, a silent wait) is no damage."""

import json
import struct

import lcm
import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.events import save_memorized_events
from tegrasp_drake.events.synthetic import synthetic_grasp
from tegrasp_drake.hardware.device_log_messages import (RUN_INFO_CHANNEL, TACTILE_CHANNEL,
                                                        TRANSITION_CHANNEL)
from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_STATUS_CHANNEL, make_jaco_status
from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info, lcmt_tegrasp_transition
from tegrasp_drake.rig.files import one_line
from tegrasp_drake.runs.hardware_log_reader import read_run_log
from tegrasp_drake.runs.hardware_run import transition_message
from tegrasp_drake.scenario.scenario import Scenario, scenario_to_yaml
from tegrasp_drake.scenario.trial_log_writer import package_versions
from tests.bad_input.probes import assert_one_line_error, run_cli
from tests.runs.test_hardware_log_reader import EVENTS, GRASP, logged_transitions, tactile_message


# Rule: a run log's TEGRASP_RUN_INFO is checked as a whole when it is read: a controller
# the package lacks or an object name no folder can have is refused naming the field.
@pytest.mark.parametrize("field, value", [("controller", "bogus"),
                                          ("object_name", "../../etc")])
def test_a_run_info_field_the_run_never_writes_is_refused(tmp_path, field, value):
    import lcm
    from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL
    from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info
    from tegrasp_drake.runs.hardware_log_reader import RunLogError, read_run_log
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name, info.versions_json = "memorized", "box", "{}"
    setattr(info, field, value)
    path = tmp_path / "run.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(0, RUN_INFO_CHANNEL, info.encode())
    log.close()
    with pytest.raises(RunLogError, match=f"'{field}'") as refused:
        read_run_log(path)
    assert "\n" not in str(refused.value)


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

START_US = 1_796_070_992_580_719  # a hardware log's first receive time (lcm-logger's clock)

WAIT_US = 300_000_000  # the run's info, then 300 s of silence while the devices come up

SWAP_US = 156  # the largest step back measured in hardware logs (two messages swapped)


def _run_log_received_at(path, receive_times):
    """A run's log from the synthetic grasp at 1 kHz: TEGRASP_RUN_INFO, then the tactile
    messages, written with lcm.EventLog at `receive_times(k)` [us] for message k (k = 0 the
    run's info). The messages' own times run forward whatever the receive times do."""
    trial = synthetic_grasp(GRASP)
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name, info.versions_json = "memorized", "box", "{}"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(receive_times(0), RUN_INFO_CHANNEL, info.encode())
    for k, t in enumerate(trial.t_ra):
        sa = trial.sa[min(np.searchsorted(trial.t_sa, t, side="right") - 1, len(trial.sa) - 1)]
        log.write_event(receive_times(k + 1), TACTILE_CHANNEL,
                        tactile_message(t, sa, trial.ra[k]).encode())
    log.close()
    return path


def _real_run_times(k):
    """Receive times as a real run's: the wait for the devices after the run's info, 1 ms
    ticks, and one pair of messages swapped by SWAP_US."""
    if k == 0:
        return START_US
    return START_US + WAIT_US + 1000 * k - (SWAP_US + 1000 if k == 1001 else 0)


# Rule: the receive times run forward (lcm-logger writes messages in the order it receives
# them; two that arrive together may swap by less than MAX_RECEIVE_STEP_BACK_US) and never
# jump further than a run's bus can be silent (MAX_RECEIVE_GAP_US); a log breaking this is
# damaged, and says where.
def test_a_31_year_jump_in_the_receive_times_is_damage(tmp_path):
    jump = 10**15  # added to every receive time from one message on
    path = _run_log_received_at(tmp_path / "jump.lcmlog",
                    lambda k: _real_run_times(k) + (jump if k >= 3000 else 0))
    log = read_run_log(path)
    assert len(log.damage) == 1, log.damage
    damage = log.damage[0]
    assert "receive times" in damage and "forward" in damage and "31.7 years" in damage
    assert "between messages 3000 and 3001" in damage, damage
    text = log.damage_text()
    assert str(path) in text and "\n" not in text
    assert len(log.tactile["t"]) == log.message_counts[TACTILE_CHANNEL]  # contents kept


def test_receive_times_going_back_seconds_are_damage(tmp_path):
    # a log joined to a copy of its end: the receive times go back 5 s at message 2501, while
    # the messages' own times run on
    path = _run_log_received_at(tmp_path / "back.lcmlog",
                    lambda k: _real_run_times(k) - (5_000_000 if k >= 2500 else 0))
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert "go back" in damage[0] and "by 5 s" in damage[0], damage
    assert "between messages 2500 and 2501" in damage[0], damage


def test_replay_exits_3_naming_a_jump_in_the_receive_times(tmp_path, capfd):
    save_memorized_events(tmp_path / "events", EVENTS.values())
    path = _run_log_received_at(tmp_path / "jump.lcmlog",
                    lambda k: _real_run_times(k) + (10**15 if k >= 3000 else 0))
    code, text = run_cli(["replay", str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text
    assert "Traceback" not in text
    warnings = [line for line in text.splitlines() if line.startswith("tegrasp: warning:")]
    assert len(warnings) == 1 and "damaged log" in warnings[0], text
    assert "receive times" in warnings[0] and "jump forward" in warnings[0], text


def _run_info(**fields):
    """A run's TEGRASP_RUN_INFO as run_info_message writes it (the box scenario), with
    `fields` changed."""
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name, info.versions_json = "memorized", "box", "{}"
    info.scenario_yaml = scenario_to_yaml(Scenario())
    for name, value in fields.items():
        setattr(info, name, value)
    return info


def _run_log(path, infos=(), tactile=lambda k, message: message):
    """A run's log from the synthetic grasp at 1 kHz, written with lcm.EventLog: the
    TEGRASP_RUN_INFO messages `infos` (the first before the tactile messages, the others
    after the 500th), then the tactile messages, tactile(k, message) of message k."""
    trial = synthetic_grasp(GRASP)
    log = lcm.EventLog(str(path), "w", overwrite=True)
    infos = list(infos) or [_run_info()]
    log.write_event(START_US, RUN_INFO_CHANNEL, infos[0].encode())
    for k, t in enumerate(trial.t_ra):
        sa = trial.sa[min(np.searchsorted(trial.t_sa, t, side="right") - 1, len(trial.sa) - 1)]
        receive_us = START_US + 1000 * (k + 1)
        log.write_event(receive_us, TACTILE_CHANNEL,
                        tactile(k, tactile_message(t, sa, trial.ra[k])).encode())
        if k == 500:
            for info in infos[1:]:
                log.write_event(receive_us, RUN_INFO_CHANNEL, info.encode())
    log.close()
    return path


def _replay(argv, capfd):
    code, text = run_cli(["replay", *argv], capfd)
    assert "Traceback" not in text
    return code, text


# Rule: the run's events folder (TEGRASP_RUN_INFO events_dir) is the events the run used; a
# folder that is gone is refused as a missing --events DIR is, never swapped for the
# package's events in silence.
def test_the_runs_events_folder_gone_is_refused_naming_it(tmp_path, capfd):
    gone = tmp_path / "events-of-the-run"
    path = _run_log(tmp_path / "run.lcmlog", [_run_info(events_dir=str(gone))])
    code, text = _replay([str(path)], capfd)
    assert code == 1, text
    lines = text.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tegrasp: error:"), text
    assert str(gone) in text and "--events DIR" in text, text
    # given --events, the log replays
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 0, text


# Rule: run_info_message writes object_name and controller from its scenario, once per run; a log
# whose TEGRASP_RUN_INFO contradicts itself, or that holds two that differ, is damaged.
def test_run_info_object_differing_from_its_scenario_is_damage(tmp_path, capfd):
    path = _run_log(tmp_path / "run.lcmlog", [_run_info(object_name="thin_cylinder")])
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert "thin_cylinder" in damage[0] and "'box'" in damage[0], damage
    save_memorized_events(tmp_path / "events", EVENTS.values())  # the box's only
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text
    assert "object box" in text and "thin_cylinder" in text, text


def test_run_info_controller_differing_from_its_scenario_is_damage(tmp_path, capfd):
    path = _run_log(tmp_path / "run.lcmlog", [_run_info(controller="heuristic")])
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert "controller 'heuristic'" in damage[0] and "'memorized'" in damage[0], damage
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text


def test_two_run_infos_that_differ_are_damage(tmp_path, capfd):
    path = _run_log(tmp_path / "run.lcmlog",
                    [_run_info(), _run_info(object_name="thin_cylinder",
                                            scenario_yaml="")])
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert f"2 {RUN_INFO_CHANNEL}" in damage[0] and "object_name" in damage[0], damage
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3 and "object box" in text, text


def _run_info_scenario_changed(path, change):
    """The log at `path` with its TEGRASP_RUN_INFO's scenario text's bytes passed through
    change(bytearray), in place: LCM logs carry no checksum, so corrupt bytes decode."""
    data = bytearray(path.read_bytes())
    text = scenario_to_yaml(Scenario()).encode()
    start = data.find(text)
    assert start > 0
    data[start:start + len(text)] = change(bytearray(text))
    path.write_bytes(bytes(data))


def _flipped(*positions):
    def change(text):
        for k in positions:
            text[k] ^= 0xFF
        return text
    return change


def _upper_cased(word):
    def change(text):
        k = text.find(word.encode())
        text[k:k + len(word)] = word.upper().encode()
        return text
    return change


# Rule: a TEGRASP_RUN_INFO whose scenario text corrupt bytes changed is damage, named (which
# message and field, not UTF-8 at which byte, or which field does not load), with no raw
# replacement character; the log is replayed with its logged object and the matcher's
# defaults, exit 3 as for any damaged log.
@pytest.mark.parametrize("change, words", [
    # the 'b' of 'object:\n  name: box' made 0x9d, a UTF-8 continuation byte with no lead
    (_flipped(31), "is not UTF-8 at byte 31"),
    (_upper_cased("expected_xy"), "placement.EXPECTED_XY"),  # UTF-8, a key no scenario has
])
def test_a_run_info_scenario_with_corrupt_bytes_is_damage_and_the_log_replays(
        tmp_path, capfd, change, words):
    path = _run_log(tmp_path / "run.lcmlog")
    _run_info_scenario_changed(path, change)
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert f"{RUN_INFO_CHANNEL} field 'scenario_yaml'" in damage[0] and words in damage[0], \
        damage
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text
    assert "\ufffd" not in text, text
    assert "object box" in text and "fired at" in text, text
    warnings = [line for line in text.splitlines() if line.startswith("tegrasp: warning:")]
    assert len(warnings) == 1 and words in warnings[0], text


def _run_info_versions_changed(path, change):
    """The log at `path` with its TEGRASP_RUN_INFO's versions_json bytes passed through
    change(bytearray), in place."""
    data = bytearray(path.read_bytes())
    text = VERSIONS_JSON.encode()
    start = data.find(text)
    assert start > 0
    data[start:start + len(text)] = change(bytearray(text))
    path.write_bytes(bytes(data))


VERSIONS_JSON = '{"drake": "1.51.1", "numpy": "2.4.6"}'


# Rule: a TEGRASP_RUN_INFO whose versions (provenance only) corrupt bytes changed is damage,
# named (not UTF-8 at which byte, or not a JSON object), never a refusal of the whole log.
@pytest.mark.parametrize("change, words", [
    (_flipped(19), "is not UTF-8 at byte 19 of its text"),  # the space before "numpy"
    (_flipped(0), "is not UTF-8 at byte 0 of its text"),
    (lambda text: text.replace(b"{", b"["), "is not a JSON object of package versions"),
])
def test_run_info_versions_with_corrupt_bytes_are_damage_and_the_log_replays(
        tmp_path, capfd, change, words):
    path = _run_log(tmp_path / "run.lcmlog", [_run_info(versions_json=VERSIONS_JSON)])
    _run_info_versions_changed(path, change)
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert f"{RUN_INFO_CHANNEL} field 'versions_json' {words}" in damage[0], damage
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text
    assert "\ufffd" not in text, text
    assert "object box" in text and "fired at" in text, text


# Rule: every error line shows a replacement character U+FFFD (bytes a decoder could not
# read) escaped, as it shows line breaks and ESC, so that no line looks like intact text.
def test_an_error_line_escapes_the_replacement_character():
    assert one_line("name: \ufffd\ufffdx\n") == "name: \\ufffd\\ufffdx\\n"


def _renumbered(path, number):
    """The log at `path` with event k's number set to number(k)."""
    data = bytearray(path.read_bytes())
    position = k = 0
    while position < len(data):
        _, _, _, channel_length, data_length = struct.unpack_from(">IqqII", data, position)
        struct.pack_into(">q", data, position + 4, number(k))
        position += 28 + channel_length + data_length
        k += 1
    path.write_bytes(bytes(data))
    return k


# Rule: lcm-logger numbers its events 0, 1, 2, ...; numbers that do not go up (two logs
# spliced, corrupt bytes) are damage even where no message is lost.
def test_event_numbers_that_do_not_increase_are_damage(tmp_path):
    path = _run_log(tmp_path / "run.lcmlog")
    events = _renumbered(path, lambda k: 0)
    log = read_run_log(path)
    assert sum(log.message_counts.values()) == events
    assert len(log.damage) == 1, log.damage
    assert "event number" in log.damage[0] and str(events - 1) in log.damage[0], log.damage


def test_event_numbers_starting_again_are_one_place_of_damage(tmp_path):
    # a log whose event numbers start again from 0 at its 2001st event (two logs spliced):
    # one place, the numbers that follow it followed, nothing lost
    path = _run_log(tmp_path / "run.lcmlog")
    _renumbered(path, lambda k: k if k < 2000 else k - 2000)
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert damage[0].startswith("1 event number(s) do not follow"), damage


def _every_third_tactile_damaged(tmp_path, **fields):
    """(path, read log) of a run log whose every third tactile message has `fields` set,
    checked to be one damage line that counts those messages, all of them skipped."""
    def altered(k, message):
        if k % 3 == 2:
            for name, value in fields.items():
                setattr(message, name, value)
        return message
    path = _run_log(tmp_path / "run.lcmlog", tactile=altered)
    log = read_run_log(path)
    logged = log.message_counts[TACTILE_CHANNEL]
    assert len(log.damage) == 1, log.damage
    assert f"{logged // 3} message(s) on {TACTILE_CHANNEL}" in log.damage[0], log.damage
    assert len(log.tactile["t"]) == logged - logged // 3
    return path, log


# Rule: a taxel force outside what the taxel model can read (taxel_reading_range) is an
# impossible value, as 1e30 m/s^2 is.
def test_taxel_forces_no_taxel_reads_are_damage(tmp_path):
    _every_third_tactile_damaged(tmp_path, left_taxel_forces=[-50.0] * 12)


# Rule: a pad acceleration past the full scale of the run's RA transducer (its scenario's, the
# bound a trial log's pad accelerations are held to, or the myRIO's at the default
# calibration) is an impossible value, skipped and counted; the replay exits 3.
def test_pad_accelerations_past_the_ra_transducers_full_scale_are_damage(tmp_path, capfd):
    # 5000 m/s^2: past the 2527 m/s^2 full scale at the defaults
    path, log = _every_third_tactile_damaged(tmp_path,
                                             left_pad_acceleration=[5000.0, 0.0, 0.0])
    assert "accelerations beyond" in log.damage[0], log.damage
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text


# Rule: the myRIO's clock (device_utime, unwrapped by the host) goes back only where the device
# restarted, after which it streams on; device times going back frame after frame are frames
# from elsewhere or corrupt bytes: damage (the messages are kept: the replay uses their own
# times).
def test_device_times_going_back_are_damage(tmp_path):
    def backwards(k, message):
        message.device_utime = 10_000_000 - 1000 * k
        return message
    log = read_run_log(_run_log(tmp_path / "run.lcmlog", tactile=backwards))
    logged = log.message_counts[TACTILE_CHANNEL]
    assert len(log.damage) == 1, log.damage
    assert "device times" in log.damage[0] and "go back" in log.damage[0], log.damage
    assert f"of {logged - 2} message(s)" in log.damage[0], log.damage
    assert len(log.tactile["t"]) == logged


def test_a_myrio_restart_is_no_damage(tmp_path):
    def restarted(k, message):
        if k >= 1000:  # the device's clock starts again, and runs on
            message.device_utime = 20_000 + 1000 * (k - 1000)
        return message
    log = read_run_log(_run_log(tmp_path / "run.lcmlog", tactile=restarted))
    assert log.damage == [], log.damage


def _silent(seconds, after=(1500, 3000)):
    """tactile(k, message) of _run_log: the messages' times moved `seconds` later after each of
    the messages `after` (their receive times run on 1 ms apart)."""
    def shifted(k, message):
        message.utime += int(seconds * 1e6) * sum(k >= a for a in after)
        message.device_utime = message.utime
        return message
    return shifted


class _SteppedTime:
    """A stand-in for Simulator that records the time [s] each AdvanceTo steps through, and
    refuses to step further than MOST_S at once."""
    MOST_S = 60.0

    def __init__(self):
        self.spans = []

    def __call__(self, diagram):
        from pydrake.systems.analysis import Simulator
        simulator, spans, most = Simulator(diagram), self.spans, self.MOST_S

        class Recording:
            def __getattr__(self, name):
                return getattr(simulator, name)

            def AdvanceTo(self, t):
                start = simulator.get_context().get_time()
                assert t - start <= most, f"the replay steps the matcher {t - start} s"
                spans.append(t - start)
                return simulator.AdvanceTo(t)
        return Recording()


# Rule: the station publishes TEGRASP_TACTILE every 1 ms tick while the run lasts, and its
# watchdog stops a run whose tactile data stop for its timeout; a longer silence is damage,
# and the replay steps the matcher through the logged stretches only, never through the
# silence: its cost follows the messages, not the time they span.
def test_a_tactile_silence_past_the_watchdog_is_damage_and_not_stepped_through(
        tmp_path, monkeypatch):
    from tegrasp_drake.events import replay as event_replay
    from tegrasp_drake.runs import hardware_log_replay
    from tegrasp_drake.runs.hardware_log_replay import replay_run_log
    save_memorized_events(tmp_path / "events", EVENTS.values())
    path = _run_log(tmp_path / "run.lcmlog", tactile=_silent(600.0))
    log = read_run_log(path)
    assert len(log.damage) == 1, log.damage
    assert "silent for longer than the tactile watchdog's timeout" in log.damage[0], log.damage
    assert "in 2 place(s)" in log.damage[0], log.damage
    stepped = _SteppedTime()
    monkeypatch.setattr(hardware_log_replay, "Simulator", stepped)
    monkeypatch.setattr(event_replay, "Simulator", stepped)
    replay = replay_run_log(path, events_dir=str(tmp_path / "events"))
    span = 4.0  # [s] of logged ticks, in three stretches
    assert sum(stepped.spans) <= 2 * span + 0.1, stepped.spans  # the two replays' steps
    assert len(replay.in_sequence.times) <= span / 1e-3 + 3


# Rule: the silence allowed is the run's own tactile watchdog timeout (its TEGRASP_RUN_INFO
# hardware config), the default when it logged none.
@pytest.mark.parametrize("tactile_timeout, damaged", [(None, True), (2.0, False)])
def test_the_silence_allowed_is_the_runs_tactile_watchdog_timeout(tactile_timeout, damaged,
                                                                   tmp_path):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    config = HardwareStationConfig()
    if tactile_timeout is not None:
        config.watchdog.tactile_timeout = tactile_timeout
    info = _run_info(hardware_yaml=hardware_config_to_yaml(config))
    log = read_run_log(_run_log(tmp_path / "run.lcmlog", [info], tactile=_silent(1.0)))
    assert bool(log.damage) == damaged, log.damage
    assert log.tactile_timeout == config.watchdog.tactile_timeout


# Rule: on the devices a taxel's force is its calibrated count, which may read past what the
# scenario's simulated model reads (678 N at the defaults) for a pad calibrated with a larger
# gain: such a run log is no damage, up to the largest gain a calibration file may give.
def test_a_calibrated_force_past_the_models_range_is_no_damage(tmp_path):
    def pressed_hard(k, message):
        if k == 700:
            message.left_taxel_forces = [900.0] * 12  # 0.03 N/count x 30,000 counts
        return message
    log = read_run_log(_run_log(tmp_path / "run.lcmlog", tactile=pressed_hard))
    assert log.damage == [], log.damage

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


def write_log(path, forged_at=None, forged=(), transitions=None):
    """A run's log (the synthetic grasp at 1 kHz, its transitions, an arm status every
    10 ms) with the (channel, data) messages `forged` written after tactile tick
    `forged_at`, as another publisher on the bus would have them logged; `transitions`:
    the timeline logged instead of the run's (logged_transitions)."""
    trial = synthetic_grasp(GRASP)
    log = lcm.EventLog(str(path), "w", overwrite=True)
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name = "memorized", "box"
    info.versions_json = json.dumps(package_versions())
    now = [0.0]  # [s] the run's time as lcm-logger receives each message

    def write(channel, data):
        log.write_event(WALL_START_US + round(now[0] * 1e6), channel, data)
    write(RUN_INFO_CHANNEL, info.encode())
    transitions = iter(logged_transitions() if transitions is None else transitions)
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


# Rule: a run's timeline holds only triggers its controller (TEGRASP_RUN_INFO's) fires; a
# trigger another controller's detector fires is damage, said, the timeline kept.
def test_a_trigger_the_logged_controller_never_fires_is_damage(genuine, tmp_path, capfd):
    timeline = logged_transitions()
    timeline[1] = {**timeline[1], "trigger": "heuristic_event"}
    path = write_log(tmp_path / "run.lcmlog", transitions=timeline)
    log = read_run_log(path)
    assert [t["trigger"] for t in log.transitions] == [t["trigger"] for t in timeline]
    (words,) = [words for words in log.damage if "never fires" in words]
    assert words.startswith(f"its {TRANSITION_CHANNEL} timeline's 'transitions[1].trigger' "
                            "(at "), words
    assert ("is heuristic_event, which the memorized controller never fires (it fires "
            "corrective, corrective_event, fault, memorized_event, threshold, timer)") in words
    assert not genuine.damage
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3 and "damaged log" in text and "never fires" in text, text
    code, text = _replay([str(genuine.path), "--events", str(tmp_path / "events")], capfd)
    assert code == 0 and "damaged log" not in text, text


def test_a_replay_against_another_objects_events_says_whose_run_it_was(genuine, capfd):
    """`replay --object thin_cylinder` of a box run named the log's object thin_cylinder."""
    code = cli.main(["replay", str(genuine.path), "--object", "thin_cylinder"])
    out, err = capfd.readouterr()
    assert code == 0, err
    assert "the run was of the object 'box'" in err and err.count("\n") == 1
    assert "object thin_cylinder's events (the run's object: box)" in out


# Rule: a file with no LCM event's sync word anywhere (a few bytes of text, an image) or with
# nothing in it is no LCM log, said so with its size and what to give, never called a log
# cut short; a real log whose last (or only) event is cut keeps the truncated wording.
@pytest.mark.parametrize("content, words", [
    (b"abc", "is not an LCM log: its 3 bytes hold no LCM event's sync word 0xEDA1DA01; "),
    (b"not a log\n" * 30, "is not an LCM log: its 300 bytes hold no LCM event's sync word "
                         "0xEDA1DA01; "),
    (b"", "is empty (0 bytes), not an LCM log; ")])
def test_a_file_that_is_no_lcm_log_is_named_so_not_truncated(content, words, tmp_path, capfd):
    path = tmp_path / "short2.bin"
    path.write_bytes(content)
    code, text = run_cli(["replay", str(path)], capfd)
    assert code == 1, text
    assert text.strip() == (f"tegrasp: error: run log '{path}' {words}give a log written by "
                            "`tegrasp hardware --log FILE` or lcm-logger"), text


@pytest.mark.parametrize("cut", [2, 3, 10, -5])
def test_a_real_log_cut_short_keeps_the_truncated_wording(cut, tmp_path, capfd):
    path = tmp_path / "run.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(START_US, RUN_INFO_CHANNEL, _run_info().encode())
    log.close()
    data = path.read_bytes()
    path.write_bytes(data[:cut])  # inside the sync word, the header, or the message
    code, text = run_cli(["replay", str(path)], capfd)
    assert code == 1 and "holds no LCM message (truncated: " in text, text
    assert "not an LCM log" not in text, text


# Rule: the run's object's events are used only if they were felt on the object the run
# grasped (its logged scenario's), as a trial's and a hardware run's are; events of the same
# name recorded on a heavier box are refused naming the file and the field.
def test_a_replay_with_events_felt_on_another_object_is_refused(tmp_path, capfd):
    import dataclasses
    heavier = [dataclasses.replace(event, object_description={**event.object_description,
                                                              "mass": 0.3})
               for event in EVENTS.values()]
    save_memorized_events(tmp_path / "events", heavier)
    path = _run_log(tmp_path / "run.lcmlog")
    code, text = _replay([str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "recorded on another object: mass 0.3 (recorded)")
    save_memorized_events(tmp_path / "same", EVENTS.values())
    code, text = _replay([str(path), "--events", str(tmp_path / "same")], capfd)
    assert code == 0, text


def _sparse_log(path, utime_shift_s=lambda k: 0.0):
    """A run's log of 12 tactile messages 0.3 s apart, each received as its time passes; the
    utime of message k shifted by utime_shift_s(k) [s], its receive time not."""
    trial = synthetic_grasp(GRASP)
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(START_US, RUN_INFO_CHANNEL, _run_info().encode())
    for n, k in enumerate(range(0, 12 * 300, 300)):
        t = trial.t_ra[k]
        sa = trial.sa[min(np.searchsorted(trial.t_sa, t, side="right") - 1, len(trial.sa) - 1)]
        message = tactile_message(t, sa, trial.ra[k])
        message.utime += int(utime_shift_s(n) * 1e6)
        log.write_event(START_US + 1000 + int(t * 1e6), TACTILE_CHANNEL, message.encode())
    log.close()
    return path


# Rule: a silence moves the messages' times and the log's receive times together; only a
# time that leaves its neighbours' while the receive time stays is a corrupt one, and it is
# said as a time, not as an impossible value.
def test_messages_between_silences_are_kept_and_only_a_corrupt_time_is_skipped(tmp_path):
    sparse = read_run_log(_sparse_log(tmp_path / "sparse.lcmlog"))
    assert len(sparse.tactile["t"]) == 12, sparse.damage
    assert not [d for d in sparse.damage if "impossible" in d or "carry a time" in d]
    assert any("silent for longer" in d for d in sparse.damage), sparse.damage
    flipped = read_run_log(_sparse_log(tmp_path / "flipped.lcmlog",
                                       lambda n: 100.0 if n == 5 else 0.0))
    assert len(flipped.tactile["t"]) == 11
    said = [d for d in flipped.damage if "carry a time" in d]
    assert len(said) == 1 and said[0].startswith("1 message(s) on TEGRASP_TACTILE"), said
    assert not [d for d in flipped.damage if "impossible" in d], flipped.damage


# Rule: when the events folder a run log recorded (TEGRASP_RUN_INFO events_dir) is there but
# cannot be replayed with (no events of the object, events felt on another object), the
# refusal says it is the folder the log recorded (the user gave none), names it, and says to
# give --events DIR; never a replay-less remedy such as --set.
@pytest.mark.parametrize("held", ["nothing", "another object's events"])
def test_the_runs_recorded_events_folder_that_cannot_be_used_is_named_as_the_logs(
        tmp_path, capfd, held):
    import dataclasses
    recorded = tmp_path / "events-of-the-run"
    recorded.mkdir()
    if held != "nothing":
        save_memorized_events(recorded, [dataclasses.replace(
            event, object_description={**event.object_description, "mass": 0.9})
            for event in EVENTS.values()])
    path = _run_log(tmp_path / "run.lcmlog", [_run_info(events_dir=str(recorded))])
    code, text = _replay([str(path)], capfd)
    assert_one_line_error(code, text, f"run log '{path}' recorded the events folder its run "
                          f"used, '{recorded}'", "when no --events is given", "--events DIR")
    assert "--set" not in text, text
