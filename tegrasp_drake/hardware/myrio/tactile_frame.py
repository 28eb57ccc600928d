"""The myRIO tactile stream's binary frame: `encode_frame` and a resynchronising streaming
decoder. Layout, rates and decoding rules: hardware/myrio/TACTILE_FRAME.md. The decoder
passes on only CRC-valid frames that follow the last one, counts what it skips, follows a
restarted device after RESTART_RUN frames and unwraps device time frame by frame. Each frame
it refuses is also handed to its MessageBoundary, which says the first of each reason."""

import dataclasses
import struct
import zlib

import numpy as np

from tegrasp_drake.hardware.message_boundary import MessageBoundary

SYNC = b"\xa5\x5a"
VERSION = 1
FLAG_LEFT_COUNTS = 0x01
FLAG_RIGHT_COUNTS = 0x02
_HEADER = struct.Struct("<2sBBHIhh")   # sync, version, flags, sequence, timestamp, piezo x2
_COUNTS = struct.Struct("<12H")
_CRC = struct.Struct("<I")
HEADER_SIZE = _HEADER.size             # 14
COUNTS_SIZE = _COUNTS.size             # 24
CRC_SIZE = _CRC.size                   # 4
MIN_FRAME_SIZE = HEADER_SIZE + CRC_SIZE
MAX_FRAME_SIZE = MIN_FRAME_SIZE + 2 * COUNTS_SIZE
PIEZO_VOLTS_PER_COUNT = 10.0 / 32768.0
SEQUENCE_MODULUS = 1 << 16
TIMESTAMP_MODULUS = 1 << 32
RESTART_RUN = 8
FRAME_PERIOD_US = 1000  # one frame per millisecond
# A frame follows the last one when its timestamp advanced by its sequence gap's frame
# periods within this tolerance (the device's clock drives both).
TIME_TOLERANCE_US = 2000
TIME_TOLERANCE_FRACTION = 0.05


@dataclasses.dataclass(frozen=True)
class TactileFrame:
    """One decoded frame: u16 sequence; device timestamp [us] (unwrapped by the decoder);
    (left, right) piezo samples [counts]; 12 AD7147 counts per finger or None; arrival_time:
    host `time.monotonic()` [s] of the chunk that completed it."""
    sequence: int
    timestamp_us: int
    piezo: tuple[int, int]
    left_counts: np.ndarray | None = None
    right_counts: np.ndarray | None = None
    arrival_time: float = 0.0

    @property
    def time(self) -> float:
        """Device timestamp [s]."""
        return self.timestamp_us * 1e-6


def frame_size(flags: int) -> int:
    """Length [bytes] of a frame with these flags."""
    return (MIN_FRAME_SIZE + COUNTS_SIZE * bool(flags & FLAG_LEFT_COUNTS)
            + COUNTS_SIZE * bool(flags & FLAG_RIGHT_COUNTS))


def encode_frame(sequence: int, timestamp_us: int, piezo, left_counts=None,
                 right_counts=None) -> bytes:
    """The bytes of one frame (sequence and timestamp are wrapped to u16 and u32)."""
    flags = (FLAG_LEFT_COUNTS if left_counts is not None else 0) | (
        FLAG_RIGHT_COUNTS if right_counts is not None else 0)
    body = bytearray(_HEADER.pack(SYNC, VERSION, flags, sequence % SEQUENCE_MODULUS,
                                  timestamp_us % TIMESTAMP_MODULUS, int(piezo[0]),
                                  int(piezo[1])))
    for counts in (left_counts, right_counts):
        if counts is not None:
            body += _COUNTS.pack(*(int(c) for c in counts))
    body += _CRC.pack(zlib.crc32(body[len(SYNC):]))
    return bytes(body)


