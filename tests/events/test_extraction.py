"""Cutting memorized events out of a recorded trial."""

import numpy as np
import pytest

from tegrasp_drake.events.extraction import (
    DEFAULT_PRE_TRANSITION_S, TactileTrial, extract_memorized_events)
from tegrasp_drake.events.synthetic import SyntheticGraspConfig, synthetic_grasp

VERSIONS = {"drake": "1.51.1"}


def ramp_trial(transition_times, *, sa_rate_hz=1000.0, duration_s=3.0):
    """SA = [t, 3 t] and RA = [t, t] + 1 logged at the given rates: values reveal times."""
    t_sa = np.arange(int(duration_s * sa_rate_hz) + 1) / sa_rate_hz
    t_ra = np.arange(int(duration_s * 1000.0) + 1) / 1000.0
    return TactileTrial(t_sa=t_sa, sa=np.stack([t_sa, 3.0 * t_sa], axis=1),
                        t_ra=t_ra, ra=np.stack([t_ra + 1.0, t_ra + 1.0], axis=1),
                        transition_times=transition_times)


def extract(trial, **options):
    return extract_memorized_events(trial, object_name="box", sa_rate_hz=100.0,
                                    ra_rate_hz=1000.0, package_versions=VERSIONS, **options)


def test_window_starts_pre_transition_before_the_event_and_holds_the_log():
    event = extract(ramp_trial({"reach_load": 1.2345}))["reach_load"]
    start = 1.2345 - DEFAULT_PRE_TRANSITION_S
    # SA logged at 1 kHz, memorized at 100 Hz: the latest log value at or before each tick.
    sa_times = np.floor((start + np.arange(50) / 100.0) * 1000.0 + 1e-6) / 1000.0
    np.testing.assert_allclose(event.sa[0], sa_times / sa_times[-1], rtol=1e-12)
    ra_times = np.floor((start + np.arange(500) / 1000.0) * 1000.0 + 1e-6) / 1000.0
    np.testing.assert_allclose(event.ra[1], (ra_times + 1.0) / (ra_times[-1] + 1.0),
                               rtol=1e-12)


def test_window_placement_is_configurable():
    event = extract(ramp_trial({"load_lift": 2.0}), pre_transition_s=0.1)["load_lift"]
    assert event.pre_transition_s == 0.1
    np.testing.assert_allclose(event.sample_times("sa_left")[[0, -1]], [-0.1, 0.39])
    np.testing.assert_allclose(event.sa[0] * 2.39, 1.9 + np.arange(50) / 100.0, rtol=1e-12)


def test_each_channel_is_normalised_by_its_own_maximum():
    event = extract(ramp_trial({"reach_load": 1.0}))["reach_load"]
    np.testing.assert_allclose(event.sa[0], event.sa[1], rtol=1e-12)  # right = 3 x left
    assert np.max(event.sa, axis=1).tolist() == [1.0, 1.0]
    assert np.max(event.ra, axis=1).tolist() == [1.0, 1.0]


def test_events_come_in_grasp_order_with_their_provenance():
    times = {"place_unload": 2.5, "reach_load": 0.5, "load_lift": 1.0}
    events = extract(ramp_trial(times), scenario="ideal box grasp")
    assert list(events) == ["reach_load", "load_lift", "place_unload"]
    for transition, event in events.items():
        assert event.transition_time_s == times[transition]
        assert (event.object_name, event.scenario) == ("box", "ideal box grasp")
        assert event.package_versions == VERSIONS


@pytest.mark.parametrize("time, where", [(0.1, "0.1000 s"), (2.9, "2.9000 s")])
def test_transition_too_near_the_log_ends_is_refused(time, where):
    with pytest.raises(ValueError, match=rf"transition 'reach_load' at {where}.*log covers"):
        extract(ramp_trial({"reach_load": time}))


def test_unknown_transition_is_refused():
    with pytest.raises(ValueError, match="unknown transition 'grab'"):
        extract(ramp_trial({"grab": 1.0}))


def test_channel_without_signal_is_refused():
    trial = ramp_trial({"reach_load": 1.0})
    silent = TactileTrial(t_sa=trial.t_sa, sa=trial.sa, t_ra=trial.t_ra,
                          ra=np.zeros_like(trial.ra), transition_times={"reach_load": 1.0})
    with pytest.raises(ValueError, match="ra_left.*zero throughout"):
        extract(silent)


def test_synthetic_grasp_events_hold_the_event_in_the_middle_of_the_window():
    events = extract(synthetic_grasp(SyntheticGraspConfig()))
    contact = events["reach_load"]
    before = contact.sample_times("sa_left") < 0.0
    assert np.all(contact.sa[:, before] == 0.0)  # no force before the first contact
    assert np.all(contact.sa[:, -1] == 1.0)  # the touch force plateau after it
    burst = contact.sample_times("ra_left")[np.argmax(contact.ra, axis=1)]
    assert np.all((burst >= 0.0) & (burst < 0.01))
