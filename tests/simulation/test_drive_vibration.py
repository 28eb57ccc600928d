"""The drives' vibration (drive_vibration.py): nothing while the joints stand still; while
they move, tones at the orders of the motor's rotation, growing with speed, each scaled by
the fingertip mode's gain, sampled at the RA rate (a tone above 500 Hz folds back); a
drive's joints lumped into one set of tones."""

import math

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, VectorLogSink

from tegrasp_drake.simulation.drive_vibration import (AddDriveVibration, DriveVibrationConfig,
                                                      arm_drive_default, gripper_drive_default,
                                                      mode_gain)

PERIOD_S, MODE_HZ, ZETA = 1e-3, 400.0, 0.05


def _readings(rates_by_drive, configs, duration_s=1.0) -> np.ndarray:
    """The [left, right] readings, one row per RA sample, of drives `configs` whose joints
    turn at the constant `rates_by_drive`."""
    builder = DiagramBuilder()
    sources = []
    for rates, config in zip(rates_by_drive, configs):
        source = builder.AddSystem(ConstantVectorSource(np.asarray(rates, dtype=float)))
        sources.append((config, source.get_output_port()))
    output = AddDriveVibration(builder, sources=sources, period_s=PERIOD_S,
                               mode_frequency_hz=MODE_HZ, damping_ratio=ZETA)
    logger = builder.AddSystem(VectorLogSink(2, PERIOD_S))
    builder.Connect(output, logger.get_input_port())
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.AdvanceTo(duration_s)
    return logger.FindLog(simulator.get_context()).data().T[1:]


def _tone(samples: np.ndarray, frequency_hz: float) -> float:
    """The amplitude of the tone at frequency_hz in samples at 1 / PERIOD_S (a whole number
    of its periods in the record)."""
    t = np.arange(len(samples)) * PERIOD_S
    return float(2.0 * abs(np.mean(samples * np.exp(-2j * math.pi * frequency_hz * t))))


def test_drives_read_nothing_while_their_joints_stand_still():
    readings = _readings([[0.0], np.zeros(6)], [gripper_drive_default(), arm_drive_default()])
    np.testing.assert_array_equal(readings, np.zeros_like(readings))


def test_a_moving_gripper_reads_its_motor_and_mesh_tones_scaled_by_speed_and_mode():
    config = gripper_drive_default()
    v = 0.5 * config.full_speed  # half speed: 50 rev/s of the motor
    readings = _readings([[v]], [config])
    left = readings[:, 0]
    np.testing.assert_array_equal(readings[:, 1], left)  # both pads read the base's shaking
    motor_hz = config.motor_revolutions_per_unit * v
    assert motor_hz == pytest.approx(50.0)
    # Order 1 at 50 Hz; order 12 at 600 Hz folds to 400 Hz at 1 kHz sampling.
    assert _tone(left, 50.0) == pytest.approx(0.5 * 0.1 * mode_gain(50.0, MODE_HZ, ZETA),
                                              rel=1e-3)
    assert _tone(left, 400.0) == pytest.approx(
        0.5 * 0.3 * mode_gain(600.0, MODE_HZ, ZETA), rel=1e-3)
    assert np.sqrt(np.mean(left ** 2)) == pytest.approx(np.hypot(
        _tone(left, 50.0), _tone(left, 400.0)) / math.sqrt(2), rel=1e-3)


def test_an_arm_reads_one_tone_set_at_its_fastest_joint_with_the_power_of_all():
    config = DriveVibrationConfig(amplitudes_mps2=[0.2], orders=[2.0],
                                  motor_revolutions_per_unit=100.0 / (2 * math.pi),
                                  full_speed=0.5)
    # Joint 2 at 0.5 rad/s (7.96 rev/s of its motor, order 2 at 15.9 Hz), joint 5 at
    # -0.25 rad/s: one tone at 15.9 Hz of amplitude 0.2 x sqrt(0.5^2 + 0.25^2) / 0.5 (2 s
    # hold 31.8 of its periods: the fraction's leakage is below 2 %).
    rates = [0.0, 0.5, 0.0, 0.0, -0.25, 0.0]
    readings = _readings([rates], [config], duration_s=2.0)[:, 0]
    fast = 2 * 0.5 * 100 / (2 * math.pi)
    assert _tone(readings, fast) == pytest.approx(
        0.2 * math.hypot(0.5, 0.25) / 0.5 * mode_gain(fast, MODE_HZ, ZETA), rel=0.02)
    assert _tone(readings, fast / 2) < 0.01 * _tone(readings, fast)


def test_a_drive_with_no_amplitude_adds_no_system():
    builder = DiagramBuilder()
    source = builder.AddSystem(ConstantVectorSource([1.0]))
    off = DriveVibrationConfig(amplitudes_mps2=[0.0], orders=[1.0],
                               motor_revolutions_per_unit=10.0)
    assert AddDriveVibration(builder, sources=[(off, source.get_output_port())],
                             period_s=PERIOD_S, mode_frequency_hz=MODE_HZ,
                             damping_ratio=ZETA) is None
    assert len(builder.GetSystems()) == 1


def test_mode_gain_is_one_below_the_mode_its_peak_at_it_and_falls_above():
    assert mode_gain(1.0, MODE_HZ, ZETA) == pytest.approx(1.0, abs=1e-5)
    assert mode_gain(MODE_HZ, MODE_HZ, ZETA) == pytest.approx(1 / (2 * ZETA))
    assert mode_gain(4000.0, MODE_HZ, ZETA) == pytest.approx(1 / 99, rel=1e-3)
