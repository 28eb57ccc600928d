"""An emulated myRIO streaming tactile frames on a pseudo-terminal, at the real rate.

It replays a TactileRecording: frame k carries the film's acceleration at its time (through
the inverse calibration) and, when a finger's AD7147 completes a sequence, its 12 counts.
Frames follow the stream's own clock or a given `trial_clock`; a ControllerClock gone idle
(the arm commands stopped) leaves the stream at the real rate holding the replay's last
sample, as a myRIO streams whatever the arm does, and its next run restarts the replay from
the beginning. With a `gripper_request` the replay holds at each recorded grip or release
until the emulated gripper is commanded alike (docs/hardware.md, "The commands"). Faults are
drawn per frame from a seeded generator; a full pty buffer drops frames (counted) and never
blocks."""

import collections
import dataclasses
import os
import threading
import time
import zipfile
import zlib

import numpy as np

from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.rig.files import is_read_failure, one_line, read_error_remedy, os_error_text
from tegrasp_drake.rig.npz_headers import (MAX_TRIAL_LOG_BYTES, DamagedNpzError,
                                           DeclaredArraysError, NotAnNpzError,
                                           NpzHeaderError, checked_npz_arrays)
from tegrasp_drake.hardware.myrio.tactile_calibration import (
    TactileCalibration, counts_from_forces, piezo_from_acceleration)
from tegrasp_drake.hardware.myrio.tactile_frame import encode_frame
from tegrasp_drake.scenario.trial_log_file import (ARRAY_FIELDS, TrialLogError,
                                                   check_trial_log_file,
                                                   declared_arrays_problem,
                                                   holds_this_versions_metadata, load_trial_log,
                                                   trial_arrays_problem, trial_log_npz_refusal)
from tegrasp_drake.emulators.null_modem import open_raw_pty

MAX_SENT_RECORDS = 200_000  # `sent()` keeps the newest frames only (200 s at 1 kHz)


@dataclasses.dataclass
class TactileRecording:
    """The raw pad signals of a recorded trial: times [s] ascending; forces (n, 12) [N];
    accelerations (m,) or (m, 3) [m/s^2]; optionally the gripper's rPR requests at their times."""
    force_times: np.ndarray
    left_forces: np.ndarray
    right_forces: np.ndarray
    acceleration_times: np.ndarray
    left_acceleration: np.ndarray
    right_acceleration: np.ndarray
    gripper_times: np.ndarray | None = None
    gripper_requests: np.ndarray | None = None

    @property
    def duration(self) -> float:
        return float(max(self.force_times[-1], self.acceleration_times[-1]))


class TactileRecordingError(ValueError):
    """A file is not a trial log holding the pad signals; the message names it."""

    def __init__(self, message: str):
        super().__init__(one_line(message))


# The arrays of a bare recording (save_tactile_recording): a trial log's pad signals and
# gripper commands, and no metadata.
RECORDING_ARRAYS = ("t_sa", "taxels", "t_ra", "pad_acceleration")
RECORDING_OPTIONAL_ARRAYS = ("t_slow", "gripper_command")


