"""A hardware run's LCM log read back, and the event matcher re-run on it (`tegrasp replay`),
on a log written here from a synthetic grasp."""

import contextlib
import io
import json
import struct

import lcm
import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.hardware.device_log_messages import (RUN_INFO_CHANNEL, TACTILE_CHANNEL,
                                                        TRANSITION_CHANNEL)
from tegrasp_drake.events import extract_memorized_events, save_memorized_events
from tegrasp_drake.events.synthetic import SyntheticGraspConfig, synthetic_grasp
from tegrasp_drake.runs.hardware_run import BusLogWriter, transition_message
from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info, lcmt_tegrasp_tactile
from tegrasp_drake.runs.hardware_log_reader import RunLogError, read_run_log
from tegrasp_drake.runs.hardware_log_replay import (expected_event_schedule,
                                                    matcher_config_of_run, replay_matcher)
from tegrasp_drake.events.event_matcher import EventMatcherConfig
from tegrasp_drake.events.replay import live_matcher_config
from tegrasp_drake.rig.objects import object_description
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.scenario.trial_log_writer import package_versions

GRASP = SyntheticGraspConfig()
# felt on the box (a replay checks the run's object's events against the object it grasped)
EVENTS = extract_memorized_events(
    synthetic_grasp(GRASP), object_name="box", sa_rate_hz=100.0, ra_rate_hz=1000.0,
    package_versions={}, object_description=object_description(LoadScenario(name="box").object))
LATE = 0.3  # [s] the logged transitions come this long after the physical events


def logged_transitions():
    times = GRASP.transition_times()
    return [{"t": times["reach_load"] + LATE, "from": "Reach", "to": "Load",
             "trigger": "memorized_event", "reason": "Reach-Load event"},
            {"t": times["load_lift"] + LATE, "from": "Load", "to": "Lift",
             "trigger": "memorized_event", "reason": "Load-Lift event"},
            {"t": times["lift_hold"] + LATE, "from": "Lift", "to": "Hold",
             "trigger": "timer", "reason": "lift motion ended"},
            {"t": times["place_unload"] - 0.2, "from": "Hold", "to": "Place",
             "trigger": "timer", "reason": "held"},
            {"t": times["place_unload"] + LATE, "from": "Place", "to": "Unload",
             "trigger": "memorized_event", "reason": "Place-Unload event"}]


def tactile_message(t, sa, ra):
    message = lcmt_tegrasp_tactile()
    message.utime = message.device_utime = int(round(t * 1e6))
    message.num_taxels = 12
    message.left_taxel_forces = [sa[0] / 12] * 12
    message.right_taxel_forces = [sa[1] / 12] * 12
    message.left_pad_acceleration = [ra[0], 0.0, 0.0]
    message.right_pad_acceleration = [ra[1], 0.0, 0.0]
    message.arrival_s, message.tick_s = t, t + 0.001
    return message


@pytest.fixture(scope="module")
def run_log_path(tmp_path_factory):
    """A run's log as `tegrasp hardware` writes it, from the synthetic grasp at 1 kHz."""
    trial = synthetic_grasp(GRASP)
    path = tmp_path_factory.mktemp("run") / "run.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name = "memorized", "box"
    info.versions_json = json.dumps(package_versions())  # as run_info_message writes it
    log.write_event(0, RUN_INFO_CHANNEL, info.encode())
    transitions = iter(logged_transitions())
    pending = next(transitions, None)
    for k, t in enumerate(trial.t_ra):
        sa = trial.sa[min(np.searchsorted(trial.t_sa, t, side="right") - 1, len(trial.sa) - 1)]
        log.write_event(k, TACTILE_CHANNEL, tactile_message(t, sa, trial.ra[k]).encode())
        if pending is not None and pending["t"] <= t:
            log.write_event(k, TRANSITION_CHANNEL, transition_message(pending).encode())
            pending = next(transitions, None)
    log.close()
    return path


def test_run_log_reads_back_channels_and_transitions(run_log_path):
    log = read_run_log(run_log_path)
    assert log.run_info.object_name == "box"
    assert [(t["from"], t["to"]) for t in log.transitions] == [
        (t["from"], t["to"]) for t in logged_transitions()]
    trial = log.tactile_trial()
    reference = synthetic_grasp(GRASP)
    np.testing.assert_allclose(trial.ra, reference.ra, atol=1e-12)
    assert trial.sa.max() == pytest.approx(reference.sa.max())


