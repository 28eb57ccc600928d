"""A hardware run's LCM log whose TEGRASP_RUN_INFO contradicts itself or the run, read by
`tegrasp replay`: refused or named as damage, never trusted in silence."""

import re
import struct

import lcm
import numpy as np
import pytest

from tegrasp_drake.events import save_memorized_events
from tegrasp_drake.events.synthetic import synthetic_grasp
from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL, TACTILE_CHANNEL
from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info
from tegrasp_drake.rig.files import one_line
from tegrasp_drake.runs.hardware_log_reader import read_run_log
from tegrasp_drake.scenario.scenario import Scenario, scenario_to_yaml
from tests.runs.test_hardware_log_reader import EVENTS, GRASP, tactile_message
from tests.test_bad_input import run_cli

START_US = 1_796_070_992_580_719  # a hardware log's first receive time (lcm-logger's clock)


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


# Rule: run_info_message writes object_name from its scenario's object, once per run; a log
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


# Rule: a taxel force outside what the taxel model can read (taxel_reading_range) is an
# impossible value, as 1e30 m/s^2 is.
def test_taxel_forces_no_taxel_reads_are_damage(tmp_path):
    def negative(k, message):
        if k % 3 == 2:
            message.left_taxel_forces = [-50.0] * 12
        return message
    path = _run_log(tmp_path / "run.lcmlog", tactile=negative)
    log = read_run_log(path)
    logged = log.message_counts[TACTILE_CHANNEL]
    assert len(log.damage) == 1, log.damage
    assert f"{logged // 3} message(s) on {TACTILE_CHANNEL}" in log.damage[0], log.damage
    assert len(log.tactile["t"]) == logged - logged // 3


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


# Rule: a tactile calibration file's gains, offsets and piezo offset lie in their declared
# ranges, each pad's lists 12 long, named in one line.
@pytest.mark.parametrize("body, field", [
    ("left: {gain: [-1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, "
     "1.0e-3, 1.0e-3, 1.0e-3]}", "left.gain[0]"),
    ("left: {gain: [1.0e-3]}", "left.gain"),
    ("right: {offset: [70000, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]}", "right.offset[0]"),
    ("left: {piezo_offset: 50.0}", "left.piezo_offset"),
])
def test_a_tactile_calibration_out_of_its_ranges_is_refused(tmp_path, body, field):
    from tegrasp_drake.hardware.myrio.tactile_calibration import LoadTactileCalibration
    from tegrasp_drake.rig.typed_yaml import ConfigError
    path = tmp_path / "calibration.yaml"
    path.write_text(body + "\n")
    with pytest.raises(ConfigError, match=f"field '{re.escape(field)}'"):
        LoadTactileCalibration(str(path))