def load_tactile_recording(path, *, bare: bool = True) -> TactileRecording:
    """The pad signals of a TrialLog .npz (left then right) and the gripper's position
    requests when present, the log read whole (load_trial_log: its checksum among the rest).
    A bare recording (what save_tactile_recording writes: RECORDING_ARRAYS and
    RECORDING_OPTIONAL_ARRAYS, no metadata) is checked alike when `bare` (refused otherwise:
    `tegrasp emulate --trial` replays trial logs); a file holding more of a trial log's arrays
    but no metadata, a trial log stripped of its metadata and checksum, never is."""
    wanted = RECORDING_ARRAYS
    try:
        check_trial_log_file(path)
    except TrialLogError as e:
        raise TactileRecordingError(str(e)) from None
    try:
        arrays = checked_npz_arrays(path, wanted, optional=(
            "meta", "channels", "t_slow", "gripper_command"), max_bytes=MAX_TRIAL_LOG_BYTES,
            text=("meta",), known=("meta", *ARRAY_FIELDS), kind="a trial log",
            declared_problem=declared_arrays_problem)
    except NpzHeaderError as e:
        if isinstance(e, (NotAnNpzError, DamagedNpzError, DeclaredArraysError)) or (
                "lacks the arrays" in str(e) and holds_this_versions_metadata(path)):
            raise TactileRecordingError(trial_log_npz_refusal(path, e)) from None
        raise TactileRecordingError(f"'{path}' is not a trial log with t_sa, taxels, t_ra "
                                    f"and pad_acceleration: {e}") from None
    except (OSError, KeyError, ValueError, EOFError, zipfile.BadZipFile, zlib.error) as e:
        if is_read_failure(e):  # the disk's error, not the file's: no word of damage
            raise TactileRecordingError(f"'{path}' cannot be read ({os_error_text(e)}); "
                                        f"{read_error_remedy(e)}") from None
        raise TactileRecordingError(f"'{path}' is not a trial log with t_sa, taxels, t_ra "
                                    f"and pad_acceleration (or it is truncated or corrupt): "
                                    f"{type(e).__name__}: {e}") from None
    if "meta" in arrays:
        try:
            log = load_trial_log(path)
        except TrialLogError as e:
            raise TactileRecordingError(str(e)) from None
        arrays = {name: getattr(log, name) for name in (*wanted, *RECORDING_OPTIONAL_ARRAYS)}
    else:
        _refuse_bare_recording(path, bare)
    t_sa, taxels = arrays["t_sa"], arrays["taxels"]
    t_ra, acceleration = arrays["t_ra"], arrays["pad_acceleration"]
    problem = trial_arrays_problem(arrays)
    if problem:
        raise TactileRecordingError(f"'{path}': {problem}; it cannot be streamed (run the "
                                    "trial again to remake it)")
    gripper_times, gripper_requests = _gripper_requests(path, arrays)
    return TactileRecording(t_sa, taxels[:, :TAXELS_PER_PAD], taxels[:, TAXELS_PER_PAD:],
                            t_ra, acceleration[:, :3], acceleration[:, 3:],
                            gripper_times, gripper_requests)


def _refuse_bare_recording(path, bare: bool) -> None:
    """TactileRecordingError naming `path`, a file holding no trial metadata, unless it is a
    bare recording (only RECORDING_ARRAYS and RECORDING_OPTIONAL_ARRAYS) and `bare` allows
    one: a trial log's other arrays without its metadata are a log whose checksum was
    removed with it, so what it holds cannot be told from an edit."""
    with zipfile.ZipFile(path) as archive:  # its directory bounded by checked_npz_arrays
        members = [name.removesuffix(".npy") for name in archive.namelist()]
    log_only = [name for name in ARRAY_FIELDS if name in members
                and name not in (*RECORDING_ARRAYS, *RECORDING_OPTIONAL_ARRAYS)]
    if log_only:
        raise TactileRecordingError(
            f"'{path}' holds a trial log's arrays ({', '.join(log_only)}) but not its metadata "
            "('meta', with the checksum that shows the log is as its trial wrote it); give "
            "the trial.npz as `tegrasp trial` wrote it, or run the trial again")
    if not bare:
        raise TactileRecordingError(
            f"'{path}' holds no trial metadata ('meta'), so it is not a trial log; give a "
            "trial.npz that `tegrasp trial --out DIR` (DIR/trial.npz) or `tegrasp demo` "
            "(out/demo/trial.npz) wrote")


def _gripper_requests(path, arrays) -> tuple:
    """(t_slow, gripper_command's rPR column) of a trial log's arrays, or (None, None)."""
    if "t_slow" not in arrays or "gripper_command" not in arrays:
        return None, None
    times, command = arrays["t_slow"], arrays["gripper_command"]
    if (times.ndim != 1 or len(times) < 1 or command.ndim != 2 or command.shape[0] != len(times)
            or command.shape[1] < 1 or not np.all(np.isfinite(times))
            or not np.all(np.isfinite(command)) or np.any(np.diff(times) <= 0)):
        raise TactileRecordingError(
            f"'{path}': t_slow and gripper_command must be increasing finite times and as "
            f"many rows of finite gripper commands (got {times.shape} and {command.shape}); "
            "remake the trial log")
    return times, command[:, 0]


