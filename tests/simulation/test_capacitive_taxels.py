"""The AD7147 capacitive taxel: the parallel-plate formula on a known compression, its
counts, its calibration and its noise."""

import numpy as np
import pytest

from tegrasp_drake.simulation.capacitive_taxels import (CapacitiveTaxelConfig,
                                                        CapacitiveTaxels,
                                                        ad7147_frame_rate_hz, ad7147_stage_s,
                                                        calibration_gain_n_per_count,
                                                        frame_rate_matches)

# The pad and electrode as docs/model.md gives them, written out here so that the test
# checks the module's formula against its own numbers.
ELECTRODE_AREA_M2 = (0.020 / 3) * (0.024 / 4)
GAP_M = 0.004
MODULUS_PA = 2.0e6
EPSILON_0 = 8.8541878128e-12
COUNTS_PER_F = 4096 * 1e12  # 16 bits over the AD7147's +-8 pF


def readings(config, forces, noise=None, modulus_pa=MODULUS_PA):
    system = CapacitiveTaxels(config=config, pad_modulus_pa=modulus_pa)
    context = system.CreateDefaultContext()
    system.GetInputPort("true_taxel_forces").FixValue(context, forces)
    if noise is not None:
        system.GetInputPort("noise").FixValue(context, noise)
    return np.concatenate([system.GetOutputPort(f"{f}_taxel_forces").Eval(context)
                           for f in ("left", "right")])


def test_counts_follow_the_parallel_plate_formula_on_a_known_compression():
    config = CapacitiveTaxelConfig(noise_std_counts=0.0, output="counts")
    # 0.4 mm of compression (10 % of the gap) needs p = E 0.1 on the electrode.
    compression = 0.0004
    force = MODULUS_PA * compression / GAP_M * ELECTRODE_AREA_M2
    forces = np.zeros(24)
    forces[5], forces[17] = force, force / 2
    delta_c = config.relative_permittivity * EPSILON_0 * ELECTRODE_AREA_M2 * (
        1 / (GAP_M - compression) - 1 / GAP_M)
    half = config.relative_permittivity * EPSILON_0 * ELECTRODE_AREA_M2 * (
        1 / (GAP_M - compression / 2) - 1 / GAP_M)
    counts = readings(config, forces)
    assert counts[5] == np.rint(delta_c * COUNTS_PER_F)
    assert counts[17] == np.rint(half * COUNTS_PER_F)
    assert np.count_nonzero(counts) == 2
    # 1/d1 grows faster than the compression: half the force gives less than half.
    assert counts[17] < 0.5 * counts[5]


def test_calibrated_readings_are_exact_at_the_calibration_point_and_nonlinear_elsewhere():
    config = CapacitiveTaxelConfig(noise_std_counts=0.0, calibration_force_n=5.0)
    forces = np.zeros(24)
    forces[:3] = (1.0, 5.0, 20.0)
    newtons = readings(config, forces)
    gain = calibration_gain_n_per_count(config, pad_modulus_pa=MODULUS_PA)
    assert newtons[1] == pytest.approx(5.0, abs=gain)  # within one count
    assert newtons[0] < 1.0 - gain  # below the calibration point it reads low
    assert newtons[2] > 20.0 + gain  # above it, high
    assert np.all(newtons[3:] == 0.0)


def test_noise_is_in_counts_and_the_calibration_clips_negative_readings_to_zero():
    config = CapacitiveTaxelConfig(noise_std_counts=4.0, output="counts")
    noise = np.linspace(-2.0, 2.0, 24)
    counts = readings(config, np.zeros(24), noise)
    np.testing.assert_array_equal(counts, np.rint(4.0 * noise))
    calibrated = readings(CapacitiveTaxelConfig(noise_std_counts=4.0), np.zeros(24), noise)
    gain = calibration_gain_n_per_count(CapacitiveTaxelConfig(),
                                        pad_modulus_pa=MODULUS_PA)
    np.testing.assert_allclose(calibrated, np.maximum(np.rint(4.0 * noise), 0.0) * gain)


def test_the_gap_never_closes():
    config = CapacitiveTaxelConfig(noise_std_counts=0.0, output="counts")
    forces = np.full(24, 1e4)  # far beyond what the elastomer takes
    counts = readings(config, forces)
    limit = config.relative_permittivity * EPSILON_0 * ELECTRODE_AREA_M2 * (
        1 / (config.minimum_gap_fraction * GAP_M) - 1 / GAP_M)
    np.testing.assert_array_equal(counts, np.rint(limit * COUNTS_PER_F))


@pytest.mark.parametrize("decimation, frame_s, rate_hz", [(64, 9.216e-3, 108.0),
                                                          (128, 18.432e-3, 54.0),
                                                          (256, 36.864e-3, 27.0)])
def test_decimation_sets_the_stage_time_and_the_frame_rate(decimation, frame_s, rate_hz):
    # The data sheet's 12 stages of 0.768 ms at decimation 64, twice and four times that.
    assert 12 * ad7147_stage_s(decimation) == pytest.approx(frame_s)
    assert ad7147_frame_rate_hz(decimation) == pytest.approx(1.0 / frame_s)
    assert frame_rate_matches(rate_hz, decimation)
    assert not frame_rate_matches(rate_hz * 2, decimation)
    assert not frame_rate_matches(rate_hz / 2, decimation)


@pytest.mark.parametrize("decimation, noise_counts", [(64, 4.0), (128, 4.0 / 2 ** 0.5),
                                                      (256, 2.0)])
def test_a_larger_decimation_averages_the_noise_down(decimation, noise_counts):
    # A unit noise sample on every taxel reads noise_counts counts (rounded) above zero.
    config = CapacitiveTaxelConfig(output="counts", decimation=decimation)
    read = readings(config, np.zeros(24), noise=np.full(24, 10.0))
    np.testing.assert_array_equal(read, np.full(24, np.rint(10.0 * noise_counts)))


def test_a_stiffer_pad_compresses_less_under_the_same_force():
    """The compression d0 p / E follows the pad's modulus: twice as stiff, half the
    compression, read through the same parallel-plate formula."""
    config = CapacitiveTaxelConfig(noise_std_counts=0.0, output="counts")
    force = MODULUS_PA * 0.0004 / GAP_M * ELECTRODE_AREA_M2  # 0.4 mm at the default modulus
    forces = np.zeros(24)
    forces[5] = force
    stiffer = readings(config, forces, modulus_pa=2 * MODULUS_PA)
    delta_c = config.relative_permittivity * EPSILON_0 * ELECTRODE_AREA_M2 * (
        1 / (GAP_M - 0.0002) - 1 / GAP_M)
    assert stiffer[5] == np.rint(delta_c * COUNTS_PER_F)
    assert stiffer[5] < readings(config, forces)[5]
    # the calibration follows: the bench force over its counts on the stiffer pad
    bench = CapacitiveTaxelConfig()
    compression = GAP_M * bench.calibration_force_n / ELECTRODE_AREA_M2 / (2 * MODULUS_PA)
    bench_counts = bench.relative_permittivity * EPSILON_0 * ELECTRODE_AREA_M2 * (
        1 / (GAP_M - compression) - 1 / GAP_M) * COUNTS_PER_F
    assert calibration_gain_n_per_count(bench, pad_modulus_pa=2 * MODULUS_PA) == \
        pytest.approx(bench.calibration_force_n / bench_counts, rel=1e-12)
