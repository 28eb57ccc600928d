"""How memorized events are matched with Eq. 3 (Sec. III-B): the thresholds, the RA envelope
and the RA noise floor, declared once for the controllers that read memorized events
(`controller.matching`, control/controller_config.py) and for the EventMatcher itself
(events/event_matcher.py, whose fields of these names take these declarations).

It lives below both (no Drake), so that the command line can read the controllers' settings
without loading Drake.
"""

import dataclasses

from tegrasp_drake.rig.ranges import bounded

# Eq. 3 scores are correlations, in [-1, 1]: a threshold outside never or always passes.
SCORE_RANGE = dict(low=-1.0, high=1.0, why="Eq. 3 scores are correlations")


@dataclasses.dataclass
class EventMatchingConfig:
    """The Eq. 3 thresholds and the RA channel's envelope and noise floor."""
    # A channel passes when its score is greater than its threshold (Sec. III-B).
    sa_threshold: float = bounded(0.9, **SCORE_RANGE)
    ra_threshold: float = bounded(0.7, **SCORE_RANGE)
    # Cutoff [Hz] of the RA envelope on the memorized and live RA windows before Eq. 3
    # (events/ra_envelope.py, docs/transfer.md): 2.0, the corner both RA chains share (the
    # charge amplifier's and the accelerometer's high-pass), lets events memorized with one
    # vibration transducer match on the other; 0 (the paper): Eq. 3 on the raw windows.
    ra_envelope_hz: float = bounded(0.0, low=0.0, high=10_000.0, unit="Hz",
                                    below="must be 0 (no RA envelope) or lie between 0 and half "
                                          "the RA rate")
    # The RA noise floor (events/ra_noise_floor.py, docs/transfer.md): an RA window counts
    # only if its peak rises above its channel's noise mean + ra_noise_floor_sigmas standard
    # deviations, the noise measured on the stream's first ra_noise_quiet_s [s]. 5.39 is
    # the rule's k (noise alone crosses it in at most one trial of a thousand); 0 (the
    # paper): no floor. 2 s: within the 2.8 s approach (scripted_grasp.py: settle_s 0.3 +
    # reach_s 2.5), before the open fingers can reach the object.
    ra_noise_floor_sigmas: float = bounded(0.0, low=0.0, high=100.0,
                                           below="must be 0 (no RA noise floor) or positive "
                                                 "(standard deviations of the RA noise)")
    ra_noise_quiet_s: float = bounded(2.0, low=0.0, high=60.0, unit="s",
                                      below="must be zero or positive [s]")
    # Beyond the paper: a flat template channel (Load-Lift's SA, the settled grip) scores
    # only a live window that is flat too, so Load-Lift waits until the grip has held for a
    # window (events/correlation.py); False (the paper): Eq. 3 alone, which passes a grip
    # still rising once 81 % of the window is on its plateau (a grip that rises over
    # 0.8 s: lifted at 68 % of it).
    flat_template_needs_flat_window: bool = False

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first setting that does not fit the
        RA stream read at ra_rate_hz [Hz] whose approach (pads untouched) ends at
        approach_s [s]; None when all fit."""
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

