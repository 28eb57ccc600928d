"""A reader thread for the myRIO tactile stream: serial port -> decoder -> bounded queue. The
diagram calls only `drain()`, which never blocks; when it falls behind the oldest frames are
dropped and counted; a serial error is counted and retried (a replugged adapter comes back)."""

import collections
import contextlib
import dataclasses
import threading
import time

import serial

from tegrasp_drake.hardware.message_boundary import MessageBoundary
from tegrasp_drake.hardware.myrio.tactile_frame import (
    TactileDecoderCounters, TactileFrame, TactileFrameDecoder)

DEFAULT_BAUDRATE = 921600


@dataclasses.dataclass
class TactileReaderCounters:
    """Decoder counters plus the reader's own."""
    decoder: TactileDecoderCounters
    bytes_read: int = 0
    queue_overflows: int = 0   # frames dropped because the consumer fell behind
    discarded_before_start: int = 0  # frames received before the control loop started
    serial_errors: int = 0
    last_error: str = ""


def no_valid_frame_problem(counters: TactileReaderCounters) -> str:
    """What the reader counted when no valid frame arrived, and what to check, in words."""
    decoder = counters.decoder
    if counters.bytes_read == 0:
        problem = ("not one byte arrived; is the myRIO (or `tegrasp emulate myrio` or `all`) "
                   "streaming on that port?")
    else:
        problem = (f"{counters.bytes_read} bytes arrived but none made a valid myRIO frame "
                   f"({decoder.bad_crc} with a bad CRC, {decoder.corrupt_header} with an "
                   f"unknown header, {decoder.truncated} cut short, {decoder.skipped_bytes} "
                   "bytes outside any frame); is this another device's port (the gripper's?), "
                   "or is tactile.baudrate not the myRIO's?")
    if counters.serial_errors:
        problem += (f" The port reported {counters.serial_errors} read errors (the last: "
                    f"{counters.last_error}).")
    return problem


def zeroing_problem(counters: TactileReaderCounters, zero_samples: int) -> str:
    """Why the pads were not zeroed although frames arrived, and what to check, in words."""
    return (f"the frames that arrived ({counters.decoder.summary()}) did not hold "
            f"{zero_samples} taxel count sequences per finger (frames with flags 0x01 and "
            "0x02, hardware/myrio/TACTILE_FRAME.md); does the myRIO stream send the pads' "
            "counts, or is ready_timeout shorter than they take (one per ~9.2 ms)?")


class TactileSerialReader:
    """Reads and decodes frames on a thread; `drain()` hands them over without blocking.
    `port`: a device path or pyserial URL; a context manager. Bursts are batched for
    `batch_period` [s], so the thread takes the interpreter lock a few hundred times a second."""

    def __init__(self, port: str, *, baudrate: int = DEFAULT_BAUDRATE, queue_size: int = 1024,
                 read_timeout: float = 0.005, batch_period: float = 0.002):
        self._port = port
        self._baudrate = baudrate
        self._read_timeout = read_timeout
        self._batch_period = batch_period
        self._queue = collections.deque(maxlen=queue_size)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._decoder = TactileFrameDecoder(boundary=MessageBoundary(f"tactile: {port}"))
        self._counters = TactileReaderCounters(decoder=self._decoder.counters)
        self._serial = None
        self._thread = None

    @property
    def port(self) -> str:
        return self._port

    @property
    def boundary(self) -> MessageBoundary:
        """Where the decoder counts the frames it refuses, by reason (said once each in a run)."""
        return self._decoder.boundary

    def start(self) -> "TactileSerialReader":
        """Opens the port (raises if it cannot) and starts the thread."""
        # exclusive: a flock on the port (POSIX), so a second reader (another run on the same
        # devices) cannot open it and split the frames with this one.
        self._serial = serial.serial_for_url(self._port, baudrate=self._baudrate,
                                             timeout=self._read_timeout, exclusive=True)
        self._thread = threading.Thread(target=self._run, name=f"tactile {self._port}",
                                        daemon=True)
        self._thread.start()
        return self

    def close(self, timeout: float = 1.0):
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)
        if self._serial is not None:
            self._serial.close()

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.close()

    def drain(self) -> list[TactileFrame]:
        """All frames decoded since the last call, oldest first (never blocks)."""
        with self._lock:
            frames = list(self._queue)
            self._queue.clear()
        return frames

    def discard_pending(self) -> int:
        """Drops the frames received so far (a start-up backlog) and overflows; returns how many."""
        with self._lock:
            dropped = len(self._queue) + self._counters.queue_overflows
            self._queue.clear()
            self._counters.discarded_before_start += dropped
            self._counters.queue_overflows = 0
        return dropped

    def counters(self) -> TactileReaderCounters:
        """A snapshot of the counters."""
        with self._lock:
            return dataclasses.replace(
                self._counters, decoder=dataclasses.replace(self._decoder.counters))

    def _run(self):
        while not self._stop.is_set():
            try:
                data = self._serial.read(max(1, self._serial.in_waiting))
            except (serial.SerialException, OSError) as exc:
                with self._lock:
                    self._counters.serial_errors += 1
                    self._counters.last_error = str(exc)
                self._stop.wait(0.1)
                continue
            if not data:
                continue
            arrival_time = time.monotonic()
            if self._batch_period > 0:  # let a few frames gather (see the class docstring)
                self._stop.wait(self._batch_period)
                with contextlib.suppress(serial.SerialException, OSError):
                    data += self._serial.read(self._serial.in_waiting)
            with self._lock:
                self._counters.bytes_read += len(data)
                frames = self._decoder.feed(data, arrival_time)
                overflow = max(0, len(self._queue) + len(frames) - self._queue.maxlen)
                self._counters.queue_overflows += overflow
                self._queue.extend(frames)
