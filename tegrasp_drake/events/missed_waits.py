"""Why a memorized event did not come in time: a logged wait replayed through Eq. 3.

A wait is the time a mode spent expecting its event until the event's timeout;
`event_waits` finds them in a trial's transitions, by the code of the rule that gave up
(EVENT_TIMEOUT_RULES), or by the reason's words for an entry written before codes.
`classify_missed_wait` replays the channels with the event held expected (the run's matcher
settings) and names the cause: a weak dynamic stimulus (SA passed, an RA channel did not:
the paper's Sec. V), SA did not match, or matched in replay. Definitions: docs/sweeps.md,
"A sweep"."""

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from tegrasp_drake.events.event_matcher import EventMatcherConfig
from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.replay import replay_event_held
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS, transition_states
from tegrasp_drake.rig.number_text import number_text

WEAK_DYNAMIC_STIMULUS = "weak dynamic stimulus"
SA_DID_NOT_MATCH = "SA did not match"
MATCHED_IN_REPLAY = "matched in replay"
MISS_CLASSES = (WEAK_DYNAMIC_STIMULUS, SA_DID_NOT_MATCH, MATCHED_IN_REPLAY)

# The mode that waits for each event-triggered transition (its from-state), by label.
_WAITING_MODE = {transition_states(name)[0]: name for name in REQUIRED_TRANSITIONS}
# The rules that give up waiting for an event, by name (a timeline entry's code): the event
# transition each waited for. Their `when` starts "no X-Y event" in the rule tables
# (docs/controller.md); the taxel-aware ones Load or Lift where the paper's would Re-Reach.
EVENT_TIMEOUT_RULES = {
    "reach_timeout": "reach_load",
    "reach_timeout_both_pads": "reach_load",
    "reach_timeout_caged": "reach_load",
    "load_timeout": "load_lift",
    "load_timeout_both_pads": "load_lift",
    "load_timeout_caged": "load_lift",
    "place_timeout": "place_unload",
}


@dataclasses.dataclass(frozen=True)
class EventWait:
    """The machine expected `transition`'s event from start_s [s], gave up at end_s for `reason`."""
    transition: str
    start_s: float
    end_s: float
    reason: str


def timeout_reason_prefix(transition: str) -> str:
    """How the reasons start when `transition`'s event timed out ("no Reach-Load event")."""
    return "no {}-{} event".format(*transition_states(transition))


def timed_out_event(entry: Mapping) -> str | None:
    """The event transition whose timeout a timeline entry (JSON form) gave up on, or None: by
    its rule's code (EVENT_TIMEOUT_RULES), or, for an entry without one (written before
    codes), by its reason starting with timeout_reason_prefix of its mode's event."""
    if entry.get("code") is not None:
        return EVENT_TIMEOUT_RULES.get(entry["code"])
    transition = _WAITING_MODE.get(entry["from"])
    if transition is not None and entry["reason"].startswith(timeout_reason_prefix(transition)):
        return transition
    return None


def event_waits(transitions: Sequence[Mapping]) -> list[EventWait]:
    """The waits in a trial's transitions (JSON form, in time order) that ended on their event's
    timeout, each from the last entry into the waiting mode (0 for the first Reach)."""
    waits, entered = [], {"Reach": 0.0}  # the machine starts in Reach at 0
    for entry in transitions:
        transition = timed_out_event(entry)
        if transition is not None:
            start = entered.get(entry["from"], 0.0)
            waits.append(EventWait(transition, float(start), float(entry["t"]),
                                   entry["reason"]))
        entered[entry["to"]] = float(entry["t"])
    return waits


@dataclasses.dataclass(frozen=True)
class MissedWait:
    """A wait's replay (module docstring).

    thresholds: (SA, RA) of the event. best_tick_s: the SA-passing tick whose lower RA score is
    highest (None when SA never passed); best_sa, best_ra: [left, right] scores there (without
    it, best_sa at the tick of highest lower SA score). ra_peak: [left, right] peak |RA|
    [m/s^2] of the window ending at best_tick_s; ra_wait_peak: over the whole wait;
    ra_noise_mean, ra_noise_std: the RA noise [m/s^2] of the quiet approach."""
    wait: EventWait
    miss_class: str
    thresholds: tuple[float, float]
    best_sa: np.ndarray
    ra_wait_peak: np.ndarray
    ra_noise_mean: np.ndarray
    ra_noise_std: np.ndarray
    best_tick_s: float | None = None
    best_ra: np.ndarray | None = None
    ra_peak: np.ndarray | None = None

    def ra_peak_sigmas(self) -> np.ndarray | None:
        """[left, right] (peak - noise mean) / noise std; inf for a channel without noise."""
        return None if self.ra_peak is None else self._sigmas(self.ra_peak)

    def _sigmas(self, peak: np.ndarray) -> np.ndarray:
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.ra_noise_std > 0.0,
                            (peak - self.ra_noise_mean) / self.ra_noise_std, np.inf)

    def ra_wait_peak_sigmas(self) -> np.ndarray:
        """[left, right] (ra_wait_peak - noise mean) / noise std; inf for a noiseless channel."""
        return self._sigmas(self.ra_wait_peak)

    def failing_ra_within_floor(self, sigmas: float) -> bool | None:
        """Whether an RA channel failing at the best tick never read above its noise mean +
        `sigmas` std over the wait; None without a best tick."""
        if self.best_ra is None:
            return None
        failing = self.best_ra <= self.thresholds[1]
        return bool(np.any(failing & (self.ra_wait_peak_sigmas() <= sigmas)))


