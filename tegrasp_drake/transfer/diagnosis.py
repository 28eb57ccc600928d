"""Which channel's Eq. 3 score falls short, per transition, in a trial run with events
memorized elsewhere (docs/transfer.md, "What breaks transfer"): each event scored offline
every `step_s` while a mode waited for it; "best" per channel, "together" at the tick with
the largest smallest margin, "match" whether that tick passes."""

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.event_matcher import EventMatcherConfig, event_templates
from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.ra_envelope import enveloped_event, ra_envelope
from tegrasp_drake.rig.channels import RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.tactile.sampling import samples_per_window

# The mode that waits for each event transition's memorized event.
WAITING_MODE = {"reach_load": "Reach", "load_lift": "Load", "place_unload": "Place"}
STEP_S = GraspControllerConfig().update_period_s  # [s] the state machine's tick


@dataclasses.dataclass(frozen=True)
class TransitionDiagnosis:
    """The offline Eq. 3 scores of one event over the modes that waited for it: best, each
    channel's highest; at_s, the tick [s] where the four came nearest their thresholds;
    together, the scores there; match, whether all four passed."""
    best: tuple[float, ...]
    at_s: float
    together: tuple[float, ...]
    match: bool

    def to_dict(self) -> dict:
        """Rounded to 3 decimals (ms for at_s), as the script prints it."""
        return {"best": [round(x, 3) for x in self.best], "at_s": round(self.at_s, 3),
                "together": [round(x, 3) for x in self.together], "match": self.match}


def mode_periods(transitions: Sequence[Mapping]) -> list[tuple[str, float, float]]:
    """(mode, entered, left) [s] of each mode a trial passed, from its logged transitions."""
    periods, mode, entered = [], "Reach", 0.0
    for transition in transitions:
        periods.append((mode, entered, float(transition["t"])))
        mode, entered = transition["to"], float(transition["t"])
    return periods


def _thresholds(config: EventMatcherConfig) -> np.ndarray:
    return np.array([config.sa_threshold] * len(SA_CHANNELS)
                    + [config.ra_threshold] * len(RA_CHANNELS))


def diagnose_transition(trial: TactileTrial, event: MemorizedEvent,
                        periods: Sequence[tuple[str, float, float]], *,
                        config: EventMatcherConfig | None = None,
                        step_s: float = STEP_S) -> TransitionDiagnosis | None:
    """`event` scored on `trial` (channels as logged: RA already enveloped if wanted) every
    step_s [s] of each period whose mode waits for it; None if no tick had full windows."""
    config = config or EventMatcherConfig()
    sa_rate = 1.0 / float(np.median(np.diff(trial.t_sa)))
    ra_rate = 1.0 / float(np.median(np.diff(trial.t_ra)))
    sa, ra = np.asarray(trial.sa, dtype=float).T, np.asarray(trial.ra, dtype=float).T
    n_sa = samples_per_window(event.window_s, sa_rate)
    n_ra = samples_per_window(event.window_s, ra_rate)
    templates = (list(event_templates(event, SA_CHANNELS, n_sa))
                 + list(event_templates(event, RA_CHANNELS, n_ra)))
    thresholds = _thresholds(config)
    best, together = np.full(len(thresholds), -1.0), None
    for mode, entered, left in periods:
        if mode != WAITING_MODE[event.transition]:
            continue
        for t in np.arange(entered + step_s, left + 1e-9, step_s):
            i = int(np.searchsorted(trial.t_sa, t, "right"))
            j = int(np.searchsorted(trial.t_ra, t, "right"))
            if i < n_sa or j < n_ra:
                continue
            live = list(sa[:, i - n_sa:i]) + list(ra[:, j - n_ra:j])
            scores = event_scores_reference(live, templates, config.min_contrast)
            best = np.maximum(best, scores)
            margin = float(np.min(scores - thresholds))
            if together is None or margin > together[0]:
                together = (margin, float(t), scores)
    if together is None:
        return None
    return TransitionDiagnosis(best=tuple(best.tolist()), at_s=together[1],
                               together=tuple(together[2].tolist()), match=together[0] > 0.0)


def diagnose_trial(trial: TactileTrial, transitions: Sequence[Mapping],
                   events: Mapping[str, MemorizedEvent], *, ra_envelope_hz: float = 0.0,
                   config: EventMatcherConfig | None = None,
                   step_s: float = STEP_S) -> dict[str, TransitionDiagnosis]:
    """{transition: TransitionDiagnosis} for each event of `events` with a waiting mode and a
    tick to score; ra_envelope_hz: the RA envelope's cutoff [Hz], 0 for none."""
    if ra_envelope_hz:
        ra_rate = 1.0 / float(np.median(np.diff(trial.t_ra)))
        trial = dataclasses.replace(trial, ra=ra_envelope(
            np.asarray(trial.ra, dtype=float).T, ra_envelope_hz, ra_rate).T)
    periods = mode_periods(transitions)
    report = {}
    for transition, event in events.items():
        if transition not in WAITING_MODE:
            continue
        if ra_envelope_hz:
            event = enveloped_event(event, ra_envelope_hz)
        diagnosis = diagnose_transition(trial, event, periods, config=config, step_s=step_s)
        if diagnosis is not None:
            report[transition] = diagnosis
    return report