def save_tactile_recording(path, recording: TactileRecording):
    """Writes what `load_tactile_recording` reads (a one-axis acceleration as x); returns `path`."""
    def three_axes(acceleration):
        acceleration = np.asarray(acceleration, dtype=float)
        if acceleration.ndim == 2:
            return acceleration
        return np.column_stack([acceleration, np.zeros((len(acceleration), 2))])
    gripper = {}
    if recording.gripper_times is not None:  # rPR, with rSP and rFR zero
        requests = np.asarray(recording.gripper_requests, dtype=float)
        gripper = dict(t_slow=recording.gripper_times, gripper_command=np.column_stack(
            [requests, np.zeros((len(requests), 2))]))
    np.savez(path, t_sa=recording.force_times,
             taxels=np.hstack([recording.left_forces, recording.right_forces]),
             t_ra=recording.acceleration_times,
             pad_acceleration=np.hstack([three_axes(recording.left_acceleration),
                                         three_axes(recording.right_acceleration)]),
             **gripper)
    return path


@dataclasses.dataclass
class StreamFaults:
    """Per-frame probabilities of each injected fault, and the generator's seed."""
    bit_flip: float = 0.0
    dropped_byte: float = 0.0
    truncated: float = 0.0
    seed: int = 0


@dataclasses.dataclass
class MyRioEmulatorConfig:
    """Stream timing [s], the calibration to invert, faults."""
    frame_period: float = 1e-3  # one frame per ms (hardware/myrio/TACTILE_FRAME.md)
    cdc_period: float = 9.2e-3  # AD7147: 12 stages at decimation 64 (TACTILE_FRAME.md)
    lead_in: float = 0.5  # longer than zeroing's 32 sequences (0.3 s)
    piezo_axis: int | None = None
    start_on_trigger: bool = False
    hold_at_end: bool = False
    calibration: TactileCalibration = dataclasses.field(default_factory=TactileCalibration)
    faults: StreamFaults = dataclasses.field(default_factory=StreamFaults)


@dataclasses.dataclass(frozen=True)
class GripperCommandChange:
    """A change of the recorded position request from `before` to `after` [rPR bytes], made after
    `hold_time` [s] (the last time the old request was logged)."""
    hold_time: float
    before: int
    after: int


def gripper_command_changes(times, requests) -> list[GripperCommandChange]:
    """Each change of the recorded position requests (none for None)."""
    if times is None:
        return []
    requests = np.asarray(requests)
    return [GripperCommandChange(float(times[i - 1]), int(requests[i - 1]), int(requests[i]))
            for i in np.flatnonzero(np.diff(requests) != 0) + 1]


def gripper_followed(change: GripperCommandChange, request: int | None) -> bool:
    """Whether the gripper's request [byte] is nearer the new request than the old."""
    return request is not None and abs(request - change.after) < abs(request - change.before)


def held_sample(times, values, t):
    """values at the last time <= t (the first value before the first time)."""
    index = np.searchsorted(times, t, side="right") - 1
    return values[max(index, 0)]


def film_signal(acceleration, piezo_axis):
    """The film's one-axis reading of an (m,) or (m, 3) acceleration array."""
    acceleration = np.asarray(acceleration, dtype=float)
    if acceleration.ndim == 1:
        return acceleration
    if piezo_axis is None:
        return np.linalg.norm(acceleration, axis=1)
    return acceleration[:, piezo_axis]


def cdc_completes(k: int, frame_period: float, cdc_period: float, phase: float) -> bool:
    """Whether a CDC sequence with this phase completes within frame k's period."""
    def completed(t):
        return np.floor((t - phase) / cdc_period)
    return completed(k * frame_period) > completed((k - 1) * frame_period)


def inject_faults(frame: bytes, faults: StreamFaults, rng) -> tuple[bytes, list[str]]:
    """The frame after the faults drawn for it, and their names."""
    data, injected = bytearray(frame), []
    if rng.random() < faults.bit_flip:
        data[rng.integers(len(data))] ^= 1 << int(rng.integers(8))
        injected.append("bit_flip")
    if rng.random() < faults.dropped_byte:
        del data[rng.integers(len(data))]
        injected.append("dropped_byte")
    if rng.random() < faults.truncated:
        del data[rng.integers(1, len(data)):]
        injected.append("truncated")
    return bytes(data), injected


