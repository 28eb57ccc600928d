"""What a taxel reads from noise alone, as an exact distribution of the transducer's model,
for the SA thresholds (docs/model.md, "SA thresholds against the taxels' noise"). Every path
ends in a quantiser, so the noise is a lattice distribution; the calibrated reading is
clipped at zero (a positive mean at rest), which under load is not reached (`loaded_noise`)."""

import dataclasses

import numpy as np
from scipy import signal
from scipy.stats import norm

from tegrasp_drake.simulation.capacitive_taxels import (calibration_gain_n_per_count,
                                                        noise_std_at_decimation)

_TAIL_SIGMAS = 12.0  # the lattice covers +-12 sigma: the mass beyond is below 1e-32
_CONTINUOUS_STEPS_PER_SIGMA = 64


@dataclasses.dataclass(frozen=True)
class LatticeDistribution:
    """A random value that takes origin + k step, k = 0, 1, ..., with probability pmf[k]."""
    step: float
    origin: float
    pmf: np.ndarray

    def values(self) -> np.ndarray:
        return self.origin + self.step * np.arange(len(self.pmf))

    def mean(self) -> float:
        return float(self.values() @ self.pmf)

    def std(self) -> float:
        return float(np.sqrt(((self.values() - self.mean()) ** 2) @ self.pmf))

    def sum_of(self, count: int) -> "LatticeDistribution":
        """The sum of `count` independent copies (Eq. 1's sum over a pad's taxels)."""
        pmf = np.ones(1)
        for _ in range(count):
            pmf = np.clip(signal.fftconvolve(pmf, self.pmf), 0.0, None)
        return LatticeDistribution(self.step, count * self.origin, pmf / pmf.sum())

    def exceeded_with(self, probability: float) -> float:
        """The smallest value v of the lattice with P(X > v) <= probability."""
        above = np.concatenate([np.cumsum(self.pmf[::-1])[::-1][1:], [0.0]])
        return float(self.values()[int(np.argmax(above <= probability))])


def _rounded_gaussian(sigma: float, mean: float = 0.0) -> LatticeDistribution:
    """rint(mean + sigma Z) on the integers (sigma in lattice steps)."""
    half = int(np.ceil(abs(mean) + _TAIL_SIGMAS * max(sigma, 1e-12))) + 1
    k = np.arange(-half, half + 1)
    if sigma == 0.0:
        pmf = (k == np.rint(mean)).astype(float)
    else:
        pmf = norm.cdf((k + 0.5 - mean) / sigma) - norm.cdf((k - 0.5 - mean) / sigma)
    return LatticeDistribution(1.0, float(-half), pmf / pmf.sum())


def _scaled(d: LatticeDistribution, scale: float) -> LatticeDistribution:
    return LatticeDistribution(d.step * scale, d.origin * scale, d.pmf)


def _clipped_at_zero(d: LatticeDistribution) -> LatticeDistribution:
    values = d.values()
    below = d.pmf[values <= 0.0].sum()
    kept = d.pmf[values > 0.0]
    return LatticeDistribution(d.step, 0.0, np.concatenate([[below], kept]))


def _reading_noise(tactile_config, *, at_rest: bool) -> LatticeDistribution:
    c = tactile_config
    if c.transducer == "capacitive":
        counts = _rounded_gaussian(noise_std_at_decimation(c.capacitive))
        if c.capacitive.output == "counts":
            return counts
        if at_rest:
            counts = _clipped_at_zero(counts)
        return _scaled(counts, calibration_gain_n_per_count(
            c.capacitive, pad_modulus_pa=c.pad_modulus_pa))
    step = c.quantization_n or c.noise_std_n / _CONTINUOUS_STEPS_PER_SIGMA
    if step == 0.0:  # neither noise nor quantisation: the reading is the offset
        return LatticeDistribution(1.0, float(c.offset_n), np.ones(1))
    offset = c.offset_n if at_rest else 0.0
    return _scaled(_rounded_gaussian(c.noise_std_n / step, offset / step), step)


def rest_reading(tactile_config) -> LatticeDistribution:
    """One untouched taxel's reading [N, or counts], for a TactileSensorConfig."""
    return _reading_noise(tactile_config, at_rest=True)


def loaded_noise(tactile_config) -> LatticeDistribution:
    """A loaded taxel's reading less its noise-free value [N, or counts]: unclipped, no offset."""
    return _reading_noise(tactile_config, at_rest=False)
