"""The receiver's playout of bursty frames (one piezo sample per tick, impacts kept) and the
myRIO emulator's replay paced by a controller's clock."""

import time

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import (
    MyRioEmulator, MyRioEmulatorConfig, TactileRecording)
from tegrasp_drake.hardware.myrio.tactile_calibration import TactileCalibration
from tegrasp_drake.hardware.myrio.tactile_frame import PIEZO_VOLTS_PER_COUNT, TactileFrame
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import (initial_receiver_state,
                                                           receiver_state_after_tick)

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

CALIBRATION = TactileCalibration(zero_samples=0)  # no zeroing: piezo offset 0
IMPACT = 3000  # piezo counts


def frames(piezo_samples, first=0):
    return [TactileFrame(first + k, (first + k) * 1000, (p, p), arrival_time=float(first + k))
            for k, p in enumerate(piezo_samples)]


def play(ticks, max_backlog=8):
    """Film readings [counts] and device times [ms] after each tick's received frames."""
    state = initial_receiver_state(CALIBRATION)
    readings = []
    for received in ticks:
        state = receiver_state_after_tick(state, received, CALIBRATION, max_backlog)
        volts = state.accelerations[0] / CALIBRATION.left.piezo_gain
        readings.append((round(volts / PIEZO_VOLTS_PER_COUNT), round(state.device_time * 1e3)))
    return readings


def test_frames_arriving_one_per_tick_play_at_once():
    assert play([[f] for f in frames([1, 2, 3])]) == [(1, 0), (2, 1), (3, 2)]


def test_two_frames_in_one_tick_play_one_per_tick_in_order():
    burst = frames([1, IMPACT, 3])
    assert play([burst[:2], [], [burst[2]]]) == [(1, 0), (IMPACT, 1), (3, 2)]


def test_a_backlog_drains_two_per_tick_keeping_the_impact():
    burst = frames([1, 2, 3, IMPACT, 5, 6])
    readings = play([burst, [], [], []])
    assert readings == [(2, 1), (IMPACT, 3), (5, 4), (6, 5)]


def test_more_than_max_backlog_frames_play_at_once_keeping_the_impact():
    burst = frames([IMPACT] + [1] * 11)
    readings = play([burst], max_backlog=4)
    assert readings == [(IMPACT, 7)]


def test_every_sample_is_played_once_in_order_whatever_the_bursts():
    # Bursts that drain one, two and many (over max_backlog) per tick and ticks with none:
    # the vector output merges and holds, played_samples hold each device sample once.
    sent = np.arange(1, 41)
    burst = frames(sent)
    ticks = [burst[:3], [], [], burst[3:20], [], burst[20:21], [], [], [], burst[21:]] + [[]] * 20
    state = initial_receiver_state(CALIBRATION)
    played, empty_ticks = [], 0
    for received in ticks:
        state = receiver_state_after_tick(state, received, CALIBRATION, max_backlog=4)
        played.extend(state.played_samples[:, 1])
        empty_ticks += len(state.played_samples) == 0
    volts = np.array(played) / CALIBRATION.right.piezo_gain
    np.testing.assert_array_equal(np.round(volts / PIEZO_VOLTS_PER_COUNT), sent)
    assert empty_ticks > 0


def test_replay_paced_by_a_clock_sends_each_sample_once_when_the_clock_reaches_it():
    t = np.arange(0.0, 1.0, 1e-3)
    trial = TactileRecording(t, np.zeros((len(t), 12)), np.zeros((len(t), 12)), t,
                         np.zeros((len(t), 3)), np.zeros(len(t)))
    clock = [0.0]
    config = MyRioEmulatorConfig(start_on_trigger=True, lead_in=0.0)
    with MyRioEmulator(trial, config, trial_clock=lambda: clock[0]) as emulator, \
            TactileSerialReader(emulator.port):
        time.sleep(0.05)
        emulator.start_trial()
        time.sleep(0.05)
        clock[0] = 0.0205  # the controller reached 20.5 ms of the trial
        time.sleep(0.1)
        start = emulator.sent()
    first = next(k for k, f in enumerate(start) if f.write_time >= emulator.trial_start_time)
    trial_frames = start[first:]
    assert len(trial_frames) == 21  # samples 0..20, once each
    assert np.all(np.diff([f.sequence for f in trial_frames]) == 1)
    assert emulator.trial_start_time == pytest.approx(trial_frames[0].write_time, abs=0.01)
