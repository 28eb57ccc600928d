"""The RA thresholds in sigmas of the channel's noise (control/noise_thresholds.py) and the
closed-form noise they use (simulation/film_readout.py): the closed form matches the
readout's noise measured on simulated quiet samples; noise alone stays below a rule's k
sigma and crosses a lower one; the threshold in force follows the noise for two noise
settings; the rule's defaults are the ones the config holds."""

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import (HeuristicControllerConfig,
                                                     MemorizedControllerConfig,
                                                     TaxelAwareControllerConfig)
from tegrasp_drake.control.noise_thresholds import (default_rule_sigmas,
                                                    resolve_noise_thresholds,
                                                    slip_band_noise_std)
from tegrasp_drake.simulation.film_readout import adc_input, reading_mps2
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           noise_draw_std_v,
                                                           ra_noise_std_mps2, volts_per_mps2)
from tegrasp_drake.tactile.slip_vibration_band import biquad_block_map, filter_block, \
    highpass_biquad

RATE_HZ = 1000.0
NOISE_SETTINGS = (0.05, 1.2)  # the amplifier's noise [m/s^2]: the default, and raised


def _quiet_readings(config: VibrationSensorConfig, samples: int, seed: int) -> np.ndarray:
    """What the readout gives for a still film (reading 0.3 m/s^2, a quarter code off the
    grid) with the config's noise, drawn from a seeded generator."""
    rng = np.random.default_rng(seed)
    std_v = noise_draw_std_v(config)
    readout = (volts_per_mps2(config), config.amplifier_swing_v, adc_input(config.adc_input))
    return np.array([reading_mps2(0.3, std_v * n, *readout)
                     for n in rng.standard_normal(samples)])


def _band_rms(readings: np.ndarray, window: int) -> np.ndarray:
    """The slip band's RMS (one pad, its film on z) after each sample of `readings`."""
    block = np.zeros((len(readings), 6))
    block[:, 2] = readings
    state = np.zeros(12 + 2 * window)
    out = []
    step = biquad_block_map(highpass_biquad(80.0, RATE_HZ), 1)
    for row in block:
        filter_block(step, row[np.newaxis], state, window)
        out.append(np.sqrt(state[12:12 + window].mean()))
    return np.asarray(out)


@pytest.mark.parametrize("noise", NOISE_SETTINGS)
def test_closed_form_noise_matches_the_readouts_measured_noise(noise):
    config = VibrationSensorConfig(noise_std_mps2=noise)
    measured = _quiet_readings(config, 40_000, seed=600).std()
    assert measured == pytest.approx(ra_noise_std_mps2(config), rel=0.02)


@pytest.mark.parametrize("noise", NOISE_SETTINGS)
def test_slip_band_noise_in_closed_form_matches_the_filtered_readings(noise):
    config = VibrationSensorConfig(noise_std_mps2=noise)
    readings = _quiet_readings(config, 20_000, seed=601)
    mean_square = (_band_rms(readings, 1)[100:] ** 2).mean()
    assert np.sqrt(mean_square) == pytest.approx(
        slip_band_noise_std(ra_noise_std_mps2(config), 80.0, RATE_HZ), rel=0.03)


@pytest.mark.parametrize("noise", NOISE_SETTINGS)
def test_noise_alone_stays_below_the_rules_k_sigma_and_crosses_a_lower_k(noise):
    config = VibrationSensorConfig(noise_std_mps2=noise)
    sigma = ra_noise_std_mps2(config)
    band_sigma = slip_band_noise_std(sigma, 80.0, RATE_HZ)
    magnitude_k, band_k = default_rule_sigmas(RATE_HZ, window_samples=10)
    readings = _quiet_readings(config, 28_000, seed=602)  # one trial's samples
    rms = _band_rms(readings, 10)[100:]
    magnitude = np.abs(readings - 0.3)  # the raw RA about its still reading
    assert magnitude.max() < magnitude_k * sigma
    assert rms.max() < band_k * band_sigma
    # Half the rule's k: the noise crosses it many times.
    assert np.count_nonzero(magnitude > 0.5 * magnitude_k * sigma) > 100
    assert np.count_nonzero(rms > 0.5 * band_k * band_sigma) > 100


