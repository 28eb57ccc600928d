"""The ensemble events' perturbations and their combination rule."""

import dataclasses
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.recording.ensemble_events import (
    ENSEMBLE_RANGES, ensemble_scenario)
from tegrasp_drake.recording.campaign import ENSEMBLE_BASE_SEED, combine_runs
from tegrasp_drake.scenario.scenario import LoadScenario
from tests.cheap_contact import cheap_contact_arguments


def event(sa_row, ra_row, t=1.0):
    """Four samples a channel: a 0.25 s window at the slowest rate an event may have."""
    return MemorizedEvent(object_name="box", transition="reach_load",
                          sa=np.array([sa_row, sa_row], dtype=float),
                          ra=np.array([ra_row, ra_row], dtype=float), sa_rate_hz=16.0,
                          ra_rate_hz=16.0, window_s=0.25, pre_transition_s=0.125,
                          transition_time_s=t)


def test_the_combined_event_is_the_max_normalised_mean_of_the_runs():
    runs = [{"reach_load": event([0, 0.5, 1, 1], [0, 1, 0, 0], t=1.0)},
            {"reach_load": event([0, 1, 1, 1], [0, 0, 1, 0], t=2.0)}]
    combined = combine_runs(runs, note="test")["reach_load"]
    np.testing.assert_allclose(combined.sa[0], [0, 0.75, 1, 1])
    np.testing.assert_allclose(combined.ra[0], [0, 1, 1, 0])
    assert combined.transition_time_s == pytest.approx(1.5)
    assert "mean of 2 runs" in combined.scenario
    with pytest.raises(ValueError):
        combine_runs([], note="none")


def test_each_run_is_perturbed_within_its_ranges_from_its_own_seed():
    base = LoadScenario(name="box")
    draws = [ensemble_scenario("box", run) for run in range(20)]
    for run, scenario in enumerate(draws):
        assert scenario.random_seed == ENSEMBLE_BASE_SEED + run
        assert abs(scenario.placement.offset[0]) <= ENSEMBLE_RANGES.placement_xy_bound_m
        assert abs(scenario.placement.offset[1]) <= ENSEMBLE_RANGES.placement_xy_bound_m
        assert abs(scenario.placement.yaw_deg) <= ENSEMBLE_RANGES.yaw_bound_deg
        assert abs(scenario.object.mass / base.object.mass - 1) <= ENSEMBLE_RANGES.mass_scale_bound
        assert abs(scenario.object.friction / base.object.friction - 1) <= (
            ENSEMBLE_RANGES.friction_scale_bound)
    assert len({s.placement.yaw_deg for s in draws}) == 20  # each its own draw
    assert ensemble_scenario("box", 3).placement.offset == draws[3].placement.offset  # repeatable
    quiet = ensemble_scenario("box", 0, dataclasses.replace(ENSEMBLE_RANGES, sensor_noise=False))
    assert quiet.tactile.noise_std_n == 0.0


@pytest.mark.slow
def test_an_ensemble_run_with_an_untouched_noise_free_pad_stops_with_one_line(tmp_path):
    """The memorizing world's sensors are noise-free: in a perturbed ensemble run one pad
    is still untouched at the Reach-Load window, its SA reads exactly zero, and no window
    of it could ever match; the command says which run, which channel and what to do."""
    repository = Path(__file__).resolve().parents[2]
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        e for e in (str(repository), os.environ.get("PYTHONPATH", "")) if e)}
    # The cheap contact: the claim is the one-line error for a pad the run leaves
    # untouched, which the placement decides, not the pads' meshing.
    done = subprocess.run(
        [sys.executable, "-m", "tegrasp_drake.cli", "record-events", "--scenario-name",
         "memorizing_world", "--ensemble-runs", "1", "--events",
         str(tmp_path / "events"), "-q", *cheap_contact_arguments()],
        env=environment, capture_output=True, text=True, timeout=900)
    assert done.returncode == 1
    (line,) = done.stderr.strip().splitlines()
    assert "Traceback" not in done.stderr
    assert line.startswith("tegrasp: error: run0 of 'box'")
    assert "are zero throughout the window" in line and "--ensemble-runs 0" in line
