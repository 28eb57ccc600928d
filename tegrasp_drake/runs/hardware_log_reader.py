"""The log of a hardware run (an LCM event log, lcm-logger's) read back: `read_run_log` ->
RunLog. Channels, types and fields: tegrasp_drake/lcmtypes/README.md. A damaged log is read
as far as it goes (RunLog.damage says what was lost); hardware_log_replay.py re-runs the
matcher on it."""

import array
import bisect
import dataclasses
import os
import pathlib
import struct

import numpy as np
from drake import lcmt_jaco_command, lcmt_jaco_status

from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES
from tegrasp_drake.control.grasp_modes import WORDS, Mode, Transition, words_problem
from tegrasp_drake.rig.objects import object_name_problem
from tegrasp_drake.rig.ranges import check_ranges, field_range
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.rig.files import (os_error_text, REPLACEMENT_CHARACTER, DuplicateKeyError,
                                     InputTooLargeError, JsonValueError, file_problem,
                                     load_json, one_line, open_bounded, read_bounded)
from tegrasp_drake.rig.file_window import FileWindow
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.hardware.watchdog import DEFAULT_TIMEOUTS
from tegrasp_drake.hardware.device_fault import DEVICE_FAULT, DEVICES, KINDS, NO_CODE
from tegrasp_drake.hardware.device_log_messages import (
    FAULT_CHANNEL, GRIPPER_CHANNEL, RUN_INFO_CHANNEL, TACTILE_CHANNEL, TACTILE_PUBLISH_PERIOD,
    TRANSITION_CHANNEL)
from tegrasp_drake.hardware.myrio.tactile_calibration import (
    COUNT_MAX, MAX_TAXEL_GAIN_N_PER_COUNT, PIEZO_INPUT_V, PadCalibration)
from tegrasp_drake.hardware.myrio.tactile_frame import RESTART_RUN
from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL, check_jaco_command_message,
    check_jaco_status_message)
from tegrasp_drake.hardware.message_boundary import RejectedMessage
from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.runs.tactile_log_columns import VALUE_CHECK_COLUMNS, TactileColumns
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.typed_yaml import ConfigError, load_typed, parse_yaml
from tegrasp_drake.robotiq.units import BYTE_MAX
from tegrasp_drake.scenario.scenario import scenario_from_yaml
from tegrasp_drake.scenario.trial_log_file import sensor_bounds, widest_configs
from tegrasp_drake.scenario.trial_result import transition_trigger_problem
from tegrasp_drake.simulation.tactile_pads import taxel_reading_range
from tegrasp_drake.lcmtypes import (lcmt_tegrasp_fault, lcmt_tegrasp_gripper,
                                    lcmt_tegrasp_run_info, lcmt_tegrasp_tactile,
                                    lcmt_tegrasp_transition)

MESSAGE_TYPES = {
    RUN_INFO_CHANNEL: lcmt_tegrasp_run_info, TACTILE_CHANNEL: lcmt_tegrasp_tactile,
    GRIPPER_CHANNEL: lcmt_tegrasp_gripper, TRANSITION_CHANNEL: lcmt_tegrasp_transition,
    FAULT_CHANNEL: lcmt_tegrasp_fault, JACO_COMMAND_CHANNEL: lcmt_jaco_command,
    JACO_STATUS_CHANNEL: lcmt_jaco_status}


class RunLogError(ValueError):
    """A run log is missing, unreadable or lacks what the replay needs; names the file."""

    def __init__(self, message: str):
        super().__init__(one_line(message))


@dataclasses.dataclass(frozen=True)
class TactileSegment:
    """A stretch of a run's tactile stream that the matcher replays in one go: its channels
    (times in the run's Context time [s]) and the time [s] its replay starts from."""
    origin: float
    trial: TactileTrial


@dataclasses.dataclass
class RunLog:
    """What a hardware run's LCM log holds (module docstring)."""
    path: pathlib.Path
    run_info: lcmt_tegrasp_run_info | None
    tactile: dict           # TEGRASP_TACTILE's kept messages, a row each: t, device_t [s];
    #                         sa (n, 2) [N], ra (n, 2) [m/s^2]; stale, zeroing; arrival_s,
    #                         tick_s [s, host monotonic]; wall_us: reception [us]
    transitions: list       # [{t, from, to, trigger, reason}]
    faults: list            # lcmt_tegrasp_fault
    gripper: list           # lcmt_tegrasp_gripper
    arm_commands: list      # (wall utime, lcmt_jaco_command)
    arm_status: list        # (wall utime, lcmt_jaco_status)
    message_counts: dict    # channel -> messages (every channel in the file)
    damage: list = dataclasses.field(default_factory=list)  # what was lost, in words
    scenario: object = None  # the run's Scenario (logged_scenario), None if not logged
    scenario_problem: str | None = None  # why a logged scenario_yaml was not read (damage)
    tactile_timeout: float = DEFAULT_TIMEOUTS["tactile"]  # [s] the run's tactile watchdog's

    def damage_text(self) -> str:
        """One line: what was read and what was lost ("" for an intact log)."""
        if not self.damage:
            return ""
        return (f"{self.path}: damaged log: read {sum(self.message_counts.values())} "
                f"messages; " + "; ".join(self.damage)
                + ". The replay uses the messages that were read.")

    @property
    def object_name(self) -> str | None:
        """The run's object: its scenario's (run_info_message writes object_name from it;
        run_info_damage says when the two differ), else the logged object_name; None
        without a TEGRASP_RUN_INFO."""
        if self.scenario is not None:
            return self.scenario.object.name
        return self.run_info.object_name if self.run_info is not None else None

    def tactile_trial(self) -> TactileTrial:
        """The SA and RA channels the controller computed from the logged tactile ports,
        at the receiver's ticks (repeated ticks dropped)."""
        return self._channels(*self._usable_ticks())

    def tactile_segments(self) -> list[TactileSegment]:
        """tactile_trial cut at the stream's silences longer than the tactile watchdog's
        timeout (tactile_stretches), the stretches of fewer than 2 ticks left out, each
        replayed from its first tick (the first from the run's start, Context time 0, when it
        starts within the timeout of it): the replay steps through the logged ticks, never
        through a silence, so its cost follows the messages read, not the time they span."""
        t, keep = self._usable_ticks()
        segments = []
        for k, stretch in enumerate(tactile_stretches(t, self.tactile_timeout)):
            if stretch.stop - stretch.start < 2:
                continue
            origin = 0.0 if k == 0 and t[0] <= self.tactile_timeout else float(t[stretch][0])
            segments.append(TactileSegment(origin, self._channels(t[stretch], keep[stretch])))
        if not segments:
            raise self._nothing_to_replay(
                f"no 2 tactile messages within the tactile watchdog's timeout, "
                f"{number_text(self.tactile_timeout)} s, of each other to replay", len(t))
        return segments

    def _usable_ticks(self) -> tuple[np.ndarray, np.ndarray]:
        """The logged tactile ticks' times [s], repeated ones dropped, and their rows."""
        t, keep = np.unique(self.tactile["t"], return_index=True)
        if len(t) < 2:
            raise self._nothing_to_replay("fewer than 2 tactile messages to replay", len(t))
        return t, keep

    def _nothing_to_replay(self, what: str, usable: int) -> RunLogError:
        why = f": {'; '.join(self.damage)}" if self.damage else ""
        return RunLogError(f"run log '{self.path}' has {what} ({usable} usable of "
                           f"{self.message_counts.get(TACTILE_CHANNEL, 0)} on "
                           f"{TACTILE_CHANNEL})" + why)

    def _channels(self, t: np.ndarray, rows: np.ndarray) -> TactileTrial:
        """The SA and RA channels of the tactile messages `rows`, at their times `t` [s]."""
        return TactileTrial(t_sa=t, sa=self.tactile["sa"][rows], t_ra=t,
                            ra=self.tactile["ra"][rows], transition_times={})