def test_expected_event_follows_the_mode_the_logged_transitions_left():
    index = {"reach_load": 0, "load_lift": 1, "place_unload": 2}
    schedule = expected_event_schedule(logged_transitions(), index)
    assert [event for _, event in schedule] == [0, 1, -1, -1, 2, -1]
    assert schedule[1][0] == logged_transitions()[0]["t"]


def test_replayed_matcher_matches_each_memorized_event_before_its_transition(run_log_path):
    log = read_run_log(run_log_path)
    results = replay_matcher(log.tactile_segments(), log.transitions, EVENTS)
    assert [r.transition for r in results] == ["reach_load", "load_lift", "lift_hold",
                                                "place_unload"]
    for result in results:
        assert result.match_time is not None, result
        assert -0.5 < result.delay < 0.0


def test_the_replay_takes_the_live_runs_matcher_settings_from_its_scenario():
    info = lcmt_tegrasp_run_info()
    info.scenario_yaml = scenario_to_yaml(LoadScenario(name="faithful_world", overrides=(
        "controller.matching.ra_envelope_hz=2.0",
        "controller.matching.ra_noise_floor_sigmas=5.39",
        "controller.matching.ra_noise_quiet_s=1.5", "controller.matching.sa_threshold=0.85")))
    config = matcher_config_of_run(info, EVENTS)
    assert (config.ra_envelope_hz, config.ra_noise_floor_sigmas, config.ra_noise_quiet_s,
            config.sa_threshold) == (2.0, 5.39, 1.5, 0.85)
    assert (config.sa_rate_hz, config.ra_rate_hz) == (108.0, 1000.0)  # the scenario's
    assert matcher_config_of_run(lcmt_tegrasp_run_info(), EVENTS) == live_matcher_config(
        EVENTS, EventMatcherConfig())  # no scenario: the defaults at the events' rates


def test_the_replay_reads_the_runs_scenario_once(run_log_path, tmp_path, monkeypatch):
    import tegrasp_drake.runs.hardware_log_reader as reader
    import tegrasp_drake.runs.hardware_log_replay as replay
    with_scenario = tmp_path / "run.lcmlog"  # the run's log with its scenario in its run info
    source, copy = lcm.EventLog(str(run_log_path), "r"), lcm.EventLog(str(with_scenario), "w")
    for event in source:
        data = event.data
        if event.channel == RUN_INFO_CHANNEL:
            info = lcmt_tegrasp_run_info.decode(data)
            info.scenario_yaml = scenario_to_yaml(LoadScenario())  # the box, memorized
            data = info.encode()
        copy.write_event(event.timestamp, event.channel, data)
    source.close()
    copy.close()
    run_log_path = with_scenario
    parsed = []
    for module in (reader, replay):
        real = module.scenario_from_yaml
        monkeypatch.setattr(module, "scenario_from_yaml",
                            lambda text, *args, real=real: parsed.append(1) or real(text, *args))
    replay.replay_run_log(run_log_path)
    assert len(parsed) == 1


def test_the_replayed_matcher_has_the_runs_ra_envelope(run_log_path):
    log = read_run_log(run_log_path)
    raw = replay_matcher(log.tactile_segments(), log.transitions, EVENTS,
                         config=live_matcher_config(EVENTS))
    enveloped = replay_matcher(log.tactile_segments(), log.transitions, EVENTS,
                               config=live_matcher_config(EVENTS, EventMatcherConfig(
                                   ra_envelope_hz=2.0)))
    first_raw, first_enveloped = raw[0].best_scores, enveloped[0].best_scores
    assert first_raw[:2] == pytest.approx(first_enveloped[:2])  # SA unchanged
    assert abs(first_raw[2] - first_enveloped[2]) > 1e-3  # RA scored on the envelope


def test_the_replayed_matcher_has_the_runs_ra_noise_floor(run_log_path):
    # Until the quiet period is measured no RA window can match: a 1.5 s one hides the
    # Reach-Load event (logged at 1.1 s) that the replay matches without a floor.
    log = read_run_log(run_log_path)
    results = replay_matcher(log.tactile_segments(), log.transitions, EVENTS,
                             config=live_matcher_config(EVENTS, EventMatcherConfig(
                                 ra_noise_floor_sigmas=5.39, ra_noise_quiet_s=1.5)))
    assert results[0].transition == "reach_load" and results[0].match_time is None
    assert results[0].best_scores[2:] == pytest.approx([0.0, 0.0])


