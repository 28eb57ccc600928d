"""How well a memorized event detects its transition, from recorded logs: detection, false
triggers and latency at any Eq. 3 threshold pair, each trial replayed once per transition.
choose_thresholds takes, of the pairs with no false trigger and the most detections, the
highest: the widest margin above the spans' scores before their events."""

import dataclasses
from collections.abc import Iterable, Sequence

import numpy as np

from tegrasp_drake.scenario.trial_result import FALSE_TRIGGER_MARGIN_S  # the judge's margin
DEADLINE_S = 0.5  # a match later than this after the event is missed
LATENCY_TARGET_S = 0.06  # the median latency choose_thresholds prefers


@dataclasses.dataclass(frozen=True)
class ScoredSpan:
    """One transition of one trial: the held event's scores (T, 4) at its armed span's times [s]."""
    label: str
    transition: str
    times: np.ndarray
    scores: np.ndarray
    armed_from_s: float
    physical_s: float


@dataclasses.dataclass(frozen=True)
class Outcome:
    """A span at one threshold pair: 'detected' (with latency_s), 'false' or 'missed'."""
    kind: str
    latency_s: float | None = None


def classify(span: ScoredSpan, sa_threshold: float, ra_threshold: float) -> Outcome:
    """The span's Outcome at these thresholds (module doc)."""
    armed = (span.times >= span.armed_from_s) & (span.times <= span.physical_s + DEADLINE_S)
    above = np.all(span.scores[:, :2] > sa_threshold, axis=1) & np.all(
        span.scores[:, 2:] > ra_threshold, axis=1)
    hits = span.times[armed & above]
    if hits.size == 0:
        return Outcome("missed")
    first = float(hits[0])
    if first < span.physical_s - FALSE_TRIGGER_MARGIN_S:
        return Outcome("false")
    return Outcome("detected", first - span.physical_s)


@dataclasses.dataclass(frozen=True)
class RatePoint:
    """Detection quality of a set of spans at one threshold pair."""
    sa_threshold: float
    ra_threshold: float
    spans: int
    detected: int
    false: int
    missed: int
    median_latency_s: float | None

    @property
    def detection_rate(self) -> float:
        return self.detected / self.spans if self.spans else 0.0

    @property
    def false_rate(self) -> float:
        return self.false / self.spans if self.spans else 0.0


def rate_point(spans: Sequence[ScoredSpan], sa_threshold: float,
               ra_threshold: float) -> RatePoint:
    """RatePoint of `spans` at (sa_threshold, ra_threshold)."""
    outcomes = [classify(span, sa_threshold, ra_threshold) for span in spans]
    latencies = [o.latency_s for o in outcomes if o.kind == "detected"]
    return RatePoint(sa_threshold, ra_threshold, len(outcomes),
                     sum(o.kind == "detected" for o in outcomes),
                     sum(o.kind == "false" for o in outcomes),
                     sum(o.kind == "missed" for o in outcomes),
                     float(np.median(latencies)) if latencies else None)


def roc_curve(spans: Sequence[ScoredSpan], scales: Iterable[float],
              base=(0.9, 0.7)) -> list[RatePoint]:
    """RatePoints at thresholds base * scale (each capped below 1), one per scale."""
    return [rate_point(spans, min(base[0] * s, 0.999), min(base[1] * s, 0.999))
            for s in scales]


def most_detecting_clean_points(spans: Sequence[ScoredSpan], sa_grid: Iterable[float],
                                ra_grid: Iterable[float]) -> list[RatePoint]:
    """The grids' threshold pairs with no false trigger on `spans` and, among those, the
    most detections; ValueError when every pair has a false trigger."""
    points = [rate_point(spans, sa, ra) for sa in sa_grid for ra in ra_grid]
    clean = [p for p in points if p.false == 0]
    if not clean:
        raise ValueError("every threshold pair of the grid has a false trigger on these spans")
    best = max(p.detected for p in clean)
    return [p for p in clean if p.detected == best]


def choose_thresholds(spans: Sequence[ScoredSpan], sa_grid: Iterable[float],
                      ra_grid: Iterable[float]) -> RatePoint:
    """The pair of the grids chosen by the module doc's rule; ValueError if all are false."""
    candidates = most_detecting_clean_points(spans, sa_grid, ra_grid)
    if candidates[0].detected:
        on_target = [p for p in candidates if p.median_latency_s <= LATENCY_TARGET_S]
        if on_target:
            candidates = on_target
        else:
            fastest = min(p.median_latency_s for p in candidates)
            candidates = [p for p in candidates if p.median_latency_s == fastest]
    return max(candidates, key=lambda p: p.sa_threshold + p.ra_threshold)


def _trial_from(trial, start_s: float):
    """`trial` (a TactileTrial) from start_s [s] on, its times shifted to start at 0."""
    from tegrasp_drake.events.extraction import TactileTrial
    keep_sa, keep_ra = trial.t_sa >= start_s, trial.t_ra >= start_s
    return TactileTrial(t_sa=trial.t_sa[keep_sa] - start_s, sa=trial.sa[keep_sa],
                        t_ra=trial.t_ra[keep_ra] - start_s, ra=trial.ra[keep_ra],
                        transition_times={})


def scored_span(label: str, trial, events, transition: str, *, armed_from_s: float,
                physical_s: float) -> ScoredSpan:
    """Replays `trial` with `events`[transition] held expected, from one window before
    armed_from_s to the physical event + DEADLINE_S; its ScoredSpan (the trial's clock)."""
    from tegrasp_drake.events.replay import replay_event_held
    window_s = next(iter(events.values())).window_s
    start = max(0.0, armed_from_s - window_s - 0.05)
    part = _trial_from(trial, start) if start > 0.0 else trial
    t_end = min(physical_s + DEADLINE_S + 0.01, float(trial.t_ra[-1])) - start
    replay = replay_event_held(part, events, transition, t_end=t_end)
    return ScoredSpan(label, transition, replay.times + start, replay.scores, armed_from_s,
                      physical_s)
