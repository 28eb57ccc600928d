"""The RA noise floor (events/ra_noise_floor.py): the rule for k, the enveloped noise's
spread, the live floor, and the matcher's RA scores gated by it."""

import math

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import (ConstantVectorSource, LogVectorOutput,
                                        TrajectorySource)
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.events.event_matcher import EventMatcherConfig, add_event_matcher
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.ra_envelope import envelope_coefficient, ra_envelope
from tegrasp_drake.events.ra_noise_floor import (
    FALSE_ALARM_PER_TRIAL, TRIAL_HORIZON_S, RaNoiseFloor, floor_sigmas, noise_floor)
from tegrasp_drake.control.controller_config import EventTriggeredConfig


def test_k_is_the_gaussian_tail_of_the_false_alarm_rate_over_a_trials_samples():
    samples = int(TRIAL_HORIZON_S * 1000.0 * 2)
    k = floor_sigmas(FALSE_ALARM_PER_TRIAL, samples)
    assert samples * 0.5 * math.erfc(k / math.sqrt(2.0)) == pytest.approx(
        FALSE_ALARM_PER_TRIAL, rel=1e-6)
    assert k == pytest.approx(5.39, abs=0.005)


def test_the_controllers_documented_k_follows_the_rule():
    # The value the controller's comment and the remedy spec carry (docs/transfer.md).
    assert floor_sigmas(FALSE_ALARM_PER_TRIAL, int(TRIAL_HORIZON_S * 1000.0 * 2)) == \
        pytest.approx(5.39, abs=0.005)
    assert EventTriggeredConfig().matching.ra_noise_floor_sigmas == 0.0  # off by default


def test_the_floor_is_the_enveloped_quiet_mean_plus_k_deviations():
    quiet = np.array([[1.0, 3.0] * 50, [2.0] * 100])
    enveloped = ra_envelope(quiet, 2.0, 1000.0)
    np.testing.assert_allclose(
        noise_floor(quiet, sigmas=5.0, envelope_hz=2.0, rate_hz=1000.0),
        enveloped.mean(axis=1) + 5.0 * enveloped.std(axis=1))
    # A constant reading has no spread: its floor is itself. Without an envelope the
    # alternating one's is mean 2 + 5 x sd 1.
    assert noise_floor(quiet[1], sigmas=5.0, envelope_hz=2.0, rate_hz=1000.0)[0] == \
        pytest.approx(2.0)
    assert noise_floor(quiet[0], sigmas=5.0, envelope_hz=0.0, rate_hz=1000.0)[0] == \
        pytest.approx(7.0)


def test_white_noise_spreads_less_after_the_envelope_and_slow_drift_does_not():
    # Why s_w is measured after the filter: white noise shrinks by sqrt(a / (2 - a)), a
    # drift slower than the cutoff passes whole.
    rng = np.random.default_rng(600)
    white = np.abs(rng.normal(0.0, 0.05, 200_000))
    a = envelope_coefficient(2.0, 1000.0)
    assert ra_envelope(white, 2.0, 1000.0)[0].std() == pytest.approx(
        white.std() * math.sqrt(a / (2.0 - a)), rel=0.1)
    drift = 0.05 * np.sin(2.0 * math.pi * 0.2 * np.arange(20_000) / 1000.0)
    assert ra_envelope(drift, 2.0, 1000.0)[0].std() == pytest.approx(drift.std(), rel=0.05)


def alternating_ra_source(builder, low: float, high: float, end_s: float):
    """Channels [0, 0, ra, ra]: RA alternating low, high every 1 ms sample."""
    times = np.arange(0.0, end_s, 1e-3)
    ra = np.where(np.arange(len(times)) % 2 == 0, low, high)
    values = np.vstack([np.zeros_like(ra), np.zeros_like(ra), ra, ra])
    return builder.AddSystem(TrajectorySource(PiecewisePolynomial.ZeroOrderHold(
        times - 1e-9, values)))


def live_floor(envelope_hz: float):
    """(times, floors (2, T)) of a RaNoiseFloor with k = 4 and a 0.2 s quiet period, fed an
    RA alternating 1 and 3 m/s^2; and the quiet samples it measured."""
    builder = DiagramBuilder()
    source = alternating_ra_source(builder, 1.0, 3.0, 1.0)
    floor = builder.AddSystem(RaNoiseFloor(sigmas=4.0, quiet_s=0.2, ra_rate_hz=1000.0,
                                           envelope_hz=envelope_hz))
    builder.Connect(source.get_output_port(), floor.GetInputPort("channels"))
    log = LogVectorOutput(floor.GetOutputPort("ra_floor"), builder, 0.05)
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(0.5)
    data = log.FindLog(simulator.get_context())
    return data.sample_times(), data.data(), np.tile([1.0, 3.0], 100)