class TactileFrameSource:
    """Builds frame k of a trial (module docstring); pure apart from the fault generator."""

    def __init__(self, trial: TactileRecording, config: MyRioEmulatorConfig):
        self._trial = trial
        self._config = config
        self._film = [film_signal(trial.left_acceleration, config.piezo_axis),
                      film_signal(trial.right_acceleration, config.piezo_axis)]
        self._forces = [np.asarray(trial.left_forces, dtype=float),
                        np.asarray(trial.right_forces, dtype=float)]
        self.gripper_changes = gripper_command_changes(trial.gripper_times,
                                                       trial.gripper_requests)
        self.lead_in_frames = int(round(config.lead_in / config.frame_period))
        self.trial_frames = int(np.ceil(trial.duration / config.frame_period))
        self.frame_count = self.lead_in_frames + self.trial_frames

    def frame(self, k: int, trial_start_frame: int | None = -1) -> bytes:
        """Frame k of the stream whose trial time 0 is frame `trial_start_frame` (-1: after
        the lead-in; None: not started, a quiet frame)."""
        c = self._config
        if trial_start_frame == -1:
            trial_start_frame = self.lead_in_frames
        t = -1.0 if trial_start_frame is None else (k - trial_start_frame) * c.frame_period
        return self.frame_at(k, t)

    def frame_at(self, k: int, t: float) -> bytes:
        """Frame k of the stream carrying the trial at time t [s] (t < 0: quiet)."""
        c = self._config
        piezo, counts = [], []
        for i, pad in enumerate(c.calibration.pads()):
            acceleration = held_sample(self._trial.acceleration_times, self._film[i], t) \
                if t >= 0 else 0.0
            piezo.append(piezo_from_acceleration(
                acceleration, c.calibration.piezo_volts_per_count, pad.piezo_gain,
                pad.piezo_offset))
            if cdc_completes(k, c.frame_period, c.cdc_period, i * c.cdc_period / 2):
                forces = held_sample(self._trial.force_times, self._forces[i], t) \
                    if t >= 0 else np.zeros(self._forces[i].shape[1])
                counts.append(counts_from_forces(forces, pad.gain, pad.offset))
            else:
                counts.append(None)
        timestamp_us = int(round(k * c.frame_period * 1e6))
        return encode_frame(k, timestamp_us, piezo, counts[0], counts[1])


@dataclasses.dataclass(frozen=True)
class SentFrame:
    """A frame written to the port."""
    sequence: int
    timestamp_us: int
    write_time: float     # time.monotonic() [s] after the write returned
    faults: tuple = ()    # names of the faults injected into it
    trial_time: float = -1.0  # [s] the recording's time it carried (< 0: a quiet frame)


@dataclasses.dataclass
class MyRioEmulatorCounters:
    frames_sent: int = 0
    faulted_frames: int = 0   # frames sent with at least one injected fault
    tx_overruns: int = 0   # frames not written because the pty buffer was full
    held_frames: int = 0   # frames that held the replay until the gripper followed
    restarts: int = 0   # replays restarted from the beginning by a new run's arm commands
    injected: dict = dataclasses.field(default_factory=lambda: collections.Counter())


