"""The myRIO emulator on a pty, the reader thread and the receiver system, end to end."""

import dataclasses
import os
import time

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator

from tegrasp_drake.emulators.myrio_emulator import (
    MyRioEmulator, MyRioEmulatorConfig, StreamFaults, TactileFrameSource, TactileRecording)
from tegrasp_drake.emulators.null_modem import open_raw_pty
from tegrasp_drake.hardware.myrio.tactile_calibration import PadCalibration, TactileCalibration
from tegrasp_drake.hardware.myrio.tactile_frame import encode_frame
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

# Calibration of the emulated pads: different gains per taxel, offsets the receiver must
# find by zeroing (its own calibration starts from the default offsets).
PADS = PadCalibration(gain=list(np.linspace(1e-3, 3e-3, 12)), offset=[25000.0] * 12,
                      piezo_gain=10.0, piezo_offset=0.05)


def make_trial(duration=0.3):
    """Left pad pressed with a ramp, right pad constant; a 50 Hz vibration on both that
    settles at a constant for the last 50 ms (so the final values do not depend on when
    exactly the last frame was sampled)."""
    force_times = np.arange(0.0, duration, 0.001)
    ramp = np.minimum(force_times / 0.1, 1.0)
    left = np.outer(ramp, np.linspace(0.5, 2.0, 12))
    right = np.full((len(force_times), 12), 0.75)
    acceleration_times = np.arange(0.0, duration, 0.001)
    vibration = np.where(acceleration_times < duration - 0.05,
                         np.sin(2 * np.pi * 50 * acceleration_times), 0.3)
    left_acceleration = np.column_stack([3 * vibration, 4 * vibration, 0 * vibration])
    return TactileRecording(force_times, left, right, acceleration_times, left_acceleration,
                        2 * vibration)


def emulator_config(**faults):
    return MyRioEmulatorConfig(
        lead_in=0.12, calibration=TactileCalibration(left=PADS, right=PADS),
        faults=StreamFaults(**faults, seed=5))


def receiver_calibration():
    calibration = TactileCalibration(zero_samples=8)
    for pad in calibration.pads():
        pad.gain, pad.piezo_gain = list(PADS.gain), PADS.piezo_gain
    return calibration


def test_receiver_reproduces_the_trial_after_zeroing():
    trial = make_trial()
    with MyRioEmulator(trial, emulator_config()) as emulator, \
            TactileSerialReader(emulator.port) as reader:
        receiver = TactileSerialReceiver(reader, calibration=receiver_calibration())
        simulator = Simulator(receiver)
        simulator.set_target_realtime_rate(1.0)
        context = simulator.get_mutable_context()
        simulator.AdvanceTo(0.04)  # 8 count sequences take 74 ms
        assert receiver.GetOutputPort("zeroing").Eval(context)[0] == 1
        assert not receiver.GetOutputPort("left_taxel_forces").Eval(context).any()
        simulator.AdvanceTo(0.5)  # lead-in 0.12 s + trial 0.3 s, all in real time
        assert emulator.wait_until_finished(0.5)
        simulator.AdvanceTo(0.52)
        assert receiver.GetOutputPort("zeroing").Eval(context)[0] == 0
        np.testing.assert_allclose(receiver.GetOutputPort("left_taxel_forces").Eval(context),
                                   trial.left_forces[-1], atol=3e-3)
        np.testing.assert_allclose(receiver.GetOutputPort("right_taxel_forces").Eval(context),
                                   trial.right_forces[-1], atol=3e-3)
        # The left film is replayed as |a| (Eq. 2), the right one as recorded; x only.
        left_a = receiver.GetOutputPort("left_pad_acceleration").Eval(context)
        right_a = receiver.GetOutputPort("right_pad_acceleration").Eval(context)
        np.testing.assert_allclose(left_a, [np.linalg.norm(trial.left_acceleration[-1]), 0, 0],
                                   atol=0.01)
        np.testing.assert_allclose(right_a, [trial.right_acceleration[-1], 0, 0], atol=0.01)
        last_timestamp = emulator.sent()[-1].timestamp_us
        assert receiver.GetOutputPort("time_measured").Eval(context)[0] == pytest.approx(
            last_timestamp * 1e-6)
        assert reader.counters().decoder.rejected == 0


def test_faulty_stream_is_counted_and_only_genuine_frames_pass():
    trial = make_trial(0.4)
    config = emulator_config(bit_flip=0.03, dropped_byte=0.03, truncated=0.03)
    source = TactileFrameSource(trial, dataclasses.replace(config, faults=StreamFaults()))
    received = []
    with MyRioEmulator(trial, config) as emulator, \
            TactileSerialReader(emulator.port) as reader:
        deadline = time.monotonic() + 3.0
        while not emulator.wait_until_finished(0.01) and time.monotonic() < deadline:
            received += reader.drain()
        time.sleep(0.02)
        received += reader.drain()
        counters, sent = reader.counters(), emulator.counters()
    assert sent.faulted_frames > 10
    assert counters.decoder.rejected > 0 and counters.decoder.dropped_frames > 0
    # Frames written before the reader opened the port are flushed by the open.
    first = received[0].sequence
    expected = [s.sequence for s in emulator.sent() if s.sequence >= first and not s.faults]
    assert [frame.sequence for frame in received] == expected
    assert counters.decoder.frames == len(received)
    for frame in received:  # each passed frame is exactly what the device meant to send
        assert encode_frame(frame.sequence, frame.timestamp_us, frame.piezo,
                            frame.left_counts, frame.right_counts) == source.frame(
                                frame.sequence)


