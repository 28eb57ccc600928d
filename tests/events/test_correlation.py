"""Eq. 3 scores: the reference, the contrast gate, and the streaming core against both."""

import math

import numpy as np
import pytest

from tegrasp_drake.events.correlation import (
    event_scores_reference, max_normalized_xcorr_reference, window_contrast)
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.tactile.sampling import resample_window, samples_per_window
from tegrasp_drake.tactile.sliding_window import SlidingWindow, SlidingWindowState
from tegrasp_drake.events.streaming_correlation import StreamingCorrelator
from tegrasp_drake.events.transitions import NO_EVENT

MIN_CONTRAST = 0.25


def contact_step(length=50, onset=25, rise=12):
    """SA-like window: zero, then a smooth rise to a plateau."""
    u = np.clip((np.arange(length) - onset) / rise, 0.0, 1.0)
    return u * u * (3.0 - 2.0 * u)


def ring_down(length=500, onset=250, decay=15.0):
    """RA-like window: a rectified decaying ringing after the onset."""
    k = np.arange(length) - onset
    return np.where(k >= 0, np.exp(-np.maximum(k, 0) / decay) * np.abs(np.cos(1.13 * k)), 0.0)


def test_reference_matches_hand_computed_correlations():
    # R_XY(n) = sum_k x[k+n] y[k]; for [1,2,3] vs [3,2,1] the lags -2..2 give 1, 4, 10, 12, 9.
    assert max_normalized_xcorr_reference([1.0, 2.0, 3.0], [3.0, 2.0, 1.0]) == (
        pytest.approx(12.0 / 14.0, abs=1e-15))
    assert max_normalized_xcorr_reference([1.0, 1.0], [1.0, 0.0]) == (
        pytest.approx(1.0 / math.sqrt(2.0), abs=1e-15))


def test_reference_leaves_the_timing_free():
    burst = ring_down(onset=100)
    shifted = ring_down(onset=260)  # 160 samples later; both decay to ~1e-7 in the window
    assert max_normalized_xcorr_reference(shifted, burst) == pytest.approx(1.0, abs=1e-9)


def test_reference_is_scale_invariant():
    rng = np.random.default_rng(1)
    live, template = rng.random(80), contact_step(80, 30)
    assert max_normalized_xcorr_reference(37.0 * live, template) == pytest.approx(
        max_normalized_xcorr_reference(live, template), abs=1e-14)


def test_all_zero_window_scores_zero():
    assert max_normalized_xcorr_reference(np.zeros(50), contact_step()) == 0.0
    scores = event_scores_reference([np.zeros(50)], [contact_step()], MIN_CONTRAST)
    np.testing.assert_array_equal(scores, [0.0])


def test_constant_window_scores_zero_although_eq3_alone_rates_it_high():
    template = contact_step(onset=3)  # a step whose plateau fills most of the window
    constant = np.full(50, 4.0)
    assert max_normalized_xcorr_reference(constant, template) > 0.9  # the false-trigger risk
    np.testing.assert_array_equal(
        event_scores_reference([constant], [template], MIN_CONTRAST), [0.0])


def test_holding_a_noisy_grip_scores_zero_against_a_contact():
    rng = np.random.default_rng(2)
    holding = 4.0 + 0.05 * rng.standard_normal(50)  # 4 N grip, 0.05 N sensor noise
    assert window_contrast(holding)[0] < MIN_CONTRAST
    np.testing.assert_array_equal(
        event_scores_reference([holding], [contact_step()], MIN_CONTRAST), [0.0])


def test_a_flat_template_channel_accepts_a_flat_live_window():
    scores = event_scores_reference([np.full(50, 2.0)], [np.ones(50)], MIN_CONTRAST)
    np.testing.assert_allclose(scores, [1.0], atol=1e-15)


def test_noise_floor_scores_low_against_an_impact():
    rng = np.random.default_rng(3)
    noise = np.linalg.norm(0.2 * rng.standard_normal((3, 500)), axis=0)  # |a|, 0.2 m/s^2/axis
    score = event_scores_reference([noise], [ring_down()], MIN_CONTRAST)[0]
    assert 0.0 < score < 0.5


def random_stream(rng, length, n_channels):
    """Noise with bursts of very different sizes, negative stretches and all-zero gaps."""
    samples = rng.standard_normal((length, n_channels))
    samples[::97] *= 1e3
    samples[300:420] = 0.0
    samples[700:760] = np.abs(samples[700:760]) * 1e-4
    samples[900:1000] = 5.0  # constant
    return samples


@pytest.mark.parametrize("flat_needs_flat", [False, True])
@pytest.mark.parametrize("n_channels, length, slack", [(2, 50, 10), (2, 500, 100),
                                                       (4, 120, 7)])
