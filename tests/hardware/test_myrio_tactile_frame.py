"""The myRIO tactile frame: encoding, and a decoder that survives a damaged stream."""

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import StreamFaults, inject_faults
from tegrasp_drake.hardware.myrio.tactile_frame import (
    MAX_FRAME_SIZE, MIN_FRAME_SIZE, RESTART_RUN, TactileFrameDecoder, encode_frame)

N = 400


def make_frames(count=N, first=0):
    """Frames like the myRIO's: counts every 9th frame on the left, offset on the right."""
    rng = np.random.default_rng(1)
    frames = []
    for k in range(first, first + count):
        left = rng.integers(0, 65536, 12) if k % 9 == 0 else None
        right = rng.integers(0, 65536, 12) if k % 9 == 4 else None
        piezo = rng.integers(-32768, 32768, 2)
        frames.append(encode_frame(k, 1000 * k, piezo, left, right))
    return frames


def feed_in_chunks(decoder, data, seed=2, max_chunk=100):
    rng = np.random.default_rng(seed)
    decoded, position = [], 0
    while position < len(data):
        size = int(rng.integers(1, max_chunk))
        decoded += decoder.feed(data[position:position + size], arrival_time=position)
        position += size
    return decoded


def same_content(frame, encoded):
    """Whether a decoded frame re-encodes to exactly the bytes that were sent."""
    return encode_frame(frame.sequence, frame.timestamp_us, frame.piezo, frame.left_counts,
                        frame.right_counts) == encoded


def test_frame_sizes():
    assert len(encode_frame(0, 0, (0, 0))) == MIN_FRAME_SIZE == 18
    assert len(encode_frame(0, 0, (0, 0), [0] * 12, [0] * 12)) == MAX_FRAME_SIZE == 66


def test_round_trip_keeps_every_field():
    encoded = encode_frame(7, 123456, (-5, 300), np.arange(12), None)
    (frame,) = TactileFrameDecoder().feed(encoded, arrival_time=1.5)
    assert (frame.sequence, frame.timestamp_us, frame.piezo) == (7, 123456, (-5, 300))
    np.testing.assert_array_equal(frame.left_counts, np.arange(12))
    assert frame.right_counts is None and frame.arrival_time == 1.5
    assert frame.time == pytest.approx(0.123456)


def test_arbitrary_chunking_loses_nothing():
    frames = make_frames()
    decoder = TactileFrameDecoder()
    decoded = feed_in_chunks(decoder, b"".join(frames))
    assert [f.sequence for f in decoded] == list(range(N))
    assert all(same_content(f, e) for f, e in zip(decoded, frames))
    assert decoder.counters.rejected == decoder.counters.skipped_bytes == 0


@pytest.mark.parametrize("fault", ["bit_flip", "dropped_byte", "truncated"])
def test_damaged_frames_are_counted_and_skipped_and_the_rest_survive(fault):
    frames = make_frames()
    rng = np.random.default_rng(3)
    faults = StreamFaults(**{fault: 0.1})
    damaged, stream = set(), bytearray(frames[0])
    for k, frame in enumerate(frames[1:-1], start=1):  # clean ends bound every gap
        data, injected = inject_faults(frame, faults, rng)
        if injected:
            damaged.add(k)
        stream += data
    stream += frames[-1]
    decoder = TactileFrameDecoder()
    decoded = feed_in_chunks(decoder, bytes(stream))
    assert len(damaged) > 20
    assert [f.sequence for f in decoded] == [k for k in range(N) if k not in damaged]
    assert all(same_content(f, frames[f.sequence]) for f in decoded)
    c = decoder.counters
    assert c.frames + c.dropped_frames == N
    assert c.rejected > 0
    if fault == "truncated":
        assert c.truncated > 0
    if fault == "bit_flip":
        assert c.bad_crc + c.corrupt_header > 0


def test_garbage_between_frames_is_skipped():
    frames = make_frames(50)
    rng = np.random.default_rng(4)
    noisy = b"".join(rng.bytes(int(rng.integers(0, 20))) + frame for frame in frames)
    decoder = TactileFrameDecoder()
    decoded = feed_in_chunks(decoder, noisy)
    assert [f.sequence for f in decoded] == list(range(50))
    assert decoder.counters.skipped_bytes > 0


