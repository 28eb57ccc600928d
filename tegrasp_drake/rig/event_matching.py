"""How memorized events are matched with Eq. 3 (Sec. III-B): the thresholds, the RA
envelope and the RA noise floor, declared once for `controller.matching` and the
EventMatcher; Drake-free, so the command line reads it without loading Drake."""

import dataclasses

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.rig.api_boundary import public_dataclass

# Eq. 3 scores are correlations, in [-1, 1]: a threshold outside never or always passes.
SCORE_RANGE = dict(low=-1.0, high=1.0, why="Eq. 3 scores are correlations")


@public_dataclass
@dataclasses.dataclass
class EventMatchingConfig:
    """The Eq. 3 thresholds and the RA channel's envelope and noise floor."""
    # A channel passes when its score is greater than its threshold (Sec. III-B).
    sa_threshold: float = bounded(0.9, **SCORE_RANGE)
    ra_threshold: float = bounded(0.7, **SCORE_RANGE)
    # RA envelope cutoff [Hz] before Eq. 3 (docs/transfer.md): 2.0, the corner both RA
    # chains share, matches events across transducers; 0 (the paper): none
    ra_envelope_hz: float = bounded(0.0, low=0.0, high=10_000.0, unit="Hz",
                                    below="must be 0 (no RA envelope) or lie between 0 and half "
                                          "the RA rate")
    # RA noise floor (docs/transfer.md): a window counts only above mean + k sigma of the
    # noise on the first ra_noise_quiet_s [s] (5.39: one false trial in a thousand; 0: none);
    # 2 s lies within the 2.8 s approach, before the fingers reach the object
    ra_noise_floor_sigmas: float = bounded(0.0, low=0.0, high=100.0,
                                           below="must be 0 (no RA noise floor) or positive "
                                                 "(standard deviations of the RA noise)")
    ra_noise_quiet_s: float = bounded(2.0, low=0.0, high=60.0, unit="s",
                                      below="must be zero or positive [s]")
    # a flat template channel scores only a flat live window; False: the paper's Eq. 3
    # alone (docs/controller.md, "The paper's state machine")
    flat_template_needs_flat_window: bool = False

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first setting that does not fit the RA
        stream at ra_rate_hz [Hz] with its approach ending at approach_s [s]; None if all fit."""
        if not (self.ra_envelope_hz == 0 or self.ra_envelope_hz < ra_rate_hz / 2):
            return ("ra_envelope_hz", "must be 0 (no RA envelope) or lie between 0 and half "
                    f"the RA rate ({ra_rate_hz / 2:g} Hz)", self.ra_envelope_hz)
        if self.ra_noise_quiet_s * ra_rate_hz < 2:
            return ("ra_noise_quiet_s", "must hold at least 2 RA samples [s] (the start of the "
                    "run, pads untouched, where the RA noise is measured)",
                    self.ra_noise_quiet_s)
        if self.ra_noise_floor_sigmas != 0 and self.ra_noise_quiet_s > approach_s:
            return ("ra_noise_quiet_s", "must end with the approach, by grasp.settle_s + "
                    f"grasp.reach_s = {approach_s:g} s, when the RA noise floor is on (the "
                    "noise is measured with the pads untouched; shorten it or lengthen the "
                    "approach)", self.ra_noise_quiet_s)
        return None

