"""Memorized events from an ensemble of randomised ideal grasps, for the taxel_aware
controller: a campaign of the object's ideal grasp, each run its own draw of ENSEMBLE_RANGES
and noise seed, combined by their mean; the first TEMPLATE_RUNS make the events, the rest
choose the thresholds. docs/controller.md, "Events from an ensemble of grasps"."""

import dataclasses

import numpy as np

from tegrasp_drake.recording.campaign import (ENSEMBLE_BASE_SEED, CampaignRun,
                                              record_campaign)
from tegrasp_drake.recording.paper_events import grasp_event_times
from tegrasp_drake.rig.objects import ENSEMBLE_EVENTS_FOLDER
from tegrasp_drake.scenario.scenario import LoadScenario

# Reach-Load 0.45 s in: it matches ~50 ms after contact (target 60 ms); else the paper's.
PRE_TRANSITION_S = {"reach_load": 0.45, "load_lift": 0.25, "place_unload": 0.25}
ENSEMBLE_FOLDER = ENSEMBLE_EVENTS_FOLDER  # the events folder's subfolder (rig/objects.py)
# The runs whose mean makes the events (analysis/record_ensemble_events.py --template-runs 5).
TEMPLATE_RUNS = 5


@dataclasses.dataclass(frozen=True)
class EnsembleRanges:
    """Bounds of the uniform perturbations of an ensemble run."""
    placement_xy_bound_m: float = 0.002  # the sweep's jitter: an object set by hand
    yaw_bound_deg: float = 5.0  # the sweep's 3 deg widened toward a yawed box, still centred
    mass_scale_bound: float = 0.10  # the sweep's: nominally equal objects' spread
    friction_scale_bound: float = 0.10  # the sweep's: a friction estimate from handbooks
    sensor_noise: bool = True  # each run its own noise seed


ENSEMBLE_RANGES = EnsembleRanges()


def ensemble_scenario(object_name: str, run: int, ranges: EnsembleRanges = ENSEMBLE_RANGES,
                      base=None):
    """Run `run`'s scenario: the object's (or `base`), perturbed from ENSEMBLE_BASE_SEED + run."""
    base = base or LoadScenario(name=object_name)
    seed = ENSEMBLE_BASE_SEED + run
    rng = np.random.default_rng(seed)
    dx, dy = rng.uniform(-ranges.placement_xy_bound_m, ranges.placement_xy_bound_m, 2)
    yaw = rng.uniform(-ranges.yaw_bound_deg, ranges.yaw_bound_deg)
    mass, friction = 1.0 + rng.uniform(-1.0, 1.0, 2) * (ranges.mass_scale_bound,
                                                          ranges.friction_scale_bound)
    obj = dataclasses.replace(base.object, mass=base.object.mass * mass,
                              friction=base.object.friction * friction)
    placement = base.placement
    scenario = dataclasses.replace(
        base, object=obj, random_seed=seed, placement=dataclasses.replace(
            placement, offset=[placement.offset[0] + dx, placement.offset[1] + dy],
            yaw_deg=placement.yaw_deg + yaw))
    if not ranges.sensor_noise:
        scenario = dataclasses.replace(
            scenario, tactile=dataclasses.replace(scenario.tactile, noise_std_n=0.0),
            vibration=dataclasses.replace(scenario.vibration, noise_std_mps2=0.0,
                                          adc_noise_lsb=0.0))
    return scenario


def ensemble_runs(object_name: str, runs: int, template_runs: int = TEMPLATE_RUNS,
                  base=None) -> list[CampaignRun]:
    """The campaign's runs: the first `template_runs` make the events, the rest are held out."""
    return [CampaignRun(f"run{k}", ensemble_scenario(object_name, k, base=base),
                        role="template" if k < template_runs else "held_out")
            for k in range(runs)]


def record_object_ensemble(object_name: str, scenario, runs: int = TEMPLATE_RUNS, *,
                           template_runs: int | None = None, log_dir=None,
                           progress_of_run=None):
    """The ensemble events of `scenario`'s object: `runs` randomised ideal grasps, the first
    `template_runs` combined by the mean; RecordEventsError when a run lacks an event;
    LogNotWritten carrying the events when a log cannot be written in `log_dir`
    (record_campaign)."""
    template_runs = runs if template_runs is None else template_runs
    return record_campaign(
        ensemble_runs(object_name, runs, template_runs, base=scenario), grasp_event_times,
        object_name=object_name, nominal_object=scenario.object,
        pre_transition_s=PRE_TRANSITION_S, log_dir=log_dir, progress_of_run=progress_of_run,
        note=(f"ensemble of ideal grasps of {object_name}, seeds {ENSEMBLE_BASE_SEED}.."
              f"{ENSEMBLE_BASE_SEED + template_runs - 1}"))
