"""The myRIO's clock against the host's (hardware/myrio/device_clock.py): a stream whose
frames arrive faster than the device's 1000 a second is a fault; a late or bursty host is
not. The check on made-up times first, then through the pty, reader and receiver."""

import os
import threading
import time

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator

from tegrasp_drake.emulators.myrio_emulator import MyRioEmulator, TactileRecording
from tegrasp_drake.emulators.null_modem import open_raw_pty
from tegrasp_drake.hardware.device_fault import IMPLAUSIBLE
from tegrasp_drake.hardware.myrio.device_clock import (
    DeviceClock, device_clock_after_frames, implausible_clock_description)
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_frame import TactileFrame, encode_frame
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver

pytestmark = pytest.mark.real_time  # conftest: the pty tests run at real-time scheduling


def frames(arrival_times, first_sequence=0, first_time_us=0):
    """Frames one device millisecond apart, arriving at these host times [s]."""
    return [TactileFrame(first_sequence + k, first_time_us + 1000 * k, (0, 0),
                         arrival_time=float(t)) for k, t in enumerate(arrival_times)]


def check(stream, chunk=7):
    """The check after the stream, handed over `chunk` frames at a time (as ticks drain)."""
    clock = DeviceClock()
    for start in range(0, len(stream), chunk):
        clock = device_clock_after_frames(clock, stream[start:start + chunk])
    return clock


def test_a_stream_at_its_own_rate_keeps_to_the_host():
    clock = check(frames(100.0 + 1e-3 * np.arange(5000)))
    assert not clock.implausible
    assert abs(clock.lead) < 1e-6