def test_streaming_core_equals_the_reference(n_channels, length, slack, flat_needs_flat):
    rng = np.random.default_rng(length)
    templates = [normalize_by_max(rng.random((n_channels, length)) ** 3),
                 np.vstack([contact_step(length, length // 2, 5)] * n_channels),
                 np.vstack([np.ones(length)] + [contact_step(length, 3, 2)] * (n_channels - 1))]
    correlator = StreamingCorrelator(templates, min_contrast=MIN_CONTRAST, slack=slack,
                                     flat_needs_flat=flat_needs_flat)
    state = correlator.initial_state()
    largest_error = 0.0
    for tick, samples in enumerate(random_stream(rng, 1300, n_channels)):
        event = (tick // 230) % 4 - 1  # cycles NO_EVENT, 0, 1, 2
        scores = correlator.push(state, samples, event)
        if tick < length - 1 or event == NO_EVENT:
            np.testing.assert_array_equal(scores, 0.0)
            continue
        window = correlator.window(state)
        expected = event_scores_reference(window, templates[event], MIN_CONTRAST,
                                          flat_needs_flat)
        largest_error = max(largest_error, np.max(np.abs(scores - expected)))
        assert correlator.active_event(state) == event
    assert largest_error <= 1e-9


def test_streaming_core_scores_zero_until_the_window_is_full():
    template = np.vstack([contact_step()] * 2)
    correlator = StreamingCorrelator([template], min_contrast=MIN_CONTRAST, slack=5)
    state = correlator.initial_state()
    for value in template.T[:-1]:
        np.testing.assert_array_equal(correlator.push(state, value, 0), 0.0)
    np.testing.assert_allclose(correlator.push(state, template[:, -1], 0), 1.0, atol=1e-12)


def test_streaming_core_rejects_an_unknown_event():
    correlator = StreamingCorrelator([np.ones((2, 10))], min_contrast=MIN_CONTRAST, slack=2)
    with pytest.raises(ValueError, match="event index 1"):
        correlator.push(correlator.initial_state(), np.zeros(2), 1)


def test_streaming_core_refuses_a_state_it_cannot_update_in_place():
    correlator = StreamingCorrelator([np.vstack([contact_step(10, 5, 2)] * 2)],
                                     min_contrast=MIN_CONTRAST, slack=2)
    strided = np.zeros(2 * correlator.size)[::2]  # BLAS would update a copy
    strided[0] = NO_EVENT
    with pytest.raises(ValueError, match="C-contiguous"):
        for value in np.random.default_rng(0).random((12, 2)):
            correlator.push(strided, value, 0)


def test_sliding_window_keeps_the_last_samples_oldest_first():
    layout = SlidingWindowState(SlidingWindow(n_channels=2, length=5, slack=3))
    state = np.zeros(layout.size)
    for value in range(1, 38):
        layout.push(state, [value, -value])
    np.testing.assert_array_equal(layout.current(state), [[33, 34, 35, 36, 37],
                                                          [-33, -34, -35, -36, -37]])


def test_a_push_reports_where_the_window_is_and_whether_it_is_full():
    layout = SlidingWindowState(SlidingWindow(n_channels=2, length=5, slack=3))
    state = np.zeros(layout.size)
    for value in range(1, 12):
        rows, offset, full = layout.push(state, [value, -value])
        assert full == (value >= 5)
        window = layout.current(state)
        np.testing.assert_array_equal(rows[:, offset:offset + 5], window)
        np.testing.assert_array_equal(window[:, -1], [value, -value])
        assert window[0, 0] == (value - 4 if full else 0.0)  # zero until full


def test_resampling_holds_values_when_upsampling_and_averages_when_downsampling():
    np.testing.assert_allclose(resample_window([[1.0, 3.0]], 6), [[1, 1, 1, 3, 3, 3]])
    np.testing.assert_allclose(resample_window([np.arange(10.0)], 2), [[2.0, 7.0]])


def test_samples_per_window_requires_a_whole_number_of_samples():
    assert samples_per_window(0.5, 100.0) == 50
    with pytest.raises(ValueError, match="integer"):
        samples_per_window(0.5, 333.0)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_a_non_finite_sample_is_missing_for_one_window_and_poisons_nothing(bad):
    """One NaN or inf sample must not keep the streaming state wrong after it leaves the
    window, nor give NaN scores: the sample enters as the channel's previous one, the channel scores 0 while it is in the window, and from
    the tick it leaves, the scores are those of the stream without it, to round-off."""
    length, at = 50, 400
    rng = np.random.default_rng(3)
    template = normalize_by_max(rng.random((2, length)) ** 3)
    stream = random_stream(rng, 700, 2)
    held = stream.copy()
    held[at, 0] = stream[at - 1, 0]  # what "missing" enters the window as
    glitched = stream.copy()
    glitched[at, 0] = bad
    with_glitch = StreamingCorrelator([template], min_contrast=MIN_CONTRAST, slack=10)
    without = StreamingCorrelator([template], min_contrast=MIN_CONTRAST, slack=10)
    state, clean_state = with_glitch.initial_state(), without.initial_state()
    for tick in range(len(stream)):
        scores = with_glitch.push(state, glitched[tick], 0).copy()
        expected = without.push(clean_state, held[tick], 0)
        assert np.all(np.isfinite(scores)), tick
        if at <= tick < at + length:
            assert scores[0] == 0.0, tick  # the missing sample is in the window
            assert scores[1] == pytest.approx(expected[1], abs=1e-12), tick
        else:
            np.testing.assert_allclose(scores, expected, atol=1e-9, err_msg=str(tick))
        if tick == at + length:  # recovered within one window of the glitch
            assert scores[0] != 0.0


def test_a_flat_template_scores_a_rising_window_only_without_the_flat_window_option():
    """A window whose last 85 % is a plateau against a flat template: Eq. 3 gives
    sqrt(0.85) = 0.92; with flat_template_needs_flat_window it needs a flat window."""
    flat = np.ones(54)
    rising = np.concatenate([np.linspace(0.0, 1.0, 8), np.ones(46)])
    assert event_scores_reference([rising], [flat], 0.25)[0] > 0.9
    assert event_scores_reference([rising], [flat], 0.25, flat_needs_flat=True)[0] == 0.0
    settled = 1.0 + 0.01 * np.sin(np.arange(54))
    assert event_scores_reference([settled], [flat], 0.25, flat_needs_flat=True)[0] > 0.99
    # A template with a change is gated as before.
    step = np.concatenate([np.zeros(27), np.ones(27)])
    assert (event_scores_reference([step], [step], 0.25, flat_needs_flat=True)[0]
            == event_scores_reference([step], [step], 0.25)[0])
