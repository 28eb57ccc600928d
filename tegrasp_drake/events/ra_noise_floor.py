"""The RA noise floor: an RA window carries no event unless it rises above its channel's
noise, measured on the live stream while the pads are untouched.

Why. Eq. 3 is blind to amplitude: each window is max-normalised before it is scored, so a
window of noise can take any shape the max-normalisation gives it. With the RA envelope
(ra_envelope.py) the noise of a resting pad becomes a smooth plateau that wanders a few
percent, and the enveloped Place-Unload template, a broad decay, resembles it well enough
to pass: the event then fires at the start of Place, before the object reaches the table
(docs/transfer.md). A real contact reads tens to hundreds of times the noise.

What. During the first `quiet_s` of the stream (the arm's approach: the pads are open and
untouched) each RA channel passes through the envelope's low-pass, started from its first
sample as the steady state (as a memorized window is, ra_envelope.py), and the filtered
samples give that channel's noise mean m_w and standard deviation s_w. After that, a
window's RA channel counts only if its peak rises above

    floor = m_w + k s_w.

Below it the channel scores 0, as a flat window does under the contrast gate
(correlation.py), unless its template is flat too (it then expects no change). Before the
noise is known the floor is infinite: no RA channel can match in the first quiet_s.

s_w is measured after the filter, not derived from the raw spread, because what the pad
reads at rest is not only white noise: the film's electronic noise (white; through the
filter its spread shrinks by sqrt(a / (2 - a)), 12.6 times at 2 Hz and 1 kHz) and the arm's
motion that the transducer picks up (slow; it passes the filter whole). On the faithful
world's development logs the white-noise prediction put the floor at 0.052-0.056 m/s^2
and the film's Place before the table touch reached 0.048-0.054 (docs/transfer.md). Without
an envelope (a = 1) the floor is m + k s of the raw samples. The estimate is of the
quiet period's own spread: about quiet_s / (2 tau) = 12 independent values in 2 s at the
80 ms time constant, a standard error of about 20 % on s_w.

k. The noise alone must not cross the floor in a trial. A union bound over every RA
sample of a trial, whatever their correlation: P(some sample of N above m + k s_w) <=
N Q(k), Q the Gaussian upper tail (the enveloped noise averages about 2 / a = 160 samples
of the raw magnitude, so it is near Gaussian: the raw |noise| skewness of about 1 shrinks
to about 0.08). For a false-alarm probability alpha per trial, k = Q^-1(alpha / N)
(`floor_sigmas`): alpha = 1e-3 (one trial in a thousand, about two in the 2,268 trials of
the transfer matrix), N = 14 s x 1000 Hz x 2 channels (the trial's horizon at the RA
rate) give k = 5.39 (`rule_sigmas`).

Quiet templates. The same floor says when a window holds no more than the noise. A
memorized RA window that does not rise above its recording's floor (m + k s of the
recording's own quiet approach, the same rule) is stored flat: "expects no change"
(extraction.py). Such a window, a held grip before the lift for instance, is only the
converter's noise: mostly zero codes and a few one-code samples, and Eq. 3 on two such
sparse windows is close to chance. At match time the floor is the gate above turned round:
a live window within the live floor holds no change the sensor can tell from its noise,
which is what a flat template expects, so the channel scores 1. Above the floor the window
carries something and Eq. 3 judges it against the flat template as in the paper: a steady
level (a grip that creeps, read by the film as a constant offset) scores near 1, a
transient (a touch, the lift's first jolt) far lower. While the floor is not yet known Eq. 3
alone judges (SlidingCorrelation.gate_below). The matcher measures the live floor whenever
an event has a flat RA template, with `rule_sigmas` unless ra_noise_floor_sigmas sets k;
it gates the other RA channels only when ra_noise_floor_sigmas > 0.
"""

import math

import numpy as np
from pydrake.systems.framework import BasicVector, LeafSystem
from scipy.stats import norm

from tegrasp_drake.events.ra_envelope import envelope_coefficient, ra_envelope
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS

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
    """The rule's k (module docstring) at an RA rate [Hz]: FALSE_ALARM_PER_TRIAL over
    TRIAL_HORIZON_S of both RA channels' samples; 5.39 at 1 kHz."""
    return floor_sigmas(FALSE_ALARM_PER_TRIAL,
                        round(TRIAL_HORIZON_S * ra_rate_hz * len(RA_CHANNELS)))


def noise_floor(quiet: np.ndarray, *, sigmas: float, envelope_hz: float,
                rate_hz: float) -> np.ndarray:
    """Per row of `quiet` (an RA channel's raw samples of the quiet period, time along the
    last axis, at rate_hz [Hz]) the floor m_w + k s_w of its envelope at envelope_hz [Hz]
    (0: none), in the samples' units (module docstring)."""
    quiet = np.atleast_2d(np.asarray(quiet, dtype=float))
    if envelope_hz:
        quiet = ra_envelope(quiet, envelope_hz, rate_hz)
    return quiet.mean(axis=-1) + sigmas * quiet.std(axis=-1)


class RaNoiseFloor(LeafSystem):
    """Each RA channel's noise floor, measured on the live stream's first quiet_s.

    Every 1 / ra_rate_hz during the first quiet_s [s] it low-passes the raw RA samples as
    the envelope does (from the first sample as the steady state) and adds the filtered
    values to running sums (count, sum, sum of squares); its output is +inf until then, and
    afterwards the floor m_w + k s_w of those values (`noise_floor` of the same samples),
    constant for the rest of the run.

    .. pydrake_system::

        name: RaNoiseFloor
        input_ports:
        - channels
        output_ports:
        - ra_floor

    Ports:
        channels (input): [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2),
            the RA raw (ahead of any envelope).
        ra_floor (output): [left, right] floor [m/s^2] of the RA windows' peaks, in the
            units of the windows the matcher scores (enveloped when envelope_hz > 0).
    """

    def __init__(self, *, sigmas: float, quiet_s: float, ra_rate_hz: float,
                 envelope_hz: float = 0.0):
        super().__init__()
        if not sigmas > 0.0 or not quiet_s * ra_rate_hz >= 2.0:
            raise ValueError(f"the RA noise floor needs sigmas > 0 (got {sigmas}) and a quiet "
                             f"period of at least 2 RA samples (got {quiet_s} s)")
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
    """Adds a RaNoiseFloor (`ra_noise_floor`) fed by the output port `channels` (raw RA);
    returns its `ra_floor` output port.

    config: an EventMatcherConfig (read: ra_noise_floor_sigmas, ra_noise_quiet_s,
    ra_rate_hz, ra_envelope_hz); with ra_noise_floor_sigmas 0 the floor uses the rule's k
    (`rule_sigmas`: the floor that judges quiet templates)."""
    floor = builder.AddNamedSystem("ra_noise_floor", RaNoiseFloor(
        sigmas=config.ra_noise_floor_sigmas or rule_sigmas(config.ra_rate_hz),
        quiet_s=config.ra_noise_quiet_s,
        ra_rate_hz=config.ra_rate_hz, envelope_hz=config.ra_envelope_hz))
    builder.Connect(channels, floor.GetInputPort("channels"))
    return floor.GetOutputPort("ra_floor")