def test_replay_command_reports_the_log_and_the_matches(run_log_path, tmp_path):
    save_memorized_events(tmp_path / "events", EVENTS.values())
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert cli.main(["replay", str(run_log_path), "--events", str(tmp_path / "events"),
                         "--json"]) == 0
    summary = json.loads(out.getvalue())
    assert summary["object"] == "box" and summary["controller"] == "memorized"
    assert all(r["match_time"] is not None for r in summary["replay"])
    assert all(t is not None for t in summary["sequence_fire_times"].values())


def test_a_verbose_replay_logs_what_it_read_and_replayed(run_log_path, tmp_path, caplog):
    save_memorized_events(tmp_path / "events", EVENTS.values())
    with contextlib.redirect_stdout(io.StringIO()):
        assert cli.main(["replay", "-v", str(run_log_path), "--events",
                         str(tmp_path / "events")]) == 0
    info = [record.getMessage() for record in caplog.records
            if record.levelname == "INFO" and record.name.startswith("tegrasp_drake")]
    assert any(f"read {run_log_path}" in line and RUN_INFO_CHANNEL in line for line in info), info
    assert any("re-run" in line and "events of box" in line for line in info), info


def test_a_missing_log_is_named(tmp_path):
    with pytest.raises(RunLogError, match="run log '.*none.lcmlog' does not exist"):
        read_run_log(tmp_path / "none.lcmlog")


def test_an_intact_log_reports_no_damage(run_log_path):
    assert read_run_log(run_log_path).damage == []


