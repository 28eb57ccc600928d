"""The offline per-transition diagnosis of transfer trials (transfer/diagnosis.py), on
hand-built windows whose Eq. 3 scores are known in closed form."""

import numpy as np
import pytest

from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.transfer.diagnosis import diagnose_trial, mode_periods

SA_RATE, RA_RATE = 20.0, 40.0  # [Hz]: 10 and 20 samples in a 0.5 s window
TOUCH_S = 1.5  # [s] when the hand-built trial's pads are touched
TRANSITIONS = [{"t": 2.5, "to": "Load"}, {"t": 4.0, "to": "Lift"}]


def event_with_ra(ra_window: np.ndarray) -> MemorizedEvent:
    """Reach-Load: an SA step halfway through the window (5 zeros, 5 ones) on both pads."""
    sa = np.repeat([0.0, 1.0], 5)
    return MemorizedEvent(object_name="box", transition="reach_load", sa=np.array([sa, sa]),
                          ra=np.array([ra_window, ra_window]), sa_rate_hz=SA_RATE,
                          ra_rate_hz=RA_RATE)


def touch_trial(ra_width: int) -> TactileTrial:
    """SA steps from 0 to 5 N at TOUCH_S; RA is a pulse of `ra_width` samples of 3 m/s^2
    starting at TOUCH_S, zero elsewhere."""
    t_sa = np.arange(0.0, 4.5, 1.0 / SA_RATE)
    t_ra = np.arange(0.0, 4.5, 1.0 / RA_RATE)
    sa = np.where(t_sa >= TOUCH_S - 1e-9, 5.0, 0.0)
    start = int(np.searchsorted(t_ra, TOUCH_S - 1e-9))
    ra = np.zeros_like(t_ra)
    ra[start:start + ra_width] = 3.0
    return TactileTrial(t_sa=t_sa, sa=np.column_stack([sa, sa]), t_ra=t_ra,
                        ra=np.column_stack([ra, ra]), transition_times={})


def spike_at(index: int) -> np.ndarray:
    window = np.zeros(20)
    window[index] = 1.0
    return window


def test_mode_periods_start_in_reach_and_follow_the_transitions():
    assert mode_periods(TRANSITIONS) == [("Reach", 0.0, 2.5), ("Load", 2.5, 4.0)]


def test_the_memorized_shapes_felt_again_match_with_every_score_one():
    report = diagnose_trial(touch_trial(ra_width=1), TRANSITIONS, {
        "reach_load": event_with_ra(spike_at(10))})
    diagnosis = report["reach_load"]
    assert diagnosis.together == pytest.approx((1.0, 1.0, 1.0, 1.0))
    assert diagnosis.best == pytest.approx((1.0, 1.0, 1.0, 1.0))
    assert diagnosis.match
    # aligned when the window holds the step's 5 samples: it ends 0.25 s after the touch
    assert TOUCH_S + 0.2 <= diagnosis.at_s <= TOUCH_S + 0.3


def test_a_spike_against_a_four_sample_pulse_scores_one_half_and_fails():
    # Eq. 3 of a unit spike against a pulse of 4 equal samples: 1 / (1 x sqrt(4)) = 0.5,
    # at every lag where the spike meets the pulse; below the RA threshold 0.7.
    pulse = np.zeros(20)
    pulse[10:14] = 1.0
    report = diagnose_trial(touch_trial(ra_width=1), TRANSITIONS, {
        "reach_load": event_with_ra(pulse)})
    diagnosis = report["reach_load"]
    assert diagnosis.best[2:] == pytest.approx((0.5, 0.5))
    assert diagnosis.together[2:] == pytest.approx((0.5, 0.5))
    assert diagnosis.best[:2] == pytest.approx((1.0, 1.0))
    assert not diagnosis.match


def test_only_the_mode_that_waits_for_the_event_is_scored():
    # The touch lies in Reach; Load waits for load_lift, so its event sees only the flat
    # grip after the touch: SA contrast 0, score 0 (the contrast gate), no match.
    load_lift = MemorizedEvent(
        object_name="box", transition="load_lift", sa=event_with_ra(spike_at(10)).sa,
        ra=np.array([spike_at(10), spike_at(10)]), sa_rate_hz=SA_RATE, ra_rate_hz=RA_RATE)
    report = diagnose_trial(touch_trial(ra_width=1), TRANSITIONS, {"load_lift": load_lift})
    assert report["load_lift"].best == pytest.approx((0.0, 0.0, 0.0, 0.0))
    assert not report["load_lift"].match
    assert 2.5 < report["load_lift"].at_s <= 4.0


def test_events_without_a_waiting_mode_or_a_full_window_are_left_out():
    early = [{"t": 0.3, "to": "Load"}]  # Reach ends before a 0.5 s window fills
    assert diagnose_trial(touch_trial(ra_width=1), early, {
        "reach_load": event_with_ra(spike_at(10))}) == {}