@dataclasses.dataclass
class TactileDecoderCounters:
    """What the decoder accepted and what it threw away."""
    frames: int = 0           # accepted
    bad_crc: int = 0          # full-length frame whose CRC failed
    corrupt_header: int = 0   # sync followed by an unknown version or flags
    truncated: int = 0        # cut short: another frame's sync inside it
    dropped_frames: int = 0   # sequence numbers never received
    repeated: int = 0         # sequence not newer than the last accepted (discarded)
    implausible: int = 0      # newer sequence, but its time does not fit the gap (discarded)
    restarts: int = 0         # the device restarted its sequence (accepted after a run)
    skipped_bytes: int = 0    # bytes not part of an accepted frame

    @property
    def rejected(self) -> int:
        """Frames refused, whatever the reason (REJECTION_REASONS)."""
        return sum(getattr(self, reason) for reason in REJECTION_REASONS)

    def summary(self) -> str:
        """E.g. "1110 frames, 176 rejected (implausible 176), 0 dropped, 25 restarts"."""
        reasons = ", ".join(f"{reason} {getattr(self, reason)}" for reason in REJECTION_REASONS
                            if getattr(self, reason))
        return (f"{self.frames} frames, {self.rejected} rejected"
                + (f" ({reasons})" if reasons else "")
                + f", {self.dropped_frames} dropped, {self.restarts} restarts")


# The counters of refused frames; each is also the reason a MessageBoundary counts them under.
REJECTION_REASONS = ("bad_crc", "corrupt_header", "truncated", "repeated", "implausible")