def test_a_sequence_gap_counts_dropped_frames():
    frames = make_frames(20)
    decoder = TactileFrameDecoder()
    decoder.feed(b"".join(frames[:5] + frames[8:]))
    assert decoder.counters.dropped_frames == 3
    assert decoder.counters.frames == 17


def test_a_repeated_frame_is_not_passed_on_again():
    frames = make_frames(5)
    decoder = TactileFrameDecoder()
    decoded = decoder.feed(b"".join(frames[:4] + [frames[2], frames[4]]))
    assert [f.sequence for f in decoded] == [0, 1, 2, 3, 4]
    assert decoder.counters.repeated == 1


def test_a_restarted_device_is_followed_after_a_run_of_frames():
    decoder = TactileFrameDecoder()
    decoder.feed(b"".join(make_frames(100)))
    decoded = decoder.feed(b"".join(make_frames(RESTART_RUN + 2)))
    assert [f.sequence for f in decoded] == [RESTART_RUN - 1, RESTART_RUN, RESTART_RUN + 1]
    assert decoder.counters.restarts == 1
    (notice,) = decoder.boundary.new_notices()  # said live (RunReporter prints it)
    assert "restarted its sequence" in notice and f"sequence {RESTART_RUN - 1}" in notice
    assert decoder.boundary.new_notices() == []


def test_restarts_between_two_looks_are_said_once_with_their_count():
    decoder = TactileFrameDecoder()
    decoder.feed(b"".join(make_frames(100)))
    for _ in range(3):
        decoder.feed(b"".join(make_frames(RESTART_RUN + 2)))
    assert decoder.counters.restarts == 3
    (notice,) = decoder.boundary.new_notices()
    assert notice.endswith("3 times since the last report") and "\n" not in notice


def test_timestamps_are_unwrapped():
    near_wrap = (1 << 32) - 1500
    data = b"".join(encode_frame(k, near_wrap + 1000 * k, (0, 0)) for k in range(4))
    decoded = TactileFrameDecoder().feed(data)
    assert np.all(np.diff([f.timestamp_us for f in decoded]) == 1000)


def _with_outlier(outlier: bytes, at: int = 10, count: int = 30) -> tuple[list, list]:
    frames = make_frames(count)
    return frames, frames[:at] + [outlier] + frames[at:]


@pytest.mark.parametrize("sequence, timestamp_us", [
    (30000, 10_500),             # sequence 30000 in a stream at 10: a jump, not a wrap
    (10, (1 << 32) - 20),        # a timestamp near 2^32: not a wrap
    (10, 2_000),                 # a timestamp going backwards
    (11, 900_000),               # the next sequence, but 0.9 s later
])
def test_a_valid_frame_with_absurd_content_is_discarded_and_shifts_nothing(sequence,
                                                                           timestamp_us):
    frames, stream = _with_outlier(encode_frame(sequence, timestamp_us, (7, 7)))
    decoder = TactileFrameDecoder()
    decoded = decoder.feed(b"".join(stream))
    assert [f.sequence for f in decoded] == list(range(len(frames)))
    assert [f.timestamp_us for f in decoded] == [1000 * k for k in range(len(frames))]
    assert decoder.counters.dropped_frames == 0
    assert decoder.counters.implausible + decoder.counters.repeated == 1
    assert decoder.counters.restarts == 0


def test_a_stream_resuming_after_a_silence_is_followed_at_once():
    frames = make_frames(3000)
    decoder = TactileFrameDecoder()
    decoded = decoder.feed(b"".join(frames[:100] + frames[2100:2110]))
    assert [f.sequence for f in decoded] == list(range(100)) + list(range(2100, 2110))
    assert decoder.counters.dropped_frames == 2000
    assert decoder.counters.implausible == 0


def test_a_wrap_of_the_sequence_and_the_timestamp_together_is_continuous():
    start_k = (1 << 16) - 5
    base = (1 << 32) - 5000
    data = b"".join(encode_frame(k, base + 1000 * (k - start_k), (0, 0))
                    for k in range(start_k, start_k + 12))
    decoded = TactileFrameDecoder().feed(data)
    assert len(decoded) == 12
    assert np.all(np.diff([f.timestamp_us for f in decoded]) == 1000)