@pytest.mark.parametrize("noise", NOISE_SETTINGS)
def test_thresholds_in_force_are_the_larger_of_the_number_and_k_sigma(noise):
    vibration = VibrationSensorConfig(noise_std_mps2=noise)
    sigma = ra_noise_std_mps2(vibration)
    config = HeuristicControllerConfig()
    resolved = resolve_noise_thresholds(config, ra_noise_std_mps2=sigma, ra_rate_hz=RATE_HZ)
    band = slip_band_noise_std(sigma, config.lift_load.slip_band_hz, RATE_HZ)
    assert resolved.avoid.hit_ra_mps2 == pytest.approx(
        max(config.avoid.hit_ra_mps2, config.avoid.hit_ra_sigmas * sigma))
    assert resolved.lift_load.slip_vibration_mps2 == pytest.approx(
        max(config.lift_load.slip_vibration_mps2, config.lift_load.slip_vibration_sigmas * band))
    assert resolved.heuristic.place_ra_mps2 == pytest.approx(
        max(config.heuristic.place_ra_mps2, config.heuristic.place_ra_sigmas * sigma))
    assert config == HeuristicControllerConfig()  # the caller's config untouched


def test_thresholds_follow_the_noise_above_the_numbers():
    # Default electronics: sigma 0.71 m/s^2 (a code of 1.23 m/s^2 and the converter's
    # half code dominate), raised: 1.39 m/s^2. Both put k sigma above the numbers.
    low, high = (ra_noise_std_mps2(VibrationSensorConfig(noise_std_mps2=n))
                 for n in NOISE_SETTINGS)
    assert 0.6 < low < 0.8 and 1.3 < high < 1.5
    config = MemorizedControllerConfig()
    resolved = [resolve_noise_thresholds(config, ra_noise_std_mps2=s, ra_rate_hz=RATE_HZ)
                for s in (low, high)]
    assert resolved[1].avoid.hit_ra_mps2 / resolved[0].avoid.hit_ra_mps2 == pytest.approx(high / low)
    assert resolved[1].lift_load.slip_vibration_mps2 / resolved[0].lift_load.slip_vibration_mps2 == \
        pytest.approx(high / low)


def test_an_ideal_quiet_channel_keeps_the_numbers():
    config = MemorizedControllerConfig()
    sigma = ra_noise_std_mps2(VibrationSensorConfig(adc_input="ideal"))
    assert sigma == pytest.approx(0.05)
    resolved = resolve_noise_thresholds(config, ra_noise_std_mps2=sigma, ra_rate_hz=RATE_HZ)
    assert resolved.avoid.hit_ra_mps2 == config.avoid.hit_ra_mps2
    assert resolved.lift_load.slip_vibration_mps2 == config.lift_load.slip_vibration_mps2


def test_the_configs_sigmas_are_the_rules():
    magnitude_k, band_k = default_rule_sigmas(RATE_HZ, window_samples=10)
    config = HeuristicControllerConfig()
    assert config.avoid.hit_ra_sigmas == pytest.approx(magnitude_k, abs=0.005)
    assert config.heuristic.place_ra_sigmas == pytest.approx(magnitude_k, abs=0.005)
    assert config.lift_load.slip_vibration_sigmas == pytest.approx(band_k, abs=0.005)
    assert TaxelAwareControllerConfig().taxel_aware.ra_onset_sigmas == pytest.approx(
        magnitude_k, abs=0.005)


@pytest.mark.parametrize("noise", NOISE_SETTINGS)
def test_the_ra_onset_threshold_in_force_is_the_larger_of_the_number_and_k_sigma(noise):
    sigma = ra_noise_std_mps2(VibrationSensorConfig(noise_std_mps2=noise))
    taxel = TaxelAwareControllerConfig().taxel_aware
    resolved = resolve_noise_thresholds(TaxelAwareControllerConfig(), ra_noise_std_mps2=sigma,
                                        ra_rate_hz=RATE_HZ)
    assert resolved.taxel_aware.ra_onset_mps2 == pytest.approx(
        max(taxel.ra_onset_mps2, taxel.ra_onset_sigmas * sigma))


def test_an_ra_onset_threshold_of_zero_stays_off():
    config = TaxelAwareControllerConfig()
    config.taxel_aware.ra_onset_mps2 = 0.0
    resolved = resolve_noise_thresholds(config, ra_noise_std_mps2=1.0, ra_rate_hz=RATE_HZ)
    assert resolved.taxel_aware.ra_onset_mps2 == 0.0