class MyRioEmulator:
    """Streams a trial on a pseudo-terminal; the reader opens `port`. Use with `with`."""

    def __init__(self, trial: TactileRecording, config: MyRioEmulatorConfig | None = None, *,
                 trial_clock=None, gripper_request=None):
        self._config = dataclasses.replace(config or MyRioEmulatorConfig())
        self._trial_clock = trial_clock
        self._gripper_request = gripper_request
        self._source = TactileFrameSource(trial, self._config)
        self._rng = np.random.default_rng(self._config.faults.seed)
        self._master, self._slave, self._port = open_raw_pty()
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._talking = threading.Event()
        self._talking.set()
        self._trigger = threading.Event()
        self._trial_start_time = None
        self._finished = threading.Event()
        self._counters = MyRioEmulatorCounters()
        self._sent = collections.deque(maxlen=MAX_SENT_RECORDS)
        self._thread = None

    @property
    def port(self) -> str:
        return self._port

    @property
    def frame_count(self) -> int:
        return self._source.frame_count

    def start(self) -> "MyRioEmulator":
        self._thread = threading.Thread(target=self._run, name="myrio emulator", daemon=True)
        self._thread.start()
        return self

    def stop(self, timeout: float = 2.0):
        self._stop.set()
        self._talking.set()
        if self._thread is not None:
            self._thread.join(timeout)
        if self._master >= 0:
            os.close(self._master)
            os.close(self._slave)
            self._master = self._slave = -1

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()

    def stop_talking(self):
        self._talking.clear()

    def resume_talking(self):
        self._talking.set()

    def start_trial(self):
        """With `start_on_trigger`: the trial starts with the next frame."""
        self._trigger.set()

    @property
    def trial_start_time(self) -> float | None:
        """time.monotonic() [s] when the trial's first frame was due (None before)."""
        with self._lock:
            return self._trial_start_time

    def wait_until_finished(self, timeout: float) -> bool:
        return self._finished.wait(timeout)

    def counters(self) -> MyRioEmulatorCounters:
        with self._lock:
            return dataclasses.replace(self._counters,
                                       injected=collections.Counter(self._counters.injected))

    def sent(self) -> list[SentFrame]:
        """Every frame written so far, oldest first."""
        with self._lock:
            return list(self._sent)

    def _run(self):
        period = self._config.frame_period
        start = time.monotonic()
        trial_start = None if self._config.start_on_trigger else self._source.lead_in_frames
        changes = self._source.gripper_changes if self._gripper_request is not None else []
        next_change = 0  # the first of `changes` the gripper has not followed yet
        held = 0  # frames by which the trial runs behind the stream (gripper, idle clock)
        offset = 0  # frames streamed while the clock was idle: the clock's pacing shifts on
        run = getattr(self._trial_clock, "run", 0)  # the controller run the replay follows
        last_write = start
        k = 0
        while not self._stop.is_set():
            if trial_start is None and self._trigger.is_set():
                trial_start = k
            if trial_start is not None:
                if self._trial_start_time is None:
                    with self._lock:  # a clock-paced trial starts at once
                        self._trial_start_time = (
                            time.monotonic() if self._trial_clock is not None
                            else start + trial_start * period)
                if (not self._config.hold_at_end
                        and k - held >= trial_start + self._source.trial_frames):
                    break
            if self._trial_clock is not None and trial_start is not None:
                if getattr(self._trial_clock, "run", 0) != run:
                    # A new run's commands: its replay starts from the beginning, now.
                    run, trial_start, held, offset, next_change = (
                        self._trial_clock.run, k, 0, 0, 0)
                    with self._lock:
                        self._trial_start_time = time.monotonic()
                        self._counters.restarts += 1
                idle = getattr(self._trial_clock, "idle", None)
                # Paced by the clock: trial sample n goes out once the clock reached it.
                due = trial_start + offset + int(self._trial_clock() / period + 1e-9)
                if k > due and idle is not None and idle():
                    # The arm commands stopped: stream on at the real rate, holding the
                    # sample the replay reached (the frames shift the clock's pacing on).
                    delay = last_write + period - time.monotonic()
                    if delay > 0:
                        time.sleep(delay)
                    held, offset = held + 1, offset + 1
                elif k > due:
                    time.sleep(period / 4)
                    continue
                if not self._talking.is_set():
                    self._talking.wait(0.05)
                    k = trial_start + offset + int(self._trial_clock() / period)  # not sent
                    continue
            else:
                delay = start + k * period - time.monotonic()
                if delay > 0:
                    time.sleep(delay)
                if not self._talking.is_set():
                    self._talking.wait(0.05)
                    k = int((time.monotonic() - start) / period)  # silent frames are not sent
                    continue
            holding = False
            if trial_start is None:
                t = -1.0
            else:
                n = k - trial_start - held  # the trial sample due
                while next_change < len(changes):
                    last_before = int(np.floor(changes[next_change].hold_time / period + 1e-9))
                    if n <= last_before:
                        break
                    if not gripper_followed(changes[next_change], self._gripper_request()):
                        held, n, holding = held + n - last_before, last_before, True
                        break
                    next_change += 1
                t = n * period
            frame = self._source.frame_at(k, t)
            data, injected = inject_faults(frame, self._config.faults, self._rng)
            try:
                written = os.write(self._master, data)
            except BlockingIOError:
                written = 0
            last_write = time.monotonic()
            with self._lock:
                self._counters.held_frames += holding
                if written:
                    self._counters.frames_sent += 1
                    self._sent.append(SentFrame(k, int(round(k * period * 1e6)),
                                                time.monotonic(), tuple(injected), t))
                    self._counters.injected.update(injected)
                    self._counters.faulted_frames += bool(injected)
                else:
                    self._counters.tx_overruns += 1
            k += 1
        self._finished.set()
