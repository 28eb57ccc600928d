"""The RA noise floor (beyond the paper): an RA window carries no event unless its peak
rises above its channel's noise, measured while the pads are untouched. Over the first
`quiet_s` each low-passed RA channel gives the floor m + k s (+inf before), k = Q^-1(alpha / N)
a union bound over a trial's N RA samples. Reasoning: docs/transfer.md, "The RA noise floor"."""

import math

import numpy as np
from pydrake.systems.framework import BasicVector, LeafSystem
from scipy.stats import norm

from tegrasp_drake.events.ra_envelope import envelope_coefficient, ra_envelope
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS
from tegrasp_drake.rig.number_text import number_text

# The rule that sets k (module docstring): alpha per trial, the trial's horizon [s].
FALSE_ALARM_PER_TRIAL = 1e-3
TRIAL_HORIZON_S = 14.0


def floor_sigmas(false_alarm_per_trial: float, samples_per_trial: int) -> float:
    """k such that noise alone crosses m + k s_w with probability at most
    false_alarm_per_trial over samples_per_trial samples (union bound, Gaussian tail)."""
    if not 0.0 < false_alarm_per_trial < 1.0 or samples_per_trial < 1:
        raise ValueError("the false-alarm probability must lie in (0, 1) and the samples "
                         "per trial be at least 1")
    return float(norm.isf(false_alarm_per_trial / samples_per_trial))


def rule_sigmas(ra_rate_hz: float) -> float:
    """The rule's k at an RA rate [Hz], over TRIAL_HORIZON_S of both channels; 5.39 at 1 kHz."""
    return floor_sigmas(FALSE_ALARM_PER_TRIAL,
                        round(TRIAL_HORIZON_S * ra_rate_hz * len(RA_CHANNELS)))


def noise_floor(quiet: np.ndarray, *, sigmas: float, envelope_hz: float,
                rate_hz: float) -> np.ndarray:
    """Per row of `quiet` (raw RA samples of the quiet period at rate_hz [Hz], time along the
    last axis) the floor m_w + k s_w of its envelope at envelope_hz [Hz] (0: none)."""
    quiet = np.atleast_2d(np.asarray(quiet, dtype=float))
    if envelope_hz:
        quiet = ra_envelope(quiet, envelope_hz, rate_hz)
    return quiet.mean(axis=-1) + sigmas * quiet.std(axis=-1)


class RaNoiseFloor(LeafSystem):
    """Each RA channel's noise floor, measured on the live stream's first quiet_s [s]: the
    low-passed RA's running count, sum and sum of squares; the output is +inf until then, the
    floor (`noise_floor`) afterwards.

    .. pydrake_system::

        name: RaNoiseFloor
        input_ports:
        - channels
        output_ports:
        - ra_floor

    Ports:
        channels (input): [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2), RA raw.
        ra_floor (output): [left, right] floor [m/s^2] of the RA windows' peaks, in the units
            of the windows the matcher scores (enveloped when envelope_hz > 0).
    """

    def __init__(self, *, sigmas: float, quiet_s: float, ra_rate_hz: float,
                 envelope_hz: float = 0.0):
        super().__init__()
        if not sigmas > 0.0 or not quiet_s * ra_rate_hz >= 2.0:
            raise ValueError(f"the RA noise floor needs sigmas > 0 (got {number_text(sigmas)}) "
                             "and a quiet period of at least 2 RA samples (got "
                             f"{number_text(quiet_s)} s)")
        self._sigmas = sigmas
        self._quiet_samples = int(math.floor(quiet_s * ra_rate_hz + 1e-9))
        self._a = envelope_coefficient(envelope_hz, ra_rate_hz) if envelope_hz else 1.0
        self._input = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        n = len(RA_CHANNELS)
        # [count, filter value, sum, sum of squares], the last three per RA channel
        self._sums = self.DeclareDiscreteState(1 + 3 * n)
        self.DeclarePeriodicDiscreteUpdateEvent(1.0 / ra_rate_hz, 0.0, self._update)
        self.DeclareVectorOutputPort("ra_floor", BasicVector(n), self._calc_floor,
                                     prerequisites_of_calc={self.xd_ticket()})

    def _update(self, context, discrete_state):
        sums = context.get_discrete_state(self._sums).value()
        count, n = sums[0], len(RA_CHANNELS)
        if count >= self._quiet_samples:
            return
        ra = np.asarray(self._input.Eval(context), dtype=float)[list(RA_CHANNELS)]
        previous = sums[1:1 + n] if count > 0 else ra  # the first sample: steady state
        filtered = previous + self._a * (ra - previous)
        updated = sums.copy()
        updated[0] = count + 1.0
        updated[1:1 + n] = filtered
        updated[1 + n:1 + 2 * n] += filtered
        updated[1 + 2 * n:] += filtered * filtered
        discrete_state.get_mutable_vector(self._sums).SetFromVector(updated)

    def _calc_floor(self, context, output):
        sums = context.get_discrete_state(self._sums).value()
        count, n = sums[0], len(RA_CHANNELS)
        if count < self._quiet_samples:
            output.SetFromVector(np.full(n, math.inf))
            return
        mean = sums[1 + n:1 + 2 * n] / count
        sd = np.sqrt(np.maximum(sums[1 + 2 * n:] / count - mean * mean, 0.0))
        output.SetFromVector(mean + self._sigmas * sd)


def add_ra_noise_floor(builder, channels, config):
    """Adds a RaNoiseFloor fed by the output port `channels` (raw RA); returns its `ra_floor`
    port. With ra_noise_floor_sigmas 0 the floor uses the rule's k."""
    floor = builder.AddNamedSystem("ra_noise_floor", RaNoiseFloor(
        sigmas=config.ra_noise_floor_sigmas or rule_sigmas(config.ra_rate_hz),
        quiet_s=config.ra_noise_quiet_s,
        ra_rate_hz=config.ra_rate_hz, envelope_hz=config.ra_envelope_hz))
    builder.Connect(channels, floor.GetInputPort("channels"))
    return floor.GetOutputPort("ra_floor")