def event_thresholds(config: EventMatcherConfig, transition: str) -> tuple[float, float]:
    """The (SA, RA) thresholds the matcher applies to `transition`'s event."""
    return tuple(config.event_thresholds.get(transition,
                                             (config.sa_threshold, config.ra_threshold)))


def ra_noise(trial: TactileTrial, quiet_s: float) -> tuple[np.ndarray, np.ndarray]:
    """[left, right] mean and std [m/s^2] of the raw RA over the trial's first quiet_s [s]."""
    quiet = trial.ra[trial.t_ra < trial.t_ra[0] + quiet_s]
    if len(quiet) < 2:
        raise ValueError("the trial holds fewer than 2 RA samples in its first "
                         f"{number_text(quiet_s)} s")
    return quiet.mean(axis=0), quiet.std(axis=0)


def ra_window_peak(trial: TactileTrial, end_s: float, window_s: float) -> np.ndarray:
    """[left, right] largest |RA| [m/s^2] of the samples in (end_s - window_s, end_s]."""
    inside = (trial.t_ra > end_s - window_s) & (trial.t_ra <= end_s + 1e-9)
    return np.abs(trial.ra[inside]).max(axis=0) if inside.any() else np.zeros(2)


def classify_missed_wait(trial: TactileTrial, events: Mapping[str, MemorizedEvent],
                         wait: EventWait, config: EventMatcherConfig) -> MissedWait:
    """Replays `trial` to wait.end_s with wait.transition's event held expected by an
    EventMatcher of `config` (the run's) and classifies the wait by its ticks' scores."""
    if not trial.t_ra[0] <= wait.start_s <= wait.end_s <= trial.t_ra[-1] + 1e-9:
        raise ValueError(f"the wait {wait.start_s:.3f}-{wait.end_s:.3f} s is not within the "
                         f"log's {trial.t_ra[0]:.3f}-{trial.t_ra[-1]:.3f} s: the log is not "
                         "this trial's")
    replay = replay_event_held(trial, events, wait.transition, config=config,
                               t_end=wait.end_s)
    inside = (replay.times >= wait.start_s) & (replay.times <= wait.end_s)
    if not inside.any():
        raise ValueError(f"the wait {wait.start_s:.3f}-{wait.end_s:.3f} s holds no control "
                         "tick of the replay: it is shorter than a tick")
    times, scores = replay.times[inside], replay.scores[inside]
    sa_threshold, ra_threshold = event_thresholds(config, wait.transition)
    sa, ra = scores[:, :2], scores[:, 2:]
    sa_pass = np.all(sa > sa_threshold, axis=1)
    all_pass = sa_pass & np.all(ra > ra_threshold, axis=1)
    thresholds = (sa_threshold, ra_threshold)
    wait_peak = ra_window_peak(trial, wait.end_s, wait.end_s - wait.start_s)
    mean, std = ra_noise(trial, config.ra_noise_quiet_s)
    if not sa_pass.any():
        return MissedWait(wait, SA_DID_NOT_MATCH, thresholds,
                          sa[int(np.argmax(sa.min(axis=1)))], wait_peak, mean, std)
    candidates = np.flatnonzero(sa_pass)
    best = candidates[int(np.argmax(ra[candidates].min(axis=1)))]
    window_s = next(iter(events.values())).window_s
    return MissedWait(
        wait, MATCHED_IN_REPLAY if all_pass.any() else WEAK_DYNAMIC_STIMULUS, thresholds,
        sa[best], wait_peak, mean, std, best_tick_s=float(times[best]), best_ra=ra[best],
        ra_peak=ra_window_peak(trial, float(times[best]), window_s))
