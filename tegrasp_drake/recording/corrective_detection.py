"""How well the corrective triggers detect their situations, from recorded logs: the
memorized corrective events and the heuristic triggers they would replace, on the same spans,
and the threshold rule: the centre of the admissible range (the highest admissible pair sits
at its edge and misses real hits)."""

import dataclasses
import math

import numpy as np
from scipy import signal

from tegrasp_drake.recording.detection_quality import (
    DEADLINE_S, FALSE_TRIGGER_MARGIN_S, LATENCY_TARGET_S, Outcome, ScoredSpan,
    most_detecting_clean_points, scored_span)
from tegrasp_drake.tactile.slip_vibration_band import highpass_biquad


@dataclasses.dataclass(frozen=True)
class SituationSpan:
    """Where one run is looked at for one corrective situation [s]: from armed_from_s to
    armed_until_s; physical_s the situation's physical event, None when it has none."""
    label: str
    transition: str
    armed_from_s: float
    armed_until_s: float
    physical_s: float | None


def event_span(trial, events, span: SituationSpan) -> ScoredSpan:
    """The corrective event's Eq. 3 scores over `span` of `trial`, held expected; a span
    without a physical event has physical_s = inf (every match in it is false)."""
    if span.physical_s is not None:
        return scored_span(span.label, trial, events, span.transition,
                           armed_from_s=span.armed_from_s, physical_s=span.physical_s)
    scored = scored_span(span.label, trial, events, span.transition,
                         armed_from_s=span.armed_from_s,
                         physical_s=span.armed_until_s - DEADLINE_S)
    keep = scored.times <= span.armed_until_s
    return dataclasses.replace(scored, times=scored.times[keep], scores=scored.scores[keep],
                               physical_s=math.inf)


def on_controller_ticks(span: ScoredSpan, period_s: float) -> ScoredSpan:
    """`span` at the state machine's ticks (every period_s [s]), each reading `match` once."""
    ticks = np.abs(span.times / period_s - np.round(span.times / period_s)) < 1e-6
    return dataclasses.replace(span, times=span.times[ticks], scores=span.scores[ticks])


def choose_centred_thresholds(spans, sa_grid, ra_grid):
    """The threshold pair for a corrective event: of the grid's pairs with no false trigger
    and the most detections (median latency within LATENCY_TARGET_S, if any), the one
    nearest the centre of that set. ValueError when every pair has a false trigger."""
    candidates = most_detecting_clean_points(spans, sa_grid, ra_grid)
    on_target = [p for p in candidates
                 if p.median_latency_s is not None and p.median_latency_s <= LATENCY_TARGET_S]
    candidates = on_target or candidates
    centre = [np.mean([min(values), max(values)]) for values in (
        [p.sa_threshold for p in candidates], [p.ra_threshold for p in candidates])]
    return min(candidates, key=lambda p: (p.sa_threshold - centre[0]) ** 2
               + (p.ra_threshold - centre[1]) ** 2)


def classify_first_firing(fire_s: float | None, physical_s: float | None) -> Outcome:
    """A trigger's first firing in a span as an Outcome, by detection_quality's rules."""
    if fire_s is None:
        return Outcome("missed")
    if physical_s is None or fire_s < physical_s - FALSE_TRIGGER_MARGIN_S:
        return Outcome("false")
    if fire_s > physical_s + DEADLINE_S:
        return Outcome("missed")
    return Outcome("detected", fire_s - physical_s)


def heuristic_hit_time(log, span: SituationSpan, hit_ra_mps2: float) -> float | None:
    """The first time [s] in `span` that either RA exceeds hit_ra_mps2 [m/s^2]."""
    t = np.asarray(log.t_ra)
    ra = np.asarray(log.ra).max(axis=1)
    index = np.flatnonzero((t >= span.armed_from_s) & (t <= span.armed_until_s)
                           & (ra > hit_ra_mps2))
    return float(t[index[0]]) if index.size else None


def slip_band(log, band_hz: float, window_s: float, sample_rate_hz: float) -> np.ndarray:
    """(M, 2) the pads' slip band [m/s^2] at the log's RA times (SlipVibrationBand's)."""
    b0, b1, b2, a1, a2 = highpass_biquad(band_hz, sample_rate_hz)
    high = signal.lfilter([b0, b1, b2], [1.0, a1, a2], np.asarray(log.pad_acceleration),
                          axis=0)
    squares = (high ** 2).reshape(len(high), 2, 3).sum(axis=2)
    n = max(1, round(window_s * sample_rate_hz))
    kernel = np.ones(n) / n
    mean = np.column_stack([np.convolve(squares[:, k], kernel)[:len(squares)]
                            for k in range(2)])
    return np.sqrt(mean)


def heuristic_slip_time(log, span: SituationSpan, lift_load,
                        sample_rate_hz: float) -> float | None:
    """When in `span` either slip band has stayed above lift_load.slip_vibration_mps2 for
    lift_load.slip_s [s] (lift_load: a controller's LiftLoadConfig)."""
    band = slip_band(log, lift_load.slip_band_hz, lift_load.slip_window_s, sample_rate_hz)
    t = np.asarray(log.t_ra)
    above = band.max(axis=1) > lift_load.slip_vibration_mps2
    since = None
    for k in np.flatnonzero((t >= span.armed_from_s) & (t <= span.armed_until_s)):
        if not above[k]:
            since = None
            continue
        since = t[k] if since is None else since
        if t[k] - since >= lift_load.slip_s:
            return float(t[k])
    return None