def test_a_late_and_bursty_host_is_never_a_fault():
    """Frames read in bursts (up to 300 ms late, then all at once) and a 5 s stall of the
    host: the device's time falls behind the host's, never ahead."""
    rng = np.random.default_rng(3)
    sent = 1e-3 * np.arange(20000)
    late = rng.uniform(0.0, 0.3, size=len(sent) // 100).repeat(100)  # 100-frame bursts
    arrivals = np.maximum.accumulate(sent + late)  # read in order, each burst at once
    arrivals[8000:] += 5.0                         # the host stalled 5 s
    clock = check(frames(arrivals))
    assert not clock.implausible
    assert clock.lead <= 0.3


def test_the_allowance_is_one_second_of_device_time_ahead():
    """After a second read promptly, 900 ms of frames read at one instant are a burst the
    allowance takes; 1.1 s of them are not."""
    prompt = list(1e-3 * np.arange(1000))
    assert not check(frames(prompt + [1.0] * 900)).implausible
    clock = check(frames(prompt + [1.0] * 1100))
    assert clock.implausible
    assert 1.0 < clock.lead < 1.01  # the first frame past the allowance


def test_a_backlog_drained_after_a_stall_is_never_a_fault():
    """The host stalls 3 s, then drains the 3000 frames that waited in 4 kB reads (about 180
    frames each, microseconds apart) and reads promptly again: each frame of the backlog
    was late, none ahead. Taking a backlog frame as reference would make the prompt frames
    after it look 3 s ahead."""
    before = 1e-3 * np.arange(1000)
    backlog = 4.0 + 1e-6 * (np.arange(3000) // 180)
    after = 4.001 + 1e-3 * np.arange(3000)
    clock = check(frames(np.concatenate([before, backlog, after])))
    assert not clock.implausible
    assert clock.lead <= 1e-3


def test_a_stall_whose_backlog_overflowed_is_never_a_fault():
    """A 5 s stall where the port kept the first 2800 frames (64 kB) and dropped the rest:
    the frames after the gap follow by their sequence numbers and arrive promptly."""
    before = frames(1e-3 * np.arange(1000))
    kept = frames(np.full(2800, 6.0), first_sequence=1000, first_time_us=1_000_000)
    after = frames(6.0 + 1e-3 * np.arange(1, 2000), first_sequence=6000,
                   first_time_us=6_000_000)
    clock = check(before + kept + after)
    assert not clock.implausible
    assert clock.lead <= 1e-3


def test_a_stream_twenty_times_too_fast_from_its_first_frame_is_implausible():
    """No frame of it was read before the flood: caught once its first frames settle as
    reference (0.1-0.2 s of host time), plus 1/19 s."""
    stream = frames(5.0 + 5e-5 * np.arange(10000))  # 20 000 frames a second for 0.5 s
    clock = check(stream)
    assert clock.implausible
    assert clock.ratio == pytest.approx(20.0, rel=0.01)
    assert clock.last_device_time < 0.3 * 20  # within 0.3 s of host time
    # Latched: more frames change nothing.
    assert device_clock_after_frames(clock, frames([9.0], 9000, 9_000_000)) is clock


def test_a_flood_after_an_honest_start_is_implausible_within_a_tenth_of_a_second():
    honest = 1e-3 * np.arange(2000)
    flood = 2.0 + 5e-5 * np.arange(1, 4000)
    clock = check(frames(np.concatenate([honest, flood])))
    assert clock.implausible
    assert 2000 * 1e-3 < clock.last_device_time < 2.0 + 20 * 0.1


def test_a_restarted_device_moves_the_reference():
    """A device that restarts with a clock far ahead (its time stepping by what its
    sequence numbers do not explain) is followed from there, not taken as running ahead."""
    before = frames(1e-3 * np.arange(500))
    after = frames(0.5 + 1e-3 * np.arange(500), first_sequence=3, first_time_us=3_600_000_000)
    clock = check(before + after)
    assert not clock.implausible
    assert abs(clock.lead) < 1e-6


def test_a_slow_device_clock_never_faults():
    """A device clock 1 % slow keeps falling behind; the reference follows it."""
    clock = check(frames(1.01e-3 * np.arange(20000)))
    assert not clock.implausible


def test_the_fault_says_how_fast_where_what_was_lost_and_what_to_check():
    clock = check(frames(5e-5 * np.arange(10000)))
    text = implausible_clock_description(clock, "/dev/ttyUSB0", 187525)
    assert text.startswith("frames arrive faster than the myRIO's 1000 a second: its clock "
                           "ran 20.0 times the host's on /dev/ttyUSB0 (")
    assert "; 187525 frames dropped when the queue overflowed; check that tactile.port is " \
        "the myRIO's and that it streams one frame per millisecond" in text
    assert "\n" not in text


# Through the serial path in real time.

def flood(master, stop: threading.Event, per_millisecond: int = 30):
    """Writes valid frames, each 1 ms of device time after the last, `per_millisecond` of
    them every host millisecond, until `stop` (a myRIO far faster than its 1000 a second)."""
    k = 0
    while not stop.is_set():
        chunk = b"".join(encode_frame(k + i, 1000 * (k + i), (0, 0))
                         for i in range(per_millisecond))
        try:
            os.write(master, chunk)
            k += per_millisecond
        except BlockingIOError:
            pass  # the pty is full: the reader is behind, as a real port's would be
        time.sleep(0.001)


def advance_until_fault(simulator, receiver, limit_s: float) -> tuple:
    context = simulator.get_mutable_context()
    end = context.get_time() + limit_s
    while context.get_time() < end:
        simulator.AdvanceTo(context.get_time() + 0.01)
        faults = receiver.GetOutputPort("fault").Eval(context)
        if faults:
            return faults
    return ()


def test_a_flooding_myrio_is_an_implausible_fault_on_the_receiver():
    master, slave, port = open_raw_pty()
    stop = threading.Event()
    writer = threading.Thread(target=flood, args=(master, stop), daemon=True)
    try:
        with TactileSerialReader(port) as reader:
            writer.start()
            receiver = TactileSerialReceiver(reader)
            simulator = Simulator(receiver)
            simulator.set_target_realtime_rate(1.0)
            # Generous: at 30 times its rate the device runs 1 s ahead in about 35 ms.
            faults = advance_until_fault(simulator, receiver, limit_s=10.0)
    finally:
        stop.set()
        writer.join(2.0)
        os.close(master)
        os.close(slave)
    assert [(f.device, f.kind) for f in faults] == [("tactile", IMPLAUSIBLE)]
    text = str(faults[0])
    assert text.startswith("tactile: implausible: frames arrive faster than the myRIO's "
                           "1000 a second: its clock ran "), text
    assert f" times the host's on {port} (" in text
    assert "frames dropped when the queue overflowed; check that tactile.port" in text


def test_an_honest_myrio_gives_no_fault():
    times = np.arange(0.0, 3.0, 0.001)
    trial = TactileRecording(times, np.zeros((len(times), 12)), np.zeros((len(times), 12)),
                             times, np.zeros(len(times)), np.zeros(len(times)))
    with MyRioEmulator(trial) as emulator, TactileSerialReader(emulator.port) as reader:
        receiver = TactileSerialReceiver(reader)
        simulator = Simulator(receiver)
        simulator.set_target_realtime_rate(1.0)
        assert advance_until_fault(simulator, receiver, limit_s=2.0) == ()
        assert reader.counters().decoder.frames > 500
