"""Detection, false triggers and latency of a memorized event at any thresholds, from
logged scores."""

import numpy as np
import pytest

from tegrasp_drake.recording.detection_quality import (ScoredSpan, choose_thresholds, classify,
                                                       rate_point, roc_curve)

TIMES = np.round(np.arange(0.0, 2.0, 0.001), 6)


def span(peaks, physical_s=1.0, armed_from_s=0.0, label="t"):
    """Scores that are `level` on all four channels from each (time, level, duration)."""
    scores = np.zeros((len(TIMES), 4))
    for start, level, duration in peaks:
        scores[(TIMES >= start) & (TIMES < start + duration)] = level
    return ScoredSpan(label, "reach_load", TIMES, scores, armed_from_s, physical_s)


def test_a_match_after_the_physical_event_is_a_detection_with_its_latency():
    outcome = classify(span([(1.04, 0.95, 0.05)]), 0.9, 0.7)
    assert outcome.kind == "detected" and outcome.latency_s == pytest.approx(0.04)


def test_a_match_before_the_physical_event_is_a_false_trigger_unless_within_10_ms():
    assert classify(span([(0.5, 0.95, 0.05)]), 0.9, 0.7).kind == "false"
    assert classify(span([(0.995, 0.95, 0.05)]), 0.9, 0.7).kind == "detected"
    # Before the span is armed (another mode), it does not count.
    assert classify(span([(0.5, 0.95, 0.05)], armed_from_s=0.8), 0.9, 0.7).kind == "missed"


def test_no_match_within_the_deadline_is_a_miss():
    assert classify(span([(1.6, 0.95, 0.05)]), 0.9, 0.7).kind == "missed"
    assert classify(span([(1.04, 0.85, 0.05)]), 0.9, 0.7).kind == "missed"


def test_lower_thresholds_detect_more_and_trigger_falsely_more():
    spans = [span([(0.5, 0.85, 0.01), (1.03, 0.95, 0.05)]), span([(1.05, 0.88, 0.05)])]
    strict, loose = roc_curve(spans, [1.0, 0.9])
    assert (strict.detected, strict.false) == (1, 0)
    assert (loose.detected, loose.false) == (1, 1)
    assert strict.median_latency_s == pytest.approx(0.03)


def test_the_chosen_thresholds_have_no_false_trigger_and_detect_most():
    spans = [span([(0.5, 0.85, 0.01), (1.03, 0.95, 0.05)]), span([(1.05, 0.88, 0.05)])]
    chosen = choose_thresholds(spans, [0.8, 0.86, 0.87, 0.9], [0.7])
    assert chosen.false == 0 and chosen.detected == 2
    assert chosen.sa_threshold == pytest.approx(0.87)  # the highest of equals: margin
    with pytest.raises(ValueError, match="false trigger"):
        choose_thresholds(spans, [0.8], [0.7])
    assert rate_point(spans, 0.87, 0.7).detection_rate == 1.0