def _truncated(data: bytes) -> bytes:
    return data[:len(data) // 2 + 7]  # mid-message


def _bit_flipped(data: bytes) -> bytes:
    damaged = bytearray(data)
    for k in range(len(damaged) // 3, len(damaged) // 3 + 20000, 97):
        damaged[k] ^= 0x5A
    return bytes(damaged)


@pytest.mark.parametrize("damage, words", [(_truncated, "truncated: the last message is cut"),
                                           (_bit_flipped, "corrupt bytes in")])
def test_a_damaged_log_is_replayed_as_far_as_it_goes_and_says_what_was_lost(
        damage, words, run_log_path, tmp_path, capsys):
    """A log truncated mid-message or with flipped bytes is replayed as far as it goes,
    with one warning that names the damage and the messages read, and exit code 3 (never
    exit 0 with the rest silently dropped)."""
    save_memorized_events(tmp_path / "events", EVENTS.values())
    path = tmp_path / "damaged.lcmlog"
    path.write_bytes(damage(run_log_path.read_bytes()))
    total = sum(read_run_log(run_log_path).message_counts.values())
    log = read_run_log(path)
    read = sum(log.message_counts.values())
    assert 0 < read < total
    code = cli.main(["replay", str(path), "--events", str(tmp_path / "events"), "--json"])
    captured = capsys.readouterr()
    assert code == 3
    warning = [line for line in captured.err.splitlines() if "warning" in line]
    assert len(warning) == 1 and str(path) in warning[0] and words in warning[0]
    assert f"read {read} messages" in warning[0]
    assert json.loads(captured.out)["damage"] == log.damage


def test_a_log_whose_tactile_messages_are_all_rejected_says_why_it_cannot_be_replayed(tmp_path):
    path = tmp_path / "nan.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for k in range(5):
        message = tactile_message(0.001 * k, [float("nan"), 0.0], [0.0, 0.0])
        log.write_event(k, TACTILE_CHANNEL, message.encode())
    log.close()
    with pytest.raises(RunLogError) as refused:
        read_run_log(path).tactile_trial()
    words = str(refused.value)
    assert "fewer than 2 tactile messages" in words and "0 usable of 5" in words
    assert "impossible values" in words


def test_a_log_joined_to_itself_is_a_damaged_log_exit_3(run_log_path, tmp_path, capfd):
    joined = tmp_path / "joined.lcmlog"
    joined.write_bytes(run_log_path.read_bytes() * 2)
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code = cli.main(["replay", str(joined), "--events", str(tmp_path / "events"), "--json"])
    err = capfd.readouterr().err
    assert code == 3
    assert "damaged log" in err and TRANSITION_CHANNEL in err and "internal error" not in err
    assert len(read_run_log(joined).transitions) == len(read_run_log(run_log_path).transitions)


def test_each_arm_status_in_a_log_is_decoded_once(tmp_path, monkeypatch):
    """The reader decodes a status and checks the decoded message as the live run does; it
    decoded each twice (once to read it, once more in the live check of its bytes)."""
    from drake import lcmt_jaco_status
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_STATUS_CHANNEL, make_jaco_status
    path = tmp_path / "arm.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    home = [0.0, np.pi, np.pi, 0.0, 0.0, 0.0]  # [rad] within each joint's range
    for k in range(50):
        log.write_event(k, TACTILE_CHANNEL,
                        tactile_message(0.001 * k, [1.0, 1.0], [0.0, 0.0]).encode())
        if k % 10 == 0:
            position = home if k else [float("nan")] + home[1:]  # the first: refused
            log.write_event(k, JACO_STATUS_CHANNEL, make_jaco_status(
                1_000_000 + 1000 * k, position, [0.0] * 6, [0.0] * 6).encode())
    log.close()
    decode = lcmt_jaco_status.decode
    decoded = []
    monkeypatch.setattr(lcmt_jaco_status, "decode",
                        staticmethod(lambda data: decoded.append(1) or decode(data)))
    run = read_run_log(path)
    assert len(decoded) == 5
    assert len(run.arm_status) == 4
    assert any("live run refuses (not finite 1" in words for words in run.damage)


DATA_LENGTH_AT = 24  # LCM event header: sync 4, number 8, timestamp 8, channel length 4 bytes


def _first_event(data: bytes) -> bytes:
    """The bytes of a log's first event: its header (28 bytes), channel and data."""
    channel_length, data_length = struct.unpack_from(">II", data, DATA_LENGTH_AT - 4)
    return data[:DATA_LENGTH_AT + 4 + channel_length + data_length]


def _first_data_length(data: bytes, length: int) -> bytes:
    damaged = bytearray(data)
    struct.pack_into(">I", damaged, DATA_LENGTH_AT, length)
    return bytes(damaged)


@pytest.mark.parametrize("length", [2**31 - 1, "past the end"])
def test_a_first_message_with_a_corrupt_length_is_counted_lost_and_the_rest_replayed(
        length, run_log_path, tmp_path, capsys):
    """A corrupt first frame is counted and skipped as one further on is: the message is
    said lost, every later one is read, and the replay warns and exits 3."""
    data = run_log_path.read_bytes()
    path = tmp_path / "first.lcmlog"
    path.write_bytes(_first_data_length(data, len(data) if length == "past the end" else length))
    total = sum(read_run_log(run_log_path).message_counts.values())
    log = read_run_log(path)
    assert sum(log.message_counts.values()) == total - 1
    assert any("1 message(s) lost" in words for words in log.damage)
    save_memorized_events(tmp_path / "events", EVENTS.values())
    code = cli.main(["replay", str(path), "--events", str(tmp_path / "events"),
                     "--object", "box", "--json"])
    warning = [line for line in capsys.readouterr().err.splitlines() if "damaged log" in line]
    assert code == 3 and len(warning) == 1 and "1 message(s) lost" in warning[0]


@pytest.mark.parametrize("damage, words", [
    (lambda data: _first_data_length(_first_event(data), 2**31 - 1), "corrupt bytes"),
    (lambda data: data[:10], "cut-off header"),
    (lambda data: _first_event(data)[:-5], "the last message is cut off")])
def test_a_log_whose_only_message_is_damaged_says_how(damage, words, run_log_path, tmp_path):
    """The first (and only) frame with a data length of 2^31-1 is a corrupt one (more than
    LCM ever sends), not a message cut off by the end of the file; one truncated mid-header
    or mid-payload is."""
    path = tmp_path / "only.lcmlog"
    path.write_bytes(damage(run_log_path.read_bytes()))
    with pytest.raises(RunLogError, match="holds no LCM message") as refused:
        read_run_log(path)
    assert words in str(refused.value)
    assert ("truncated" in str(refused.value)) == (words != "corrupt bytes")


def test_the_log_writers_count_skips_a_corrupt_first_frame(run_log_path, tmp_path):
    """The hardware run's count of logged messages reads a log whose first event's data
    length is 2^31-1 without allocating it (lcm.EventLog crashes the process on it)."""
    writer = BusLogWriter("udpm://239.255.76.67:7684?ttl=0", tmp_path / "run.lcmlog")
    writer.close(linger=0.0)
    writer.path.write_bytes(_first_data_length(run_log_path.read_bytes(), 2**31 - 1))
    total = sum(read_run_log(run_log_path).message_counts.values())
    assert writer.messages == total - 1


class _SliceRecorder(bytes):
    """Bytes that note the length of every slice taken of them."""
    lengths: list

    def __getitem__(self, index):
        part = super().__getitem__(index)
        if isinstance(index, slice):
            type(self).lengths.append(len(part))
        return part


# Rule: scanning a log copies at most a header's channel (MAX_CHANNEL_LENGTH bytes) per place
# it looks at, so bytes made of sync words (each a header whose lengths are themselves sync
# words) are scanned in time proportional to their size: the channel was sliced before its
# length was checked, up to the rest of the file at each of a million sync words (a 4 MB file
# took 70 s).
def test_a_log_of_sync_words_is_scanned_without_copying_the_rest_at_each(tmp_path):
    from tegrasp_drake.runs import hardware_log_reader as reader
    _SliceRecorder.lengths = []
    data = _SliceRecorder(reader.LCM_LOG_START * 4096)
    events, damage = reader._scan_lcm_bytes(data)
    assert events == [] and damage
    assert max(_SliceRecorder.lengths, default=0) <= reader.MAX_CHANNEL_LENGTH


# Rule: reading a run log holds its tactile messages as numeric columns, never a Python
# object a message: what RunLog.tactile holds is the bytes of its fields, a row a message.
# (What reading costs, memory and time, is measured by `python -m benchmarks.replay_memory`.)
TACTILE_ROW_BYTES = {"t": 8, "device_t": 8, "sa": 16, "ra": 16, "stale": 1, "zeroing": 1,
                     "arrival_s": 8, "tick_s": 8, "wall_us": 8}


def test_a_run_logs_tactile_messages_are_held_as_the_bytes_of_their_fields(run_log_path):
    log = read_run_log(run_log_path)
    rows = log.message_counts[TACTILE_CHANNEL]
    assert set(log.tactile) == set(TACTILE_ROW_BYTES)
    for name, column in log.tactile.items():
        assert isinstance(column, np.ndarray) and column.dtype != object, name
        assert len(column) == rows and column.nbytes == TACTILE_ROW_BYTES[name] * rows, name


class _RecordedReads:
    """A binary stream that notes the size asked of every read (-1: all of the rest)."""

    def __init__(self, stream):
        self._stream, self.sizes = stream, []

    def read(self, size=-1):
        self.sizes.append(size)
        return self._stream.read(size)

    def seek(self, *args):
        return self._stream.seek(*args)

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self._stream.close()


@pytest.mark.parametrize("read", ["read_run_log", "count_lcm_log_events"])
def test_a_run_log_is_read_in_bounded_reads(run_log_path, monkeypatch, read):
    """The replay's reader and the hardware run's count of what it logged read the file a
    window at a time (FileWindow), never all of it at once."""
    import functools
    from tegrasp_drake.runs import hardware_log_reader as reader
    window, streams = 64 * 1024, []

    def recorded(*args, **kwargs):
        stream, size = real(*args, **kwargs)
        streams.append(_RecordedReads(stream))
        return streams[-1], size
    real = reader.open_bounded
    monkeypatch.setattr(reader, "open_bounded", recorded)
    monkeypatch.setattr(reader, "FileWindow", functools.partial(reader.FileWindow,
                                                                window=window))
    read_back = getattr(reader, read)(run_log_path)
    sizes = streams[0].sizes
    assert run_log_path.stat().st_size > 10 * window
    assert sizes and all(0 <= size <= window for size in sizes), sizes
    if read == "read_run_log":
        assert read_back.message_counts[TACTILE_CHANNEL] == len(synthetic_grasp(GRASP).t_ra)
    else:
        assert read_back == len(reader.scan_lcm_log(run_log_path)[0])


def test_a_tactile_message_read_back_holds_its_channels_exactly(run_log_path):
    """Each tactile message's SA (its pads' taxel forces summed) and RA (its pads'
    accelerations' norms) are what its decoded values give, exactly."""
    log = read_run_log(run_log_path)
    messages = [lcmt_tegrasp_tactile.decode(event.data)
                for event in lcm.EventLog(str(run_log_path), "r")
                if event.channel == TACTILE_CHANNEL]
    taxels = np.array([[*m.left_taxel_forces, *m.right_taxel_forces] for m in messages])
    acceleration = np.array([[*m.left_pad_acceleration, *m.right_pad_acceleration]
                             for m in messages])
    assert np.array_equal(log.tactile["sa"], np.column_stack(
        [taxels[:, :12].sum(axis=1), taxels[:, 12:].sum(axis=1)]))
    assert np.array_equal(log.tactile["ra"], np.column_stack(
        [np.linalg.norm(acceleration[:, :3], axis=1),
         np.linalg.norm(acceleration[:, 3:], axis=1)]))
    assert np.array_equal(log.tactile["t"], [m.utime * 1e-6 for m in messages])
    assert np.array_equal(log.tactile["tick_s"], [m.tick_s for m in messages])