LCM_SYNC = 0xEDA1DA01
# How an LCM log file starts: LCM's format has no file header, so its first event's sync word.
LCM_LOG_START = struct.pack(">I", LCM_SYNC)
_EVENT_HEADER = struct.Struct(">IqqII")  # sync, event number, timestamp, channel, data sizes
MAX_CHANNEL_LENGTH = 256
# The largest message LCM sends (LCM_MAX_MESSAGE_SIZE, lcm/lcm.h: 2^28 bytes); lcm-logger
# writes only messages it received, so a longer data length is a corrupt header, never a
# message: the header is skipped as corrupt bytes, not read as a message cut off at the end.
MAX_LCM_MESSAGE_BYTES = 1 << 28
MAX_EVENT_GAP = 1_000_000  # event numbers further ahead than this are damaged ones
# The largest run log a replay reads, set by what the replay holds. Reading streams (a
# FileWindow; tactile messages decoded into TactileColumns, about 0.12 kB a message at the
# peak), but the matcher's re-run does not: its TrajectorySource holds the whole tactile
# stream as a PiecewisePolynomial (about 0.9 kB a tick) and its loggers every tick's
# outputs, about 1.3 kB a tactile tick in all (python -m benchmarks.replay_memory, 800,000
# ticks: 1.28 GB of memory at the most, 0.24 GB of it the imports). A TEGRASP_TACTILE event
# is 329 bytes, so a replay holds about 4 times the log's tactile bytes. A 10-minute run
# (hardware --duration's limit) logs about 230 MB (1 kHz of tactile events, 100 Hz each of
# 306-byte arm statuses and 163-byte commands: 377 kB/s), 600,000 ticks, about 0.8 GB to
# replay; 256 MiB takes it with room, and bounds what a file can make a replay hold: about
# 1.1 GB for one of tactile messages only (816,000 ticks), about 1.5 GB for one of arm
# statuses only (decoded as messages, 1.4 kB each).
MAX_RUN_LOG_BYTES = 2**28
# The largest LCM log scan_lcm_log reads whole (its bytes and events held, not a replay).
MAX_SCANNED_LOG_BYTES = 2**30


def too_large_run_log_problem(path) -> str:
    """Why the run log at `path`, larger than MAX_RUN_LOG_BYTES, is not read, and what to do:
    replay a part of it (lcm-logfilter keeps the messages of a stretch of seconds from the
    log's first one; from 0 the part keeps the run's TEGRASP_RUN_INFO) or a shorter run."""
    try:
        size = f"is {os.stat(path).st_size} bytes, "
    except OSError:
        size = ""
    return (f"run log '{path}' {size}more than the {MAX_RUN_LOG_BYTES} bytes (256 MiB) a "
            "replay reads (a 10-minute run logs about 230 MB); replay a part of it, e.g. its first "
            f"10 minutes: lcm-logfilter -c '.*' -e 600 '{path}' part.lcmlog, or a shorter run")


def _plausible_header(data, position: int) -> bool:
    """Whether an LCM event header that fits in `data` (bytes or a FileWindow) starts at
    `position`."""
    header = data[position:position + _EVENT_HEADER.size]
    if len(header) < _EVENT_HEADER.size:
        return False
    word, _, _, channel_length, data_length = _EVENT_HEADER.unpack(header)
    if not (word == LCM_SYNC and 0 < channel_length <= MAX_CHANNEL_LENGTH
            and data_length <= MAX_LCM_MESSAGE_BYTES):
        return False  # lengths first: the channel is sliced only once it is known short
    channel = data[position + _EVENT_HEADER.size:position + _EVENT_HEADER.size + channel_length]
    return len(channel) == channel_length and all(32 < c < 127 for c in channel)


def _next_header(data, start: int) -> int:
    """Position of the first plausible event header at or after `start`, or -1."""
    sync = LCM_SYNC.to_bytes(4, "big")
    position = data.find(sync, start)
    while position >= 0 and not _plausible_header(data, position):
        position = data.find(sync, position + 1)
    return position


def _next_event_number(data, position: int) -> int | None:
    """The event number of the header at `position` (None at the end or if none is)."""
    if not _plausible_header(data, position):
        return None
    return _EVENT_HEADER.unpack(data[position:position + _EVENT_HEADER.size])[1]


# The receive times of a log (its LCM event timestamps: when lcm-logger got each message,
# [us] on the host's clock) run forward with no long silence. Measured in 11 logs of
# `tegrasp hardware` on the emulators (4-19 s runs, 2791-16059 messages): the longest gap
# 11.6 ms, the largest step back 0.16 ms (3 steps back in all).
# Steps back: the kernel stamps each datagram as it arrives on one core and queues it for
# lcm-logger, which writes in queue order; datagrams from two publishers stamped on both cores
# can swap. On a loaded host that handling moves to the softirq thread, which waits its turn
# like any thread (tens of ms beside a CPU hog), so the bound is set far beyond: 1 s, 6,400
# times the largest swap measured. Longer is no such swap but a log joined or edited.
MAX_RECEIVE_STEP_BACK_US = 1_000_000
# Gaps: once the run starts the station publishes TEGRASP_TACTILE every millisecond; before,
# while `tegrasp hardware` waits for the devices (ready_timeout, at most its range's 600 s),
# the bus may hold only the run's TEGRASP_RUN_INFO; after the run lcm-logger records for at
# most 5.1 s more (BusLogWriter.close: 0.1 s, then 5 s to exit), rounded up to 10 s. A longer
# silence is not within one run.
MAX_RECEIVE_GAP_US = round(
    (field_range(HardwareStationConfig, "ready_timeout").high + 10.0) * 1e6)
_YEAR_S = 365.25 * 86400


