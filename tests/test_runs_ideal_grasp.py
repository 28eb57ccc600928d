"""The ideal open-loop grasp for the paper's three objects."""

import numpy as np
import pytest

from tegrasp_drake.runs.grasp_outcome import judge_grasp
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.scenario import LoadScenario

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module", params=["box", "thick_cylinder", "thin_cylinder"])
def trial(request, ideal_grasp_log):
    scenario = LoadScenario(name=request.param)
    log = ideal_grasp_log(request.param)
    target = np.add(scenario.expected_object_xy, scenario.grasp.place_offset)
    return scenario, log, judge_grasp(log, target_xy=target, grip_force=scenario.grasp.grip_force)


def test_lifts_holds_places_upright_and_releases(trial):
    _, _, outcome = trial
    assert outcome.lift_height_m >= 0.04
    assert outcome.hold_time_s >= 3.0
    assert outcome.final_tilt_deg < 5.0
    assert outcome.placement_error_m < 0.01
    assert outcome.released


def test_sa_equals_the_commanded_grip_force_while_holding(trial):
    # Eq. 1: the summed taxel forces are the pad's normal force, which the gripper's force
    # limit sets while the lifted object hangs in the grasp (within 5 %).
    scenario, log, _ = trial
    starts = log.meta["phase_starts"]
    holding = (log.t_sa >= starts["hold"]) & (log.t_sa < starts["place"])
    for pad in (log.taxels[holding, :12], log.taxels[holding, 12:]):
        np.testing.assert_allclose(pad.sum(axis=1), scenario.grasp.grip_force, rtol=0.05)


def _ra_peak(log, t0, t1):
    mask = (log.t_ra >= t0) & (log.t_ra < t1)
    return log.ra[mask].max(axis=0)


def test_ra_spikes_at_first_contact_and_table_touch(trial):
    _, log, outcome = trial
    noise_floor = _ra_peak(log, 1.0, 2.5).max()
    for event in ("first_contact", "table_touch"):
        t = outcome.events[event]
        assert t is not None
        assert np.all(_ra_peak(log, t - 0.05, t + 0.05) > 10 * noise_floor), event


def test_ra_stays_at_noise_in_free_motion_and_static_hold(trial):
    scenario, log, _ = trial
    starts = log.meta["phase_starts"]
    noise_bound = 6 * scenario.vibration.noise_std_mps2 * np.sqrt(3)
    reach_peak = _ra_peak(log, starts["reach"] + 0.1, starts["load"]).max()
    hold_peak = _ra_peak(log, starts["hold"], starts["place"]).max()
    assert reach_peak < noise_bound and hold_peak < noise_bound


def test_same_scenario_and_seed_give_the_same_numbers():
    scenario = LoadScenario(name="box")
    first, _ = run_ideal_grasp(scenario, duration=4.5)
    second, _ = run_ideal_grasp(scenario, duration=4.5)
    np.testing.assert_array_equal(first.channels, second.channels)
    np.testing.assert_array_equal(first.taxels, second.taxels)
    assert first.sa.max() > 10.0  # the window covers contact and loading
