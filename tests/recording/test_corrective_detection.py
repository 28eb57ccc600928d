"""The corrective triggers replayed offline from logs (experiments/corrective_detection.py):
the slip band equals what the SlipVibrationBand system computes online, first firings are
classified by detection_quality's rules, and the heuristic hit and slip triggers fire when
their conditions first hold."""

import types

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator

from tegrasp_drake.recording.corrective_detection import (
    SituationSpan, classify_first_firing, heuristic_hit_time, heuristic_slip_time, slip_band)
from tegrasp_drake.tactile.slip_vibration_band import SlipVibrationBand

RATE_HZ, BAND_HZ, WINDOW_S = 1000.0, 80.0, 0.01


def _vibration_log(seconds: float = 0.4) -> types.SimpleNamespace:
    """A log whose left pad vibrates at 200 Hz (2 m/s^2 on z) from 0.2 s on, with a slow
    30 Hz sway that the band removes, and whose right pad carries noise."""
    t = np.arange(0.0, seconds, 1.0 / RATE_HZ)
    rng = np.random.default_rng(600)
    pad = np.zeros((len(t), 6))
    pad[:, 2] = np.where(t >= 0.2, 2.0 * np.sin(2 * np.pi * 200.0 * t), 0.0) \
        + 0.5 * np.sin(2 * np.pi * 30.0 * t)
    pad[:, 3:] = 0.05 * rng.normal(size=(len(t), 3))
    return types.SimpleNamespace(t_ra=t, pad_acceleration=pad,
                                 ra=np.abs(pad[:, [2, 5]]))


@pytest.mark.parametrize("samples", [5, 37, 250])
def test_offline_slip_band_equals_the_online_system(samples):
    log = _vibration_log()
    band = SlipVibrationBand(band_hz=BAND_HZ, window_s=WINDOW_S, sample_rate_hz=RATE_HZ)
    context = band.CreateDefaultContext()
    # All the samples so far arrive at one tick (the device's batch input).
    band.GetInputPort("pad_acceleration_samples").FixValue(
        context, log.pad_acceleration[:samples])
    Simulator(band, context).AdvanceTo(0.5 / RATE_HZ)  # the tick at t = 0 only
    np.testing.assert_allclose(band.GetOutputPort("slip_vibration").Eval(context),
                               slip_band(log, BAND_HZ, WINDOW_S, RATE_HZ)[samples - 1],
                               rtol=1e-12, atol=1e-15)


def test_slip_band_passes_the_vibration_and_removes_the_sway():
    band = slip_band(_vibration_log(), BAND_HZ, WINDOW_S, RATE_HZ)
    # Before 0.2 s the left pad only sways at 30 Hz, well below the 80 Hz corner; after,
    # the 200 Hz vibration's RMS, 2 / sqrt(2) = 1.41 m/s^2, passes (about 1.07 x at 2.5
    # times a second-order Butterworth corner: within 15 %).
    assert band[150:200, 0].max() < 0.15
    assert band[260:, 0].mean() == pytest.approx(2.0 / np.sqrt(2.0), rel=0.15)


FALSE_MARGIN, DEADLINE = 0.01, 0.5  # s, detection_quality's rules


@pytest.mark.parametrize("fire_s, physical_s, kind, latency", [
    (None, 1.0, "missed", None),
    (0.5, None, "false", None),  # a span without the situation: any firing is false
    (0.985, 1.0, "false", None),  # earlier than the margin before the event
    (0.995, 1.0, "detected", -0.005),  # within the margin: detected, slightly early
    (1.2, 1.0, "detected", 0.2),
    (1.5, 1.0, "detected", 0.5),  # on the deadline
    (1.51, 1.0, "missed", None),  # after it
])
def test_first_firings_are_classified_by_the_detection_rules(fire_s, physical_s, kind,
                                                            latency):
    outcome = classify_first_firing(fire_s, physical_s)
    assert outcome.kind == kind
    if latency is None:
        assert outcome.latency_s is None
    else:
        assert outcome.latency_s == pytest.approx(latency, abs=1e-12)


SPAN = SituationSpan("test", "hold_avoid", armed_from_s=0.1, armed_until_s=0.35,
                     physical_s=0.2)


def test_heuristic_hit_fires_at_the_first_ra_above_its_level_inside_the_span():
    log = _vibration_log()
    # The left RA is |0.5 sin(30 Hz)| before 0.2 s (at most 0.5) and up to 2.5 after.
    assert heuristic_hit_time(log, SPAN, hit_ra_mps2=0.6) == pytest.approx(
        log.t_ra[np.flatnonzero((log.t_ra >= 0.2) & (log.ra[:, 0] > 0.6))[0]])
    assert heuristic_hit_time(log, SPAN, hit_ra_mps2=3.0) is None
    before = SituationSpan("test", "hold_avoid", 0.0, 0.19, None)
    assert heuristic_hit_time(log, before, hit_ra_mps2=0.6) is None


def test_heuristic_slip_fires_once_the_band_stayed_above_its_level_for_slip_s():
    log = _vibration_log()
    config = types.SimpleNamespace(slip_band_hz=BAND_HZ, slip_window_s=WINDOW_S,
                                   slip_vibration_mps2=1.0, slip_s=0.02)
    fired = heuristic_slip_time(log, SPAN, config, RATE_HZ)
    band = slip_band(log, BAND_HZ, WINDOW_S, RATE_HZ).max(axis=1)
    k = int(np.flatnonzero(log.t_ra == fired)[0])
    onset = int(np.flatnonzero(band[:k + 1] <= 1.0)[-1]) + 1  # above from here to the firing
    # It fires once above for slip_s: 20 ms after the onset, or one 1 kHz sample later when
    # the times' round-off puts the 20 ms difference a hair under.
    assert 0.02 - 1e-9 <= log.t_ra[k] - log.t_ra[onset] <= 0.021 + 1e-9
    assert log.t_ra[onset] >= 0.2  # the vibration's, not the sway's
    config.slip_vibration_mps2 = 5.0  # never reached
    assert heuristic_slip_time(log, SPAN, config, RATE_HZ) is None


def test_heuristic_slip_starts_over_when_the_band_drops_below_its_level():
    # A 10 ms burst at 0.2 s (shorter than slip_s), quiet, then vibration from 0.26 s on:
    # only the second counts, so the trigger fires 20 ms after it, not after the burst.
    log = _vibration_log()
    t = log.t_ra
    log.pad_acceleration[:, 2] *= ((t < 0.21) | (t >= 0.26))
    config = types.SimpleNamespace(slip_band_hz=BAND_HZ, slip_window_s=WINDOW_S,
                                   slip_vibration_mps2=1.0, slip_s=0.02)
    fired = heuristic_slip_time(log, SPAN, config, RATE_HZ)
    assert 0.26 + 0.02 <= fired <= 0.26 + 0.02 + 0.01  # the band's 10 ms window to rise