def _duration_text(microseconds: int) -> str:
    """A duration in words, in the largest unit it makes whole: "10.7 ms", "31.7 years"."""
    seconds = microseconds * 1e-6
    if seconds < 1.0:
        return f"{seconds * 1e3:.3g} ms"
    for unit, size in (("years", _YEAR_S), ("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


# Receive times within this of 0 [us] have steps that int64 holds exactly (corrupt bytes can
# make a timestamp anything an int64 holds: their steps are taken as Python integers).
_EXACT_STEP_BOUND_US = 2**61


def _receive_steps(timestamps) -> np.ndarray:
    """The steps [us] between consecutive receive times, exactly (int64, else objects)."""
    times = np.asarray(timestamps, dtype=np.int64)
    if len(times) and max(-int(times.min()), int(times.max())) >= _EXACT_STEP_BOUND_US:
        times = times.astype(object)
    return np.diff(times)


def receive_time_damage(timestamps) -> list[str]:
    """What is wrong with a log's receive times (the events' timestamps [us], in file order),
    in words: steps back beyond MAX_RECEIVE_STEP_BACK_US and gaps beyond MAX_RECEIVE_GAP_US,
    each said with its count and the largest one's place. The messages themselves are kept
    (their contents are checked on their own); their receive times are what is wrong."""
    steps = _receive_steps(timestamps)
    total, damage = len(timestamps), []
    for name, wrong, why in (
            ("jump forward", np.flatnonzero(steps > MAX_RECEIVE_GAP_US),
             f"longer than a run's bus is ever silent, {MAX_RECEIVE_GAP_US * 1e-6:g} s"),
            ("go back", np.flatnonzero(steps < -MAX_RECEIVE_STEP_BACK_US),
             f"lcm-logger writes messages as it receives them; two arriving together swap "
             f"by less than {_duration_text(MAX_RECEIVE_STEP_BACK_US)}")):
        if not len(wrong):
            continue
        largest = int(wrong[np.argmax(abs(steps[wrong]))])  # the first of the largest
        damage.append(
            f"the receive times (LCM event timestamps) {name} in {len(wrong)} place(s), the "
            f"largest by {_duration_text(abs(int(steps[largest])))} between messages "
            f"{largest + 1} and {largest + 2} of {total} ({why}): the log was edited or "
            "joined, or has corrupt bytes; the messages are kept, their receive times are "
            "wrong")
    return damage


def scan_lcm_log(path) -> tuple[list, list[str]]:
    """The events of an LCM log file, [(timestamp [us], channel, data)], and its damage in
    words (LcmEventScan), the file read whole (read_bounded)."""
    return _scan_lcm_bytes(read_bounded(path, MAX_SCANNED_LOG_BYTES))


def count_lcm_log_events(path) -> int:
    """How many whole events the LCM log file at `path` holds (LcmEventScan over the file
    read a window at a time: one event held at a time, whatever the log's size)."""
    stream, size = open_bounded(path, MAX_SCANNED_LOG_BYTES)
    with stream:
        return sum(1 for _ in LcmEventScan(FileWindow(stream, size)))


def _not_lcm_log_problem(data) -> str | None:
    """Why bytes (bytes or a FileWindow) that hold no LCM event are no LCM log at all, in
    words that follow "run log 'FILE' ": empty, or no event's sync word anywhere (a text
    file, an image), unlike a log whose only event is corrupt or cut off (its bytes start as
    the sync word does); or None."""
    if not len(data):
        return "is empty (0 bytes), not an LCM log"
    if data.find(LCM_LOG_START, 0) >= 0 or (len(data) < len(LCM_LOG_START)
                                            and LCM_LOG_START.startswith(data[0:len(data)])):
        return None
    return (f"is not an LCM log: its {len(data)} bytes hold no LCM event's sync word "
            f"0x{LCM_SYNC:08X}")


class LcmEventScan:
    """The events of an LCM log's bytes (bytes, or a FileWindow of its file), one at a time:
    iterating yields (timestamp [us], channel, data), and once done `damage` holds what was
    lost in words: bytes that are no events (skipped to the next header), event numbers
    missing or not following the one before, an event cut short at the end, receive times
    that cannot be one run's (receive_time_damage). LCM's format: per event a big-endian
    header (sync 0xEDA1DA01, number, timestamp, channel and data lengths), channel, data.
    lcm-logger numbers a log's events from 0, so the first one read is checked against 0 as
    each later one is against the one before: a corrupt first frame is counted as lost as
    one further on is. A length is never allocated: an event's data is a slice of the bytes,
    so the scan holds one event and the receive times (8 bytes an event) at a time."""

    def __init__(self, data):
        self.data = data
        self.damage = None

    def __iter__(self):
        data = self.data
        timestamps = array.array("q")
        channels = {}  # a channel's name as bytes -> one str for all its events
        corrupt_regions = corrupt_bytes = lost = 0
        renumbered = []  # file positions of events whose numbers go back or are damaged
        truncated = None
        position, expected_number = 0, 0
        size = len(data)
        while position < size:
            plausible = _plausible_header(data, position)
            end = None
            if plausible:
                _, number, timestamp, channel_length, data_length = _EVENT_HEADER.unpack(
                    data[position:position + _EVENT_HEADER.size])
                end = position + _EVENT_HEADER.size + channel_length + data_length
                if end > size:
                    following = _next_header(data, position + 1)
                    if following < 0:
                        truncated = (f"the last message is cut off after {size - position} "
                                     f"of its {end - position} bytes")
                        break
                    plausible = False  # a damaged length: the next event header follows
            if not plausible:
                if size - position < _EVENT_HEADER.size and not corrupt_regions:
                    truncated = f"the last {size - position} bytes are a cut-off header"
                    break
                following = _next_header(data, position + 1)
                stop = size if following < 0 else following
                corrupt_regions += 1
                corrupt_bytes += stop - position
                position = stop
                continue
            if number != expected_number:
                # the next event's number confirms this one's: a gap (messages lost) or a
                # step back (logs spliced), followed; else a damaged number, counted as the
                # next one
                confirmed = _next_event_number(data, end) in (None, number + 1)
                if confirmed and 0 < number - expected_number < MAX_EVENT_GAP:
                    lost += number - expected_number
                else:
                    renumbered.append(position)
                    if not (confirmed and number < expected_number):
                        number = expected_number
            expected_number = number + 1
            start = position + _EVENT_HEADER.size
            name = data[start:start + channel_length]
            channel = channels.get(name) or channels.setdefault(name, name.decode("ascii"))
            timestamps.append(timestamp)
            yield timestamp, channel, data[start + channel_length:end]
            position = end
        damage = []
        if corrupt_regions:
            damage.append(f"{corrupt_bytes} corrupt bytes in {corrupt_regions} place(s) skipped")
        if lost:
            damage.append(f"{lost} message(s) lost (gaps in the event numbers)")
        if renumbered:
            damage.append(
                f"{len(renumbered)} event number(s) do not follow the one before (the first "
                f"at byte {renumbered[0]}; lcm-logger numbers its events 0, 1, 2, ...: logs "
                "spliced together, or corrupt bytes); the messages are kept")
        if truncated:
            damage.append(f"truncated: {truncated}; what followed is lost")
        self.damage = damage + receive_time_damage(timestamps)


def _scan_lcm_bytes(data) -> tuple[list, list[str]]:
    """scan_lcm_log's events and damage of an LCM log's bytes, all held (LcmEventScan)."""
    scan = LcmEventScan(data)
    events = list(scan)
    return events, scan.damage


TIME_NEIGHBOURS = 5  # messages on each side whose median time a message's is compared with
MAX_TIME_OUTLIER_S = 1.0


def _in_time_order(messages: list) -> tuple[list, int]:
    """The (log time, message) pairs of the longest run of them, in log order, whose times
    never go back (by the message's utime when it has one, else the log's), byte-for-byte
    repeats of a message at its time dropped first, and how many were left out: every timed
    channel is read through it. The longest run, not "each at or after the last kept": one
    message far in the future (a forged or damaged utime) is left out alone instead of
    taking every later message with it."""
    unique, seen = [], set()
    for wall, message in messages:
        t = getattr(message, "utime", wall)
        key = (t, message.encode())
        if key not in seen:
            seen.add(key)
            unique.append((t, wall, message))
    # Longest non-decreasing subsequence: ends[k] is the index of the smallest last time of
    # a run of length k + 1 so far, before[i] the index preceding i in its run.
    end_times, ends, before = [], [], []
    for i, (t, _, _) in enumerate(unique):
        k = bisect.bisect_right(end_times, t)
        before.append(ends[k - 1] if k else -1)
        if k == len(ends):
            end_times.append(t)
            ends.append(i)
        else:
            end_times[k], ends[k] = t, i
    run, i = [], ends[-1] if ends else -1
    while i >= 0:
        run.append(i)
        i = before[i]
    kept = [unique[i][1:] for i in reversed(run)]
    return kept, len(messages) - len(kept)


def _time_order_damage(decoded: dict, channel: str) -> list[str]:
    """Puts `decoded[channel]` in time order (_in_time_order) and says what it left out."""
    decoded[channel], backwards = _in_time_order(decoded[channel])
    return ([f"{backwards} message(s) on {channel} repeat or are out of time order (a log "
             "joined to itself, a message with a forged time, or corrupt bytes); skipped"]
            if backwards else [])


def _live_refusals(messages: list, check) -> tuple[list, dict]:
    """The (log time, decoded message) pairs that `check` (the live run's boundary check
    of a decoded message, e.g. check_jaco_status_message) accepts, and the refused ones'
    counts by reason: a message the run refused on the bus (a forged or damaged status) is
    refused again, so that it never sets the replay's time order."""
    kept, refused = [], {}
    for wall, message in messages:
        try:
            check(message)
        except RejectedMessage as rejection:
            refused[rejection.reason] = refused.get(rejection.reason, 0) + 1
            continue
        kept.append((wall, message))
    return kept, refused


def _plausible(messages: list, problem_of) -> tuple[list, dict]:
    """The (log time, message) pairs for which `problem_of`(log time [us], message) is None,
    and the others' counts by what is wrong, each with the first one's words: {what: [count,
    detail]} from the (what, detail) problem_of returns."""
    kept, wrong = [], {}
    for wall, message in messages:
        found = problem_of(wall, message)
        if found:
            wrong.setdefault(found[0], [0, found[1]])[0] += 1
        else:
            kept.append((wall, message))
    return kept, wrong


def _skipped_damage(channel: str, wrong: dict) -> list[str]:
    """The damage of the messages on `channel` that _plausible (or _chained_transitions) left
    out, in words: one line per thing wrong, with its count and the first one's words."""
    return [f"{n} message(s) on {channel} {problem} (the first: {detail}; another publisher "
            "on the bus, or corrupt bytes); skipped" for problem, (n, detail) in wrong.items()]


def _run_time_problem(t: float, wall: int, span, logged_at) -> tuple[str, str] | None:
    """(what is wrong, words to add to the message's) when a message the run publishes as it
    happens (a transition, a fault) carries a Context time `t` [s] outside the run's tactile
    stream's `span` [s] (None: not checked), or more than MAX_TIME_OUTLIER_S from the run's
    time when it was logged (`logged_at`(receive time `wall` [us]) -> that Context time [s],
    from the tactile messages received around it; None: not checked), else None. The receive
    time is lcm-logger's, which no publisher sets, so a message on the bus from elsewhere must
    carry a time within a second of the run's to be taken."""
    if span is not None and not span[0] <= t <= span[1]:
        return (f"lie outside the run's tactile stream's time span, {number_text(span[0])} to "
                f"{number_text(span[1])} s", "")
    if logged_at is not None and abs(t - logged_at(wall)) > MAX_TIME_OUTLIER_S:
        return (f"carry a time more than {number_text(MAX_TIME_OUTLIER_S)} s from the run's "
                "when they were logged", f", logged at {number_text(logged_at(wall))} s")
    return None


def _plausible_transitions(messages: list, span: tuple[float, float] | None,
                           logged_at=None) -> tuple[list, dict]:
    """The (log time, lcmt_tegrasp_transition) pairs that can be the run's, and the others'
    counts by what is wrong (_plausible): no transition a controller makes (Transition's
    reader refuses it: a mode or trigger no controller has), or a time the run's is not
    (_run_time_problem). Checked before the time order, which a forged time would otherwise
    set."""
    def problem_of(wall, message):
        t = message.utime * 1e-6
        try:
            Transition.from_dict({"t": t, "from": message.from_mode, "to": message.to_mode,
                                  "trigger": message.trigger, "reason": message.reason})
        except ValueError as error:
            return "are no transition a controller makes", str(error)
        wrong = _run_time_problem(t, wall, span, logged_at)
        return wrong and (wrong[0], f"{message.from_mode} -> {message.to_mode} at "
                                    f"{number_text(t)} s{wrong[1]}")
    return _plausible(messages, problem_of)


def _fault_problem(message: lcmt_tegrasp_fault) -> str | None:
    """Why `message` is no fault the station reports (hardware_run.fault_message of a
    DeviceFault: a device and kind of device_fault's, a gFLT register byte as a device
    fault's code and none for the others, a description of WORDS, times from the run's start
    and "since" not after the report), in words, else None."""
    if message.device not in DEVICES:
        return f"device {shown(message.device)} is none of {', '.join(DEVICES)}"
    if message.kind not in KINDS:
        return f"kind {shown(message.kind)} is none of {', '.join(KINDS)}"
    if message.kind == DEVICE_FAULT and not 0 < message.code <= BYTE_MAX:
        return (f"a {DEVICE_FAULT} fault's code {message.code} is no fault code (a gFLT "
                f"register byte, 1 to {number_text(BYTE_MAX)})")
    if message.kind != DEVICE_FAULT and message.code != NO_CODE:
        return f"a {message.kind} fault's code is {NO_CODE} (none), got {message.code}"
    problem = _not_utf8_problem(message.description) or words_problem(message.description)
    if problem:
        return f"its description is not {WORDS}: {problem}"
    if message.utime < 0:
        return f"utime {message.utime} us is before the run's start (Context time 0)"
    if message.since_wall_utime < 0:
        return f"since_wall_utime {message.since_wall_utime} us is before the epoch"
    if not 0 <= message.since_utime <= message.utime:
        return (f"since {number_text(message.since_utime * 1e-6)} s is not between the run's "
                f"start and the report at {number_text(message.utime * 1e-6)} s")
    return None


def _plausible_faults(messages: list, span, logged_at) -> tuple[list, dict]:
    """The (log time, lcmt_tegrasp_fault) pairs that can be the run's, and the others' counts
    by what is wrong (_plausible): no fault the station reports (_fault_problem), or a time
    the run's is not (_run_time_problem: the run publishes a fault when it sees it, as it does
    a transition)."""
    def problem_of(wall, message):
        problem = _fault_problem(message)
        if problem:
            return "are no fault the station reports", problem
        t = message.utime * 1e-6
        wrong = _run_time_problem(t, wall, span, logged_at)
        return wrong and (wrong[0], f"{message.device} {message.kind} at {number_text(t)} s"
                                    f"{wrong[1]}")
    return _plausible(messages, problem_of)


def _gripper_problem(wall: int, message: lcmt_tegrasp_gripper) -> tuple[str, str] | None:
    """(what is wrong, the message's words) when `message` cannot be the run's
    (device_log_messages.GripperStatusSender's): a register outside the 2F-85's bytes, a
    status arrival time (host time.monotonic() [s], 0 before the first) not finite or
    negative, a negative utime (Context time); else None."""
    registers = [*message.command, *message.status]
    if not all(0 <= register <= BYTE_MAX for register in registers):
        return (f"hold registers outside the 2F-85's bytes, 0 to {number_text(BYTE_MAX)}",
                f"command {number_text(list(message.command))}, status "
                f"{number_text(list(message.status))}")
    if not (np.isfinite(message.status_arrival_s) and message.status_arrival_s >= 0):
        return ("hold a status arrival time (the host's time.monotonic()) that is not finite or "
                "negative", f"status_arrival_s {number_text(message.status_arrival_s)}")
    if message.utime < 0:
        return "carry a negative time (utime)", f"utime {message.utime} us"
    return None


def _chained_transitions(messages: list) -> tuple[list, dict]:
    """The (log time, lcmt_tegrasp_transition) pairs, in time order, each leaving the mode
    the one before entered (the timeline starts in Reach, GraspStateMachine.initial_state),
    and the others' count with the first one's words, as _plausible_transitions. One that
    follows the timeline within a second of the run's time cannot be told from the run's
    own."""
    kept, wrong, mode = [], {}, Mode.REACH.label
    for wall, message in messages:
        if message.from_mode != mode:
            wrong.setdefault("do not leave the mode the timeline is in", [0, (
                f"{shorten(message.from_mode)} -> {shorten(message.to_mode)} at "
                f"{number_text(message.utime * 1e-6)} s, in {shorten(mode)}")])[0] += 1
            continue
        kept.append((wall, message))
        mode = message.to_mode
    return kept, wrong


def taxel_force_range(scenario) -> tuple[float, float]:
    """The lowest and highest taxel force [N] a run's TEGRASP_TACTILE can hold: what the
    taxel model of `scenario` (a Scenario, the run's) reads, taxel_reading_range, as the
    trial-log reader bounds a simulated trial's taxels; for None, the widest of any
    scenario's. The messages carry newtons whatever the model's output (the tactile receiver
    calibrates the counts), so a capacitive model is taken at its calibrated output."""
    def in_newtons(config):
        return dataclasses.replace(config, capacitive=dataclasses.replace(
            config.capacitive, output="calibrated"))
    configs = [scenario.tactile] if scenario is not None else widest_configs()[0]
    ranges = [taxel_reading_range(in_newtons(config)) for config in configs]
    # On the devices the myRIO's counts are calibrated, not modelled: 0 (negative forces
    # clip) to the largest gain a calibration file may give times the AD7147's full count.
    ranges.append((0.0, MAX_TAXEL_GAIN_N_PER_COUNT * COUNT_MAX))
    return min(low for low, _ in ranges), max(high for _, high in ranges)


def pad_acceleration_bound(scenario) -> float:
    """The largest |pad acceleration| [m/s^2] a run's TEGRASP_TACTILE can hold: the full scale
    of the RA transducer of `scenario` (the run's Scenario), the bound the trial-log reader
    holds a trial's pad accelerations to (trial_log_file.sensor_bounds; for None, the widest
    of any scenario's), or the myRIO's, its piezo input's full scale at the default
    calibration's gain (PadCalibration.piezo_gain), if larger."""
    device = PadCalibration().piezo_gain * PIEZO_INPUT_V
    return max(sensor_bounds(scenario, 0.0).pad_acceleration, device)


# Rows of sliding windows whose medians are taken at once (a block's copy: 11 x 8 bytes each).
_MEDIAN_BLOCK_ROWS = 65536


def _neighbour_medians(values: np.ndarray) -> np.ndarray:
    """Each value's neighbourhood's median: of values[k - TIME_NEIGHBOURS : k +
    TIME_NEIGHBOURS + 1], cut at the ends."""
    n, reach = len(values), TIME_NEIGHBOURS
    medians = np.empty(n)
    width = 2 * reach + 1
    if n >= width:
        windows = np.lib.stride_tricks.sliding_window_view(values, width)
        for start in range(0, len(windows), _MEDIAN_BLOCK_ROWS):
            block = windows[start:start + _MEDIAN_BLOCK_ROWS]
            medians[start + reach:start + reach + len(block)] = np.median(block, axis=1)
    for k in [*range(min(reach, n)), *range(max(n - reach, min(reach, n)), n)]:
        medians[k] = np.median(values[max(0, k - reach):k + reach + 1])
    return medians


def tactile_value_check(columns: dict, taxel_range: tuple[float, float],
                        acceleration_bound: float) -> np.ndarray:
    """Which decoded TEGRASP_TACTILE messages (TactileColumns.columns) hold values that can
    be real: all finite, every taxel force within `taxel_range` [N] (taxel_force_range),
    every acceleration within `acceleration_bound` [m/s^2] (pad_acceleration_bound), 12
    taxels a pad (a message of another count is held not finite)."""
    low, high = taxel_range
    with np.errstate(invalid="ignore"):
        return (columns["finite"] & (columns["taxel_low"] >= low)
                & (columns["taxel_high"] <= high)
                & (columns["acceleration_peak"] <= acceleration_bound))


def tactile_time_check(utime: np.ndarray, wall_us: np.ndarray,
                       values_ok: np.ndarray) -> np.ndarray:
    """Which of the messages whose values are real (`values_ok`) carry a time (utime [us])
    that can be: not before the previous kept message's, and not more than
    MAX_TIME_OUTLIER_S from its neighbours' median (1 ms ticks, every decoded message
    counted) while the log's receive time (`wall_us` [us]) moved with it (a silence moves
    both clocks). A kept message's time is at least every earlier candidate's (a candidate
    left out is earlier than one kept before it), so the check needs no loop."""
    times = utime * 1e-6
    offsets = times - wall_us * 1e-6  # [s] utime - receive
    outlier = ((np.abs(times - _neighbour_medians(times)) > MAX_TIME_OUTLIER_S)
               & (np.abs(offsets - _neighbour_medians(offsets)) > MAX_TIME_OUTLIER_S))
    candidate = values_ok & ~outlier
    latest = np.maximum.accumulate(np.where(candidate, times, -np.inf))
    before = np.concatenate([[-np.inf], latest[:-1]])
    return candidate & (times >= before)


def device_time_damage(device_utimes) -> str | None:
    """What is wrong with the device times (device_utime [us], the myRIO frame timestamps the
    host unwrapped, in message order) of a log's TEGRASP_TACTILE messages, in words, else
    None. The host unwraps the myRIO's 32-bit microsecond clock (TACTILE_FRAME.md), so device
    time never goes back but where the device restarted: the decoder then follows the new
    stream once RESTART_RUN of its frames follow each other, and the device streams on. A step
    back after which the device time does not run forward through RESTART_RUN frames before
    it steps back again is no restart: frames from elsewhere, or corrupt bytes."""
    device = np.asarray(device_utimes, dtype=np.int64)
    backs = np.flatnonzero(np.diff(device) < 0) + 1
    ends = np.append(backs[1:], len(device))
    wrong = [k for k, end in zip(backs, ends)
             if end < len(device) and len(np.unique(device[k:end])) < RESTART_RUN]
    if not wrong:
        return None
    first = wrong[0]
    return (f"the device times (device_utime, the myRIO's clock) of {len(wrong)} message(s) "
            f"on {TACTILE_CHANNEL} go back (the first, message {first + 1} of {len(device)}, "
            f"by {_duration_text(int(device[first - 1] - device[first]))}) without the "
            f"{RESTART_RUN} frames running forward after it that a restarted myRIO streams: "
            "frames from elsewhere, or corrupt bytes; the messages are kept")


def _logged_text(info: lcmt_tegrasp_run_info | None, field: str):
    """(the text of TEGRASP_RUN_INFO's `field`, None); ("", None) when there is none; ("",
    what is wrong) when it is not UTF-8 (_not_utf8_problem)."""
    text = getattr(info, field) if info is not None else ""
    if not text:
        return "", None
    problem = _not_utf8_problem(text)
    return ("", problem) if problem else (text, None)


def logged_hardware_config(info: lcmt_tegrasp_run_info | None):
    """(the HardwareStationConfig of a run's TEGRASP_RUN_INFO hardware_yaml, None); (None,
    None) when it holds none; or (None, what is wrong) when the text is not one (bytes that
    are not UTF-8, or the field that does not load), as logged_scenario. Only its fields are
    read and checked against their ranges: its devices and LCM URL are the recording host's."""
    text, problem = _logged_text(info, "hardware_yaml")
    if not text:
        return None, problem
    source = "its hardware_yaml"
    try:
        data = parse_yaml(text, source)
        if not isinstance(data, dict):
            return None, f"is not a hardware config (a mapping of fields), got {shorten(text)}"
        config = load_typed(data, HardwareStationConfig, source, stored=True)
        check_ranges(config, source)
    except ConfigError as e:
        return None, f"is not a hardware config ({shorten(one_line(str(e)), 300)})"
    return config, None


def tactile_watchdog_timeout(config: HardwareStationConfig | None) -> float:
    """[s] The tactile watchdog's timeout of a run's hardware config (logged_hardware_config),
    the default for None."""
    return config.watchdog.tactile_timeout if config is not None else DEFAULT_TIMEOUTS["tactile"]


def tactile_stretches(times, timeout: float) -> list[slice]:
    """The stretches of a run's tactile stream (TEGRASP_TACTILE Context times [s], in order)
    between its silences longer than `timeout` [s] (tactile_watchdog_timeout), each a slice of
    `times`; the run's start, Context time 0, counts as the stream's first message."""
    times = np.asarray(times, dtype=float)
    cuts = (np.flatnonzero(np.diff(times) > timeout) + 1).tolist()
    bounds = [0, *cuts, len(times)]
    return [slice(start, end) for start, end in zip(bounds, bounds[1:]) if end > start]


def tactile_silence_damage(times, timeout: float) -> str | None:
    """Words for the silences of a run's tactile stream (TEGRASP_TACTILE Context times [s], in
    order) longer than `timeout` [s], the tactile watchdog's, counted from the run's start at
    Context time 0, else None. The station publishes a message every TACTILE_PUBLISH_PERIOD
    tick, stale or not, for as long as the run lasts, and its watchdog stops a run whose tactile
    data stop for `timeout`: a longer silence is messages lost or logs joined."""
    times = np.asarray(times, dtype=float)
    if not len(times):
        return None
    steps = np.diff(np.concatenate([[min(0.0, times[0])], times]))
    silent = np.flatnonzero(steps > timeout)
    if not silent.size:
        return None
    longest = silent[np.argmax(steps[silent])]
    start = times[longest - 1] if longest else 0.0
    return (f"the tactile stream (a {TACTILE_CHANNEL} message every "
            f"{_duration_text(round(TACTILE_PUBLISH_PERIOD * 1e6))}) is silent for longer than "
            f"the tactile watchdog's timeout, {number_text(timeout)} s, in {silent.size} "
            f"place(s), the longest {_duration_text(round(steps[longest] * 1e6))} from "
            f"{number_text(float(start))} s (messages lost, or logs joined: the run's watchdog "
            "stops a run that long without tactile data); the matcher is replayed on the "
            "stretches between them, not through them")


def check_run_info(info: lcmt_tegrasp_run_info, path) -> None:
    """RunLogError naming the first field of a run's TEGRASP_RUN_INFO that the replay needs
    and that holds what hardware_run.run_info_message never writes (its scenario and its
    versions are checked where they are read: damage, not a refusal)."""
    def refuse(field: str, problem: str):
        raise RunLogError(f"run log '{path}': its TEGRASP_RUN_INFO field '{field}' {problem}: "
                          "the log is damaged or was not written by `tegrasp hardware`")
    if info.controller not in CONTROLLER_NAMES:
        refuse("controller", f"names no controller of this package, got "
                             f"{shorten(repr(info.controller))} (known: "
                             f"{', '.join(CONTROLLER_NAMES)})")
    problem = object_name_problem(info.object_name)
    if problem:
        refuse("object_name", problem)


def _not_utf8_problem(text: str) -> str | None:
    """Words for decoded text that held bytes that are not UTF-8 (the generated decoder puts
    U+FFFD for them), naming the first one's byte, else None."""
    if REPLACEMENT_CHARACTER not in text:
        return None
    # the characters before the first U+FFFD decoded as they were written
    return f"is not UTF-8 at byte {len(text[:text.index(REPLACEMENT_CHARACTER)].encode())} " \
           "of its text"


def _versions_problem(info: lcmt_tegrasp_run_info) -> str | None:
    """What is wrong with a run's TEGRASP_RUN_INFO versions_json (provenance only, which the
    replay does not use), in words, else None."""
    problem = _not_utf8_problem(info.versions_json)
    if problem:
        return problem
    try:
        versions = load_json(info.versions_json)  # the package's one JSON reading
    except (DuplicateKeyError, JsonValueError) as error:  # JSON, but not text or one value
        return f"is JSON, but {error}"
    except ValueError:
        versions = None
    if not (isinstance(versions, dict)
            and all(isinstance(v, str) for v in versions.values())):
        return (f"is not a JSON object of package versions "
                f"({shorten(one_line(repr(info.versions_json)))})")
    return None


def logged_scenario(info: lcmt_tegrasp_run_info | None):
    """(the Scenario of a run's TEGRASP_RUN_INFO, None); (None, None) when it holds none; or
    (None, what is wrong) when its scenario_yaml is not a scenario: bytes that are not UTF-8
    (the generated decoder puts U+FFFD for them) named by their byte, else the field that
    does not load (ConfigError), escaped to one line."""
    text, problem = _logged_text(info, "scenario_yaml")
    if not text:
        return None, problem
    try:
        return scenario_from_yaml(text, "its scenario_yaml"), None
    except ConfigError as e:
        return None, f"is not a scenario ({shorten(one_line(str(e)), 300)})"


def run_info_damage(messages: list, scenario) -> list[str]:
    """What is wrong with a log's TEGRASP_RUN_INFO messages (in log order), in words: the
    first one's object_name or controller not its own scenario's (`scenario`, logged_scenario
    of the first; run_info_message writes both from it), and later ones that differ
    from the first (a run publishes one: two logs joined, or corrupt bytes). The replay
    uses the first, and its scenario's object."""
    first, damage = messages[0], []
    if scenario is not None and scenario.object.name != first.object_name:
        damage.append(
            f"its {RUN_INFO_CHANNEL} names the object {shorten(repr(first.object_name))} "
            f"while its own scenario's object is {shorten(repr(scenario.object.name))} (a "
            "run logs its scenario's: corrupt bytes or an edited log); the scenario's is used")
    if scenario is not None and scenario.controller.name != first.controller:
        damage.append(
            f"its {RUN_INFO_CHANNEL} names the controller {shorten(repr(first.controller))} "
            f"while its own scenario's is {shorten(repr(scenario.controller.name))} (a run "
            "logs its scenario's: corrupt bytes or an edited log); the scenario's settings "
            "are used")
    fields = [field for field in first.__slots__ if field != "utime"]
    differing = [message for message in messages[1:]
                 if any(getattr(message, f) != getattr(first, f) for f in fields)]
    if differing:
        names = sorted({f for message in differing for f in fields
                        if getattr(message, f) != getattr(first, f)})
        damage.append(
            f"{len(messages)} {RUN_INFO_CHANNEL} messages, {len(differing)} differing from the "
            f"first in {', '.join(names)} (a run publishes one: two logs joined, or corrupt "
            "bytes); the first is used")
    return damage


def unfired_trigger_damage(transitions: list, run_info) -> list[str]:
    """The damage of a run's timeline (RunLog.transitions, each one a controller makes:
    _plausible_transitions) holding a trigger its controller, the one its TEGRASP_RUN_INFO
    names, never fires (transition_trigger_problem), in words; [] without run info. Kept in
    the timeline: dropping it would break the chain of modes."""
    if run_info is None:
        return []
    problem = transition_trigger_problem(map(Transition.from_dict, transitions),
                                         run_info.controller)
    if not problem:
        return []
    return [f"its {TRANSITION_CHANNEL} timeline's {problem}, the controller its "
            f"{RUN_INFO_CHANNEL} names (another publisher on the bus, or corrupt bytes); "
            "kept in the timeline"]


def _kept_tactile(columns: dict, kept: np.ndarray) -> dict:
    """RunLog.tactile of the rows `kept` of TactileColumns.columns (and device_utime [us],
    for device_time_damage), each column cut in turn, so that the columns and their cut
    copies are never all held at once."""
    whole = bool(kept.all())
    tactile = {}
    for name in ("utime", "device_utime", "sa", "ra", "stale", "zeroing", "arrival_s",
                 "tick_s", "wall_us"):
        column = columns.pop(name)
        tactile[name] = column if whole else column[kept]
        del column
    tactile["t"] = tactile.pop("utime") * 1e-6
    tactile["device_t"] = tactile["device_utime"] * 1e-6
    return tactile


def read_run_log(path) -> RunLog:
    """Reads a hardware run's LCM log; RunLogError names the file when it is missing or
    holds no event; a damaged log is read as far as it can be (`RunLog.damage`)."""
    path = pathlib.Path(path)
    problem = file_problem(path)
    if problem == "does not exist":
        raise RunLogError(f"run log '{path}' does not exist (`tegrasp hardware --log FILE` "
                          "writes one)")
    if problem:
        raise RunLogError(f"run log '{path}' {problem} (a run "
                          "log is the file `tegrasp hardware --log FILE` writes)")
    decoded = {channel: [] for channel in MESSAGE_TYPES if channel != TACTILE_CHANNEL}
    tactile_columns = TactileColumns()
    counts, undecodable = {}, {}
    try:
        stream, size = open_bounded(path, MAX_RUN_LOG_BYTES)
    except InputTooLargeError:  # from the file's size, before a byte is read
        raise RunLogError(too_large_run_log_problem(path)) from None
    except OSError as e:
        raise RunLogError(f"run log '{path}' cannot be read: {os_error_text(e)}") from None
    with stream:
        data = FileWindow(stream, size)
        scan = LcmEventScan(data)
        try:
            for timestamp, channel, message_bytes in scan:
                counts[channel] = counts.get(channel, 0) + 1
                if channel == TACTILE_CHANNEL:
                    decodes = tactile_columns.add(timestamp, message_bytes)
                elif channel in MESSAGE_TYPES:
                    try:
                        decoded[channel].append(
                            (timestamp, MESSAGE_TYPES[channel].decode(message_bytes)))
                        decodes = True
                    except (ValueError, struct.error, UnicodeDecodeError, IndexError):
                        decodes = False
                else:
                    decodes = True
                if not decodes:
                    undecodable[channel] = undecodable.get(channel, 0) + 1
            damage = scan.damage
            not_a_log = None if counts else _not_lcm_log_problem(data)
        except OSError as e:
            raise RunLogError(f"run log '{path}' cannot be read: {os_error_text(e)}") from None
    if not_a_log:
        raise RunLogError(f"run log '{path}' {not_a_log}; give a log written by `tegrasp "
                          "hardware --log FILE` or lcm-logger")
    if not counts:
        raise RunLogError(f"run log '{path}' holds no LCM message"
                          + (f" ({'; '.join(damage)})" if damage else ""))
    damage += [f"{n} message(s) on {channel} do not decode as {MESSAGE_TYPES[channel].__name__}"
               " (corrupt bytes); skipped" for channel, n in sorted(undecodable.items())]
    for channel, check, what in ((JACO_STATUS_CHANNEL, check_jaco_status_message, "statuses"),
                                 (JACO_COMMAND_CHANNEL, check_jaco_command_message,
                                  "commands")):
        decoded[channel], refused = _live_refusals(decoded[channel], check)
        if refused:
            damage.append(
                f"{sum(refused.values())} message(s) on {channel} are {what} the live run "
                "refuses (" + ", ".join(f"{reason} {n}" for reason, n in sorted(refused.items()))
                + "; another publisher on the bus, or corrupt bytes); skipped")
    decoded[GRIPPER_CHANNEL], wrong = _plausible(decoded[GRIPPER_CHANNEL], _gripper_problem)
    damage += _skipped_damage(GRIPPER_CHANNEL, wrong)
    for channel in (GRIPPER_CHANNEL, JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL,
                    RUN_INFO_CHANNEL):
        damage += _time_order_damage(decoded, channel)
    info = decoded[RUN_INFO_CHANNEL]
    run_info = info[0][1] if info else None
    scenario = None
    scenario_problem = None
    if run_info is not None:
        check_run_info(run_info, path)
        problem = _versions_problem(run_info)
        if problem:
            damage.append(f"its {RUN_INFO_CHANNEL} field 'versions_json' {problem} (corrupt "
                          "bytes); the run's package versions are unknown")
        scenario, scenario_problem = logged_scenario(run_info)
        if scenario_problem:
            damage.append(
                f"its {RUN_INFO_CHANNEL} field 'scenario_yaml' {scenario_problem} (corrupt "
                "bytes); the run's object is its object_name, the matcher's settings the "
                "defaults (give --object to match another object's events)")
        damage += run_info_damage([message for _, message in info], scenario)
    hardware, hardware_problem = logged_hardware_config(run_info)
    if hardware_problem:
        damage.append(f"its {RUN_INFO_CHANNEL} field 'hardware_yaml' {hardware_problem} "
                      "(corrupt bytes); the tactile watchdog's default timeout is used")
    taxel_range, acceleration_bound = taxel_force_range(scenario), pad_acceleration_bound(scenario)
    columns = tactile_columns.columns()
    values_ok = tactile_value_check(columns, taxel_range, acceleration_bound)
    for name in VALUE_CHECK_COLUMNS:
        del columns[name]
    kept = tactile_time_check(columns["utime"], columns["wall_us"], values_ok)
    implausible = int(np.count_nonzero(~values_ok))
    mistimed = int(np.count_nonzero(values_ok & ~kept))
    if implausible:
        whose = "its scenario's" if scenario is not None else "any scenario's"
        damage.append(
            f"{implausible} message(s) on {TACTILE_CHANNEL} hold impossible values (not "
            f"finite, taxel forces outside {number_text(taxel_range[0])} to "
            f"{number_text(taxel_range[1])} N, what {whose} or a pad's taxels can read, "
            f"accelerations beyond {number_text(acceleration_bound)} m/s^2, the full scale of "
            f"{whose} or the myRIO's RA transducer: corrupt bytes); skipped")
    if mistimed:
        damage.append(
            f"{mistimed} message(s) on {TACTILE_CHANNEL} carry a time (utime) before the "
            f"previous message's, or more than {number_text(MAX_TIME_OUTLIER_S)} s from their "
            "neighbours' while the log's receive times did not move with it (corrupt bytes); "
            "skipped")
    tactile = _kept_tactile(columns, kept)
    tactile_timeout = tactile_watchdog_timeout(hardware)
    damage += [problem for problem in (
        device_time_damage(tactile.pop("device_utime")),
        tactile_silence_damage(tactile["t"], tactile_timeout)) if problem]
    # The transitions' Context times lie within the tactile stream's, published every tick
    # from the start of the run to its end (one tick's tolerance each side).
    span = ((tactile["t"][0] - TACTILE_PUBLISH_PERIOD, tactile["t"][-1] + TACTILE_PUBLISH_PERIOD)
            if len(tactile["t"]) else None)
    received = np.maximum.accumulate(tactile["wall_us"]) if span is not None else None
    logged_at = (None if span is None else
                 lambda wall: float(np.interp(wall, received, tactile["t"])))
    decoded[FAULT_CHANNEL], faults_wrong = _plausible_faults(decoded[FAULT_CHANNEL], span,
                                                             logged_at)
    damage += _time_order_damage(decoded, FAULT_CHANNEL)
    damage += _skipped_damage(FAULT_CHANNEL, dict(sorted(faults_wrong.items())))
    decoded[TRANSITION_CHANNEL], wrong = _plausible_transitions(decoded[TRANSITION_CHANNEL],
                                                                span, logged_at)
    damage += _time_order_damage(decoded, TRANSITION_CHANNEL)
    decoded[TRANSITION_CHANNEL], unchained = _chained_transitions(decoded[TRANSITION_CHANNEL])
    damage += _skipped_damage(TRANSITION_CHANNEL, {**dict(sorted(wrong.items())), **unchained})
    transitions = [{"t": m.utime * 1e-6, "from": m.from_mode, "to": m.to_mode,
                    "trigger": m.trigger, "reason": m.reason}
                   for _, m in decoded[TRANSITION_CHANNEL]]
    damage += unfired_trigger_damage(transitions, run_info)
    return RunLog(
        path=path, run_info=run_info, tactile=tactile, transitions=transitions,
        faults=[m for _, m in decoded[FAULT_CHANNEL]],
        gripper=[m for _, m in decoded[GRIPPER_CHANNEL]],
        arm_commands=decoded[JACO_COMMAND_CHANNEL], arm_status=decoded[JACO_STATUS_CHANNEL],
        message_counts=counts, damage=damage, scenario=scenario,
        scenario_problem=scenario_problem, tactile_timeout=tactile_timeout)