def test_the_live_floor_is_infinite_until_the_quiet_period_is_measured():
    times, floors, _ = live_floor(0.0)
    assert np.all(np.isinf(floors[:, times < 0.2 - 1e-9]))
    np.testing.assert_allclose(floors[:, times > 0.2 + 1e-9], 2.0 + 4.0 * 1.0)


def test_the_live_floor_is_the_floor_of_the_quiet_samples():
    times, floors, quiet = live_floor(2.0)
    expected = noise_floor(quiet, sigmas=4.0, envelope_hz=2.0, rate_hz=1000.0)[0]
    np.testing.assert_allclose(floors[:, times > 0.2 + 1e-9], expected, rtol=1e-9)


def step_event() -> MemorizedEvent:
    """Place-Unload: flat SA, an RA decay from the middle of the window."""
    t_ra = np.arange(500) / 1000.0
    ra = np.where(t_ra >= 0.25, np.exp(-(t_ra - 0.25) / 0.08), 0.0)
    sa = np.ones(50)
    return MemorizedEvent(object_name="box", transition="place_unload",
                          sa=np.array([sa, sa]), ra=np.array([ra, ra]), sa_rate_hz=100.0,
                          ra_rate_hz=1000.0)


def ra_scores_of_a_decay(height: float, sigmas: float, block_s: float = 0.0) -> np.ndarray:
    """The matcher's RA scores at 1.4 s with the event's own decay of `height` [m/s^2]
    starting at 1.15 s on a quiet RA of 0.04 +- 0.01 (the floor's quiet period: 1 s; no
    envelope, so the floor is 0.04 + k 0.01)."""
    builder = DiagramBuilder()
    times = np.arange(0.0, 1.6, 1e-3)
    ra = 0.04 + 0.01 * np.where(np.arange(len(times)) % 2 == 0, -1.0, 1.0)
    ra = ra + np.where(times >= 1.15, height * np.exp(-(times - 1.15) / 0.08), 0.0)
    values = np.vstack([np.ones_like(ra), np.ones_like(ra), ra, ra])
    source = builder.AddSystem(TrajectorySource(PiecewisePolynomial.ZeroOrderHold(
        times - 1e-9, values)))
    event = step_event()
    matcher = add_event_matcher(builder, {"place_unload": event}, EventMatcherConfig(
        sa_rate_hz=100.0, ra_noise_floor_sigmas=sigmas, ra_noise_quiet_s=1.0,
        block_s=block_s),
        channels=source.get_output_port())
    expected = builder.AddSystem(ConstantVectorSource([0.0]))
    builder.Connect(expected.get_output_port(), matcher.GetInputPort("expected_event"))
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(1.4)
    return matcher.GetOutputPort("scores").Eval(
        matcher.GetMyContextFromRoot(simulator.get_context()))[2:]


def test_an_ra_window_within_the_noise_scores_zero_and_one_above_it_counts():
    # Floor: 0.04 + 5 x 0.01 = 0.09. A decay of 0.03 on the noise peaks at 0.08: gated.
    assert ra_scores_of_a_decay(0.03, 5.0) == pytest.approx([0.0, 0.0])
    # Without the floor the same window scores high: Eq. 3 is blind to amplitude.
    assert np.all(ra_scores_of_a_decay(0.03, 0.0) > 0.5)
    # A decay of 1.0 rises far above the floor and keeps its score.
    np.testing.assert_allclose(ra_scores_of_a_decay(1.0, 5.0), ra_scores_of_a_decay(1.0, 0.0))
    assert np.all(ra_scores_of_a_decay(1.0, 5.0) > 0.9)


def test_the_floor_gates_a_matcher_that_takes_the_film_in_blocks_alike():
    assert ra_scores_of_a_decay(0.03, 5.0, block_s=0.01) == pytest.approx([0.0, 0.0])
    assert np.all(ra_scores_of_a_decay(1.0, 5.0, block_s=0.01) > 0.9)


def test_the_floor_is_added_ahead_of_the_matcher_only_when_set():
    events = {"place_unload": step_event()}
    for sigmas, expected in ((0.0, False), (5.39, True)):
        builder = DiagramBuilder()
        source = builder.AddSystem(ConstantVectorSource(np.zeros(4)))
        matcher = add_event_matcher(builder, events, EventMatcherConfig(
            sa_rate_hz=100.0, ra_noise_floor_sigmas=sigmas), channels=source.get_output_port())
        assert builder.HasSubsystemNamed("ra_noise_floor") is expected
        assert matcher.HasInputPort("ra_floor") is expected
