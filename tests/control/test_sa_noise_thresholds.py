"""The SA thresholds against the taxels' noise (control/noise_thresholds.py) and the exact
rest distribution they use (simulation/taxel_rest_noise.py): the distribution matches the
transducer's own readings of simulated noise; a threshold leaves at most its tail
probability above it and the lattice value below it more; the resolved config raises only
what noise would cross and keeps the user's numbers otherwise."""

import dataclasses

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import (HeuristicControllerConfig,
                                                     MemorizedControllerConfig)
from tegrasp_drake.control.noise_thresholds import resolve_noise_thresholds, sa_noise_floors
from tegrasp_drake.simulation.capacitive_taxels import (capacitive_readings,
                                                        noise_std_at_decimation)
from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig, apply_sensor_model
from tegrasp_drake.simulation.taxel_rest_noise import loaded_noise, rest_reading

SAMPLES = 200_000
SA_RATE_HZ = 108.0
CAPACITIVE = TactileSensorConfig()
FORCE = TactileSensorConfig(transducer="force")


def _capacitive_rest_sums(config: TactileSensorConfig, seed: int) -> np.ndarray:
    """Eq. 1's sum of a pad's 12 calibrated readings with nothing touching, drawn through
    the transducer's own reading function."""
    rng = np.random.default_rng(seed)
    std = noise_std_at_decimation(config.capacitive)
    noise = std * rng.standard_normal((SAMPLES, 12))
    return capacitive_readings(np.zeros((SAMPLES, 12)), config.capacitive, noise,
                               pad_modulus_pa=config.pad_modulus_pa).sum(axis=1)


def _force_rest_sums(config: TactileSensorConfig, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    readings = apply_sensor_model(np.zeros((SAMPLES, 12)), rng, config.noise_std_n,
                                  config.quantization_n, config.offset_n)
    return readings.sum(axis=1)


@pytest.mark.parametrize("config, draw", [(CAPACITIVE, _capacitive_rest_sums),
                                          (FORCE, _force_rest_sums),
                                          (dataclasses.replace(FORCE, offset_n=0.02,
                                                               quantization_n=0.0),
                                           _force_rest_sums)])
def test_the_rest_distribution_is_the_transducers_own(config, draw):
    sums = draw(config, seed=601)
    exact = rest_reading(config).sum_of(12)
    assert exact.mean() == pytest.approx(sums.mean(), abs=4 * sums.std() / np.sqrt(SAMPLES))
    assert exact.std() == pytest.approx(sums.std(), rel=0.01)
    # A tail of one in a thousand: the exact level leaves at most that above it, and the
    # lattice value below it leaves more (within the draw's binomial spread).
    level = exact.exceeded_with(1e-3)
    spread = 4 * np.sqrt(1e-3 / SAMPLES)
    assert np.mean(sums > level) <= 1e-3 + spread
    assert np.mean(sums > level - exact.step) > 1e-3 - spread


def test_the_capacitive_pads_noise_has_a_positive_mean_and_a_floor_far_above_the_number():
    floors = sa_noise_floors(CAPACITIVE, SA_RATE_HZ)
    reading = rest_reading(CAPACITIVE)
    assert reading.sum_of(12).mean() > 1.0  # the clip at zero: a mean of about 1.5 N
    assert floors.pad_sum > 10 * MemorizedControllerConfig().contact_force_n
    assert floors.taxel < floors.pad_sum
    assert loaded_noise(CAPACITIVE).mean() == pytest.approx(0.0, abs=1e-12)


def test_ideal_force_taxels_keep_the_numbers_and_noisy_ones_raise_them():
    config = HeuristicControllerConfig()
    kept = resolve_noise_thresholds(config, ra_noise_std_mps2=0.0, ra_rate_hz=1000.0,
                                    tactile=FORCE, sa_rate_hz=SA_RATE_HZ)
    assert (kept.contact_force_n, kept.taxel_contact_n, kept.avoid.sa_asymmetry_n,
            kept.heuristic.contact_force_n) == (
        config.contact_force_n, config.taxel_contact_n, config.avoid.sa_asymmetry_n,
        config.heuristic.contact_force_n)
    raised = resolve_noise_thresholds(config, ra_noise_std_mps2=0.0, ra_rate_hz=1000.0,
                                      tactile=CAPACITIVE, sa_rate_hz=SA_RATE_HZ)
    floors = sa_noise_floors(CAPACITIVE, SA_RATE_HZ)
    assert raised.contact_force_n == raised.heuristic.contact_force_n == floors.pad_sum
    assert raised.taxel_contact_n == floors.taxel
    assert raised.avoid.sa_asymmetry_n == floors.pad_asymmetry
    assert config.contact_force_n == MemorizedControllerConfig().contact_force_n  # untouched


def test_the_floor_can_be_switched_off_and_a_number_above_it_stands():
    off = dataclasses.replace(MemorizedControllerConfig(), sa_noise_floor=False)
    resolved = resolve_noise_thresholds(off, ra_noise_std_mps2=0.0, ra_rate_hz=1000.0,
                                        tactile=CAPACITIVE, sa_rate_hz=SA_RATE_HZ)
    assert resolved.contact_force_n == off.contact_force_n
    high = dataclasses.replace(MemorizedControllerConfig(), contact_force_n=20.0)
    resolved = resolve_noise_thresholds(high, ra_noise_std_mps2=0.0, ra_rate_hz=1000.0,
                                        tactile=CAPACITIVE, sa_rate_hz=SA_RATE_HZ)
    assert resolved.contact_force_n == 20.0


def test_a_slower_frame_rate_lowers_the_floor():
    """Fewer samples per trial: noise alone has fewer tries at the threshold."""
    assert (sa_noise_floors(CAPACITIVE, 27.0).pad_sum
            <= sa_noise_floors(CAPACITIVE, SA_RATE_HZ).pad_sum)


def test_the_capacitive_noise_floors_follow_the_pads_modulus():
    """The same counts of noise are more newtons on a stiffer pad (its calibration's gain):
    each floor scales with the gain, the pad's modulus in the transducer's reading."""
    from tegrasp_drake.simulation.capacitive_taxels import calibration_gain_n_per_count
    stiffer = dataclasses.replace(CAPACITIVE, pad_modulus_pa=2 * CAPACITIVE.pad_modulus_pa)
    ratio = (calibration_gain_n_per_count(stiffer.capacitive,
                                          pad_modulus_pa=stiffer.pad_modulus_pa)
             / calibration_gain_n_per_count(CAPACITIVE.capacitive,
                                            pad_modulus_pa=CAPACITIVE.pad_modulus_pa))
    assert ratio > 2.0  # the reading is nonlinear: not exactly the modulus' ratio
    base, floors = (sa_noise_floors(c, SA_RATE_HZ) for c in (CAPACITIVE, stiffer))
    for name in ("pad_sum", "taxel", "pad_asymmetry"):
        assert getattr(floors, name) == pytest.approx(ratio * getattr(base, name), rel=1e-9)
