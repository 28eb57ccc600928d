"""The RA envelope (beyond the paper): memorized and live RA windows through the same
first-order low-pass before Eq. 3, so that events memorized with one vibration transducer
match on another (docs/transfer.md, "A remedy: the RA envelope"). y[k] = y[k-1] +
a (u[k] - y[k-1]), a = 1 - exp(-2 pi f_c / f_s); a memorized window starts from its first
sample as the steady state, the live filter from zero."""

import dataclasses
import math

import numpy as np
from pydrake.systems.framework import BasicVector, LeafSystem
from scipy.signal import lfilter

from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.tactile.max_normalization import normalize_by_max


def envelope_coefficient(cutoff_hz: float, rate_hz: float) -> float:
    """a of y[k] = y[k-1] + a (u[k] - y[k-1]) for cutoff_hz in (0, rate_hz / 2) [Hz]."""
    if not 0.0 < cutoff_hz < rate_hz / 2.0:
        raise ValueError(f"RA envelope cutoff {number_text(cutoff_hz)} Hz must lie between 0 "
                         f"and half the RA rate ({number_text(rate_hz / 2.0)} Hz); 0 switches "
                         "the envelope off")
    return 1.0 - math.exp(-2.0 * math.pi * cutoff_hz / rate_hz)


def ra_envelope(windows: np.ndarray, cutoff_hz: float, rate_hz: float) -> np.ndarray:
    """Each row of `windows` (time along the last axis, sampled at rate_hz) low-passed at
    cutoff_hz, starting from its first sample as the steady state; same units."""
    a = envelope_coefficient(cutoff_hz, rate_hz)
    windows = np.atleast_2d(np.asarray(windows, dtype=float))
    filtered, _ = lfilter([a], [1.0, a - 1.0], windows, axis=-1,
                          zi=(1.0 - a) * windows[..., :1])
    return filtered


def enveloped_event(event: MemorizedEvent, cutoff_hz: float) -> MemorizedEvent:
    """`event` with its RA windows low-passed at cutoff_hz [Hz] and max-normalised again."""
    return dataclasses.replace(event, ra=normalize_by_max(
        ra_envelope(event.ra, cutoff_hz, event.ra_rate_hz)))


class RaEnvelope(LeafSystem):
    """The live side of the RA envelope: the four channels with the RA ones low-passed at
    cutoff_hz, updated every 1 / ra_rate_hz; the output uses the present input, so a matcher on
    the same ticks reads the envelope of the samples it would have read raw.

    .. pydrake_system::

        name: RaEnvelope
        input_ports:
        - channels
        output_ports:
        - channels

    Ports:
        channels (input): [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2).
        channels (output): the same, RA low-passed at cutoff_hz; SA passed through.
    """

    def __init__(self, *, cutoff_hz: float, ra_rate_hz: float):
        super().__init__()
        self._a = envelope_coefficient(cutoff_hz, ra_rate_hz)
        self._ra = list(RA_CHANNELS)
        self._input = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._previous = self.DeclareDiscreteState(len(RA_CHANNELS))  # y[k-1], zero at start
        self.DeclarePeriodicDiscreteUpdateEvent(1.0 / ra_rate_hz, 0.0, self._update)
        self.DeclareVectorOutputPort("channels", BasicVector(len(CHANNEL_NAMES)),
                                     self._calc_channels)

    def _filtered(self, context) -> np.ndarray:
        previous = context.get_discrete_state(self._previous).value()
        return previous + self._a * (self._input.Eval(context)[self._ra] - previous)

    def _update(self, context, discrete_state):
        discrete_state.get_mutable_vector(self._previous).SetFromVector(self._filtered(context))

    def _calc_channels(self, context, output):
        channels = np.array(self._input.Eval(context), dtype=float)
        channels[self._ra] = self._filtered(context)
        output.SetFromVector(channels)


def add_ra_envelope(builder, channels, *, cutoff_hz: float, ra_rate_hz: float):
    """Adds an RaEnvelope (`ra_envelope`) fed by the output port `channels`; returns its output."""
    envelope = builder.AddNamedSystem("ra_envelope", RaEnvelope(
        cutoff_hz=cutoff_hz, ra_rate_hz=ra_rate_hz))
    builder.Connect(channels, envelope.GetInputPort("channels"))
    return envelope.GetOutputPort("channels")


def ra_enveloped(builder, events, channels, config):
    """(events, channels) with the RA envelope at config.ra_envelope_hz [Hz] on both: the
    events' RA windows low-passed, `channels` through an RaEnvelope added to `builder`."""
    if channels is None:
        raise ValueError("the RA envelope needs the channels' output port to filter "
                         "(add_event_matcher(..., channels=PORT))")
    enveloped = {transition: enveloped_event(event, config.ra_envelope_hz)
                 for transition, event in events.items()}
    return enveloped, add_ra_envelope(builder, channels, cutoff_hz=config.ra_envelope_hz,
                                      ra_rate_hz=config.ra_rate_hz)