def _advance_until(simulator, receiver, stale: float, limit_s: float = 5.0) -> None:
    """Advance in 10 ms steps until the receiver's `stale` output reads `stale`, at most
    limit_s of simulated time (a busy host delivers the last frames late)."""
    context = simulator.get_mutable_context()
    end = context.get_time() + limit_s
    while receiver.GetOutputPort("stale").Eval(context)[0] != stale:
        assert context.get_time() < end, f"stale never read {stale} within {limit_s} s"
        simulator.AdvanceTo(context.get_time() + 0.01)


def test_silent_device_makes_outputs_stale_without_changing_them():
    with MyRioEmulator(make_trial(2.0), emulator_config()) as emulator, \
            TactileSerialReader(emulator.port) as reader:
        receiver = TactileSerialReceiver(reader, calibration=receiver_calibration(),
                                         stale_timeout=0.05)
        simulator = Simulator(receiver)
        simulator.set_target_realtime_rate(1.0)
        context = simulator.get_mutable_context()
        simulator.AdvanceTo(0.3)
        _advance_until(simulator, receiver, stale=0)
        emulator.stop_talking()
        _advance_until(simulator, receiver, stale=1)  # the frames under way have arrived
        before = {name: receiver.GetOutputPort(name).Eval(context).copy()
                  for name in ("left_taxel_forces", "left_pad_acceleration", "time_measured")}
        simulator.AdvanceTo(context.get_time() + 0.15)
        assert receiver.GetOutputPort("stale").Eval(context)[0] == 1
        for name, value in before.items():
            np.testing.assert_array_equal(receiver.GetOutputPort(name).Eval(context), value)
        emulator.resume_talking()
        _advance_until(simulator, receiver, stale=0)
        assert receiver.GetOutputPort("time_measured").Eval(context)[0] > (
            before["time_measured"][0])
        assert reader.counters().decoder.dropped_frames > 50


def test_a_step_with_no_data_arriving_returns_promptly():
    master, slave, port = open_raw_pty()
    try:
        with TactileSerialReader(port) as reader:
            receiver = TactileSerialReceiver(reader)
            simulator = Simulator(receiver)
            start = time.monotonic()
            simulator.AdvanceTo(0.5)  # 500 updates, as fast as possible
            elapsed = time.monotonic() - start
            assert elapsed < 0.5
            assert receiver.GetOutputPort("stale").Eval(simulator.get_context())[0] == 1
            assert receiver.GetOutputPort("time_measured").Eval(
                simulator.get_context())[0] == 0
    finally:
        os.close(master)
        os.close(slave)


def test_reader_queue_is_bounded_and_keeps_the_newest():
    master, slave, port = open_raw_pty()
    try:
        with TactileSerialReader(port, queue_size=10) as reader:
            os.write(master, b"".join(encode_frame(k, 1000 * k, (k, -k)) for k in range(50)))
            deadline = time.monotonic() + 2.0
            while reader.counters().decoder.frames < 50 and time.monotonic() < deadline:
                time.sleep(0.005)
            frames = reader.drain()
            assert [f.sequence for f in frames] == list(range(40, 50))
            assert reader.counters().queue_overflows == 40
            assert reader.drain() == []
    finally:
        os.close(master)
        os.close(slave)



def test_a_receiver_zeroed_before_the_start_starts_zeroed():
    """Zeroing before the Simulator starts leaves no stretch of exact zeros at the start of
    the run: the first tick already carries the zeroed pads (a zeroing stretch followed by
    the pads' clipped noise is a step that step-shaped memorized events match)."""
    with MyRioEmulator(make_trial(), emulator_config()) as emulator, \
            TactileSerialReader(emulator.port) as reader:
        receiver = TactileSerialReceiver(reader, calibration=receiver_calibration())
        assert receiver.zero_before_start(time.monotonic() + 2.0)
        simulator = Simulator(receiver)
        context = simulator.get_mutable_context()
        assert receiver.GetOutputPort("zeroing").Eval(context)[0] == 1  # the default state
        simulator.Initialize()
        assert receiver.GetOutputPort("zeroing").Eval(context)[0] == 0
        # The offsets found are the emulated pads' (the lead-in is quiet: zero force).
        pads = receiver.GetMyContextFromRoot(context).get_abstract_state(0).get_value().pads
        for pad in pads:
            np.testing.assert_allclose(pad.offset, PADS.offset, atol=0.5)
            assert pad.piezo_offset == pytest.approx(PADS.piezo_offset, abs=1e-3)


def test_zeroing_before_the_start_gives_up_at_its_deadline():
    with MyRioEmulator(make_trial(), emulator_config()) as emulator, \
            TactileSerialReader(emulator.port) as reader:
        receiver = TactileSerialReceiver(reader, calibration=TactileCalibration(
            zero_samples=10_000))
        assert not receiver.zero_before_start(time.monotonic() + 0.05)
