"""Tactile calibration: counts to newtons, piezo to m/s^2, zeroing, YAML."""

import numpy as np
import pytest

from tegrasp_drake.hardware.myrio.tactile_calibration import (
    LoadTactileCalibration, PadCalibration, PadZeroing, SaveTactileCalibration,
    TactileCalibration, acceleration_from_piezo, counts_from_forces, forces_from_counts,
    piezo_from_acceleration)


def test_forces_round_trip_within_one_count():
    pad = PadCalibration(gain=list(np.linspace(1e-3, 2e-3, 12)), offset=[20000.0] * 12)
    forces = np.linspace(0.0, 5.0, 12)
    counts = counts_from_forces(forces, pad.gain, pad.offset)
    np.testing.assert_allclose(forces_from_counts(counts, pad.gain, pad.offset), forces,
                               atol=np.max(pad.gain) / 2)


def test_counts_below_the_baseline_give_zero_force():
    assert forces_from_counts([29990.0] * 12, [1e-3] * 12, [30000.0] * 12).sum() == 0.0


def test_piezo_round_trip_and_saturation():
    volts_per_count = 10.0 / 32768
    samples = piezo_from_acceleration([-3.0, 0.0, 12.5, 1e6], volts_per_count, 10.0, 0.1)
    assert samples[-1] == 32767
    np.testing.assert_allclose(
        acceleration_from_piezo(samples[:3], volts_per_count, 10.0, 0.1), [-3.0, 0.0, 12.5],
        atol=10.0 * volts_per_count)


def test_zeroing_takes_the_means_seen():
    zeroing = PadZeroing()
    for counts, volts in (([100.0] * 12, 0.2), (None, 0.4), ([300.0] * 12, 0.0)):
        zeroing = zeroing.add(counts, volts)
    assert zeroing.done(2) and not zeroing.done(3)
    pad = zeroing.zeroed(PadCalibration())
    assert pad.offset == pytest.approx([200.0] * 12)
    assert pad.piezo_offset == pytest.approx(0.2)
    assert pad.gain == PadCalibration().gain


def test_yaml_round_trip(tmp_path):
    calibration = TactileCalibration(right=PadCalibration(piezo_gain=3.5), zero_samples=5)
    filename = str(tmp_path / "calibration.yaml")
    SaveTactileCalibration(calibration, filename)
    assert LoadTactileCalibration(filename) == calibration
