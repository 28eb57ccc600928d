"""The RA envelope (events/ra_envelope.py): the filter, the enveloped events, the live system
and its place ahead of the matcher."""

import math

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, LogVectorOutput

from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.event_matcher import EventMatcherConfig, add_event_matcher
from tegrasp_drake.events.ra_envelope import (
    RaEnvelope, envelope_coefficient, enveloped_event, ra_envelope)
from tegrasp_drake.events.memorized_event import MemorizedEvent


def synthetic_event() -> MemorizedEvent:
    """A contact at 0.25 s of a 0.5 s window: an SA step, an RA spike with a short ring."""
    t_sa = np.arange(50) / 100.0
    t_ra = np.arange(500) / 1000.0
    sa = np.where(t_sa >= 0.25, 1.0, 0.0)
    ra = np.where(t_ra >= 0.25, np.exp(-(t_ra - 0.25) / 0.002), 0.0)
    return MemorizedEvent(object_name="box", transition="reach_load", sa=np.array([sa, sa]),
                          ra=np.array([ra, ra]), sa_rate_hz=100.0, ra_rate_hz=1000.0)


def test_coefficient_is_the_impulse_invariant_first_order_low_pass():
    # f_c = 2 Hz at 1 kHz: a = 1 - exp(-4 pi / 1000).
    assert envelope_coefficient(2.0, 1000.0) == pytest.approx(0.012488, abs=1e-6)


@pytest.mark.parametrize("cutoff_hz", [0.0, -1.0, 500.0])
def test_cutoff_outside_the_band_is_refused(cutoff_hz):
    with pytest.raises(ValueError, match="RA envelope cutoff"):
        envelope_coefficient(cutoff_hz, 1000.0)


def test_a_spike_becomes_an_exponential_of_the_filter_time_constant():
    spike = np.zeros(200)
    spike[10] = 1.0
    a = envelope_coefficient(2.0, 1000.0)
    out = ra_envelope(spike, 2.0, 1000.0)[0]
    np.testing.assert_allclose(out[:10], 0.0)
    np.testing.assert_allclose(out[10:], a * (1.0 - a) ** np.arange(190))
    # one time constant (1 / (2 pi 2 Hz) = 80 ms) after the spike: 1/e of the peak
    assert out[10 + 80] / out[10] == pytest.approx(math.exp(-1.0), rel=0.01)


def test_a_window_starts_in_the_steady_state_of_its_first_sample():
    np.testing.assert_allclose(ra_envelope(np.full(50, 3.0), 2.0, 1000.0), 3.0)


def test_enveloped_event_filters_ra_only_and_stays_max_normalised():
    event = synthetic_event()
    enveloped = enveloped_event(event, 2.0)
    np.testing.assert_array_equal(enveloped.sa, event.sa)
    np.testing.assert_allclose(np.abs(enveloped.ra).max(axis=1), 1.0)
    expected = ra_envelope(event.ra, 2.0, event.ra_rate_hz)
    np.testing.assert_allclose(enveloped.ra, expected / expected.max(axis=1, keepdims=True))


def test_envelope_lets_a_spike_template_match_a_ringing_contact():
    # A one-sample spike memorized; the live contact rings for 8 ms and the squeeze holds
    # the reading for 60 ms: raw Eq. 3 is far below the RA threshold, enveloped it is not.
    n, rate = 500, 1000.0
    template = np.zeros(n)
    template[250] = 1.0
    t = np.arange(n) / rate
    live = np.where(t >= 0.2, np.exp(-(t - 0.2) / 0.008), 0.0)
    live += np.where((t >= 0.2) & (t < 0.26), 0.5, 0.0)
    raw = event_scores_reference([live], [template], 0.25)[0]
    enveloped = event_scores_reference([ra_envelope(live, 2.0, rate)[0]],
                                       [ra_envelope(template, 2.0, rate)[0]], 0.25)[0]
    assert raw < 0.5
    assert enveloped > 0.9


def test_live_envelope_matches_the_window_filter_sample_by_sample():
    builder = DiagramBuilder()
    source = builder.AddSystem(ConstantVectorSource([1.0, 2.0, 10.0, 4.0]))
    envelope = builder.AddSystem(RaEnvelope(cutoff_hz=2.0, ra_rate_hz=1000.0))
    builder.Connect(source.get_output_port(), envelope.GetInputPort("channels"))
    log = LogVectorOutput(envelope.GetOutputPort("channels"), builder, 1e-3)
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(0.0495)
    data = log.FindLog(simulator.get_context()).data()
    np.testing.assert_allclose(data[:2], [[1.0] * data.shape[1], [2.0] * data.shape[1]])
    # From a zero state, a constant input u reads u (1 - (1 - a)^(k + 1)) at tick k.
    a = envelope_coefficient(2.0, 1000.0)
    k = np.arange(data.shape[1])
    np.testing.assert_allclose(data[2], 10.0 * (1.0 - (1.0 - a) ** (k + 1)), rtol=1e-12)
    np.testing.assert_allclose(data[3], 4.0 * (1.0 - (1.0 - a) ** (k + 1)), rtol=1e-12)


def test_the_envelope_is_off_by_default_and_added_ahead_of_the_matcher_when_set():
    assert EventMatcherConfig().ra_envelope_hz == 0.0
    events = {"reach_load": synthetic_event()}
    for cutoff_hz, expected in ((0.0, False), (2.0, True)):
        builder = DiagramBuilder()
        source = builder.AddSystem(ConstantVectorSource(np.zeros(4)))
        add_event_matcher(builder, events, EventMatcherConfig(
            sa_rate_hz=events["reach_load"].sa_rate_hz, ra_envelope_hz=cutoff_hz),
            channels=source.get_output_port())
        assert builder.HasSubsystemNamed("ra_envelope") is expected