class TactileFrameDecoder:
    """Streaming decoder (see module docstring). Not thread-safe: one reader owns it."""

    def __init__(self, frame_period_us: int = FRAME_PERIOD_US,
                 boundary: MessageBoundary | None = None):
        self._buffer = bytearray()
        self._frame_period_us = frame_period_us
        self._last_sequence = None
        self._last_raw_timestamp = None
        self._device_time_us = 0
        self._candidate = None  # (sequence, raw timestamp, run) of frames held back
        self.counters = TactileDecoderCounters()
        # Told of every refused frame (reason, what was wrong): a run says the first of each.
        self.boundary = boundary or MessageBoundary("tactile")

    def feed(self, data: bytes, arrival_time: float = 0.0) -> list[TactileFrame]:
        """Adds a chunk; returns the frames it completed, in order."""
        self._buffer += data
        frames = []
        while True:
            start = self._buffer.find(SYNC)
            if start < 0:
                keep = 1 if self._buffer[-1:] == SYNC[:1] else 0
                self._skip(len(self._buffer) - keep)
                return frames
            self._skip(start)
            if len(self._buffer) < HEADER_SIZE:
                return frames
            version, flags = self._buffer[2], self._buffer[3]
            if version != VERSION or flags & ~(FLAG_LEFT_COUNTS | FLAG_RIGHT_COUNTS):
                self._reject("corrupt_header", f"version {version}, flags 0x{flags:02x}; "
                             f"this decoder reads version {VERSION}")
                self._skip(1)
                continue
            size = frame_size(flags)
            if len(self._buffer) < size:
                if self._complete_frame_follows(len(self._buffer)):
                    self._reject("truncated", "a valid frame starts inside this one")
                    self._skip(1)
                    continue
                return frames
            body = bytes(self._buffer[:size])
            if zlib.crc32(body[len(SYNC):-CRC_SIZE]) != _CRC.unpack_from(body, size - CRC_SIZE)[0]:
                if self._buffer.find(SYNC, 1, min(len(self._buffer), size + 1)) >= 0:
                    self._reject("truncated", "its CRC fails and another sync lies inside it")
                else:
                    self._reject("bad_crc", f"a {size}-byte frame whose CRC fails")
                self._skip(1)
                continue
            del self._buffer[:size]
            frame = self._accept(body, flags, arrival_time)
            if frame is not None:
                frames.append(frame)

    def _reject(self, reason: str, detail: str):
        """Counts a refused frame under `reason` (a counter of REJECTION_REASONS)."""
        setattr(self.counters, reason, getattr(self.counters, reason) + 1)
        self.boundary.reject(reason, detail)

    def _skip(self, count: int):
        if count > 0:
            self.counters.skipped_bytes += count
            del self._buffer[:count]

    def _complete_frame_follows(self, end: int) -> bool:
        """Whether a CRC-valid frame starts after the first byte and ends before `end`."""
        position = self._buffer.find(SYNC, 1, end)
        while position >= 0:
            if position + HEADER_SIZE <= end:
                size = frame_size(self._buffer[position + 3])
                body = self._buffer[position:position + size]
                if len(body) == size and zlib.crc32(body[len(SYNC):-CRC_SIZE]) == (
                        _CRC.unpack_from(body, size - CRC_SIZE)[0]):
                    return True
            position = self._buffer.find(SYNC, position + 1, end)
        return False

    def _follows(self, sequence: int, raw_timestamp: int, last_sequence: int,
                 last_raw: int) -> str:
        """How a frame relates to the one before it: "next", "old" or "implausible"."""
        gap = (sequence - last_sequence) % SEQUENCE_MODULUS
        if gap == 0 or gap > SEQUENCE_MODULUS // 2:
            return "old"
        elapsed = (raw_timestamp - last_raw) % TIMESTAMP_MODULUS  # forward, across a wrap
        expected = gap * self._frame_period_us
        if abs(elapsed - expected) <= TIME_TOLERANCE_US + TIME_TOLERANCE_FRACTION * expected:
            return "next"
        return "implausible"

    def _accept(self, body: bytes, flags: int, arrival_time: float) -> TactileFrame | None:
        _, _, _, sequence, raw_timestamp, piezo_left, piezo_right = _HEADER.unpack_from(body)
        if self._last_sequence is None:
            device_time_us = raw_timestamp
        else:
            relation = self._follows(sequence, raw_timestamp, self._last_sequence,
                                     self._last_raw_timestamp)
            if relation == "next":
                self.counters.dropped_frames += (sequence - self._last_sequence) % (
                    SEQUENCE_MODULUS) - 1
                self._candidate = None
                device_time_us = self._device_time_us + (
                    raw_timestamp - self._last_raw_timestamp) % TIMESTAMP_MODULUS
            else:
                # Held back: damaged, or the first of a restarted device's stream, followed
                # once RESTART_RUN frames in a row follow each other.
                run = 1
                if self._candidate is not None and self._follows(
                        sequence, raw_timestamp, *self._candidate[:2]) == "next":
                    run = self._candidate[2] + 1
                self._candidate = (sequence, raw_timestamp, run)
                if run < RESTART_RUN:
                    if relation == "old":
                        self._reject("repeated", f"sequence {sequence} is not newer than the "
                                     f"last passed on, {self._last_sequence}")
                    else:
                        elapsed = (raw_timestamp - self._last_raw_timestamp) % (
                            TIMESTAMP_MODULUS)
                        self._reject("implausible", f"sequence {sequence} follows "
                                     f"{self._last_sequence} but its timestamp moved "
                                     f"{elapsed} us; {RESTART_RUN} such frames in a row that "
                                     "follow each other are taken as a device restart")
                    return None
                self.counters.restarts += 1
                self.boundary.notice(
                    "restarted its sequence", f"followed again from sequence {sequence}, "
                    f"{RESTART_RUN} frames in a row; those before it were refused as implausible")
                self._candidate = None
                device_time_us = raw_timestamp  # the restarted device's own clock
        self._last_sequence = sequence
        self._last_raw_timestamp = raw_timestamp
        self._device_time_us = device_time_us
        counts, offset = [], HEADER_SIZE
        for flag in (FLAG_LEFT_COUNTS, FLAG_RIGHT_COUNTS):
            if flags & flag:
                counts.append(np.array(_COUNTS.unpack_from(body, offset), dtype=float))
                offset += COUNTS_SIZE
            else:
                counts.append(None)
        self.counters.frames += 1
        return TactileFrame(sequence, device_time_us, (piezo_left, piezo_right), counts[0],
                            counts[1], arrival_time)
