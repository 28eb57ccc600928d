"""Memorized events from an ensemble of randomised ideal grasps, for the
taxel_aware controller; the paper's one-clean-run events (record_events.py) stay as they are.

Each object's ideal open-loop grasp (Sec. III-A) is simulated `size` times, each with its
own draw of the perturbations below and its own sensor-noise seed; each run is cut into
windows around its physical events exactly as record_events does, and the windows of one
transition are combined by their mean.

Ranges (uniform on +-bound; ENSEMBLE_RANGES), and why:
  placement +-2 mm, yaw +-5 deg   the sweep's placement jitter (sweep/spec.py
                                  RandomisationConfig: an object set by hand on a marker) for
                                  x and y; yaw widened from the sweep's 3 deg toward a
                                  yawed box (10 deg) while keeping each run an ideal,
                                  centred grasp
  mass, friction +-10 %           the sweep's bounds: the spread between nominally equal
                                  objects and of a friction estimate from handbook ranges
                                  (docs/model.md, "Friction by material pair")
  sensor noise                    on: the taxels' 5 mN and the film's noise, each run its seed
Seeds: TRAINING_BASE_SEED + run, apart from every sweep's seeds (a sweep's seed is a CRC of
its base seed, object, marker and attempt; base seeds here start at 1_000_000).

Combination rule: the mean of the runs' max-normalised windows of a transition, aligned
on the physical event, max-normalised again. Eq. 3 is a normalised correlation; under a
signal-plus-independent-noise model of the runs the mean is the template whose expected
correlation with a new run is largest (the matched filter of the average shape), and the
noise of the template falls as 1/sqrt(runs). Several templates with the max score would
raise the false-trigger rate with each template added (the max of K noisy scores) and cost
K correlations per sample in the control loop; one mean costs the matcher nothing more.

Windows: Reach-Load is cut with its physical event PRE_TRANSITION_S["reach_load"] = 0.45 s
into the 0.5 s window, so the live window looks most like it 50 ms after first contact
(the paper's centred window matches 0.25 s after; the latency target is 60 ms). The other
transitions keep the paper's 0.25 s.
"""

import dataclasses
import logging

import numpy as np

from tegrasp_drake.events import extract_memorized_events, tactile_trial_from_log
from tegrasp_drake.events.correlation import normalize_by_max
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.runs.grasp_outcome import physical_events
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.recording.record_events import EVENT_OF_TRANSITION, RecordEventsError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario.trial_log_writer import package_versions
from tegrasp_drake.rig.objects import object_description

logger = logging.getLogger(__name__)

TRAINING_BASE_SEED = 1_000_000
PRE_TRANSITION_S = {"reach_load": 0.45, "load_lift": 0.25, "place_unload": 0.25}
ENSEMBLE_FOLDER = "ensemble"


@dataclasses.dataclass(frozen=True)
class EnsembleRanges:
    """Bounds of the uniform perturbations of an ensemble run (module doc: the sources)."""
    placement_xy_bound_m: float = 0.002
    yaw_bound_deg: float = 5.0
    mass_scale_bound: float = 0.10
    friction_scale_bound: float = 0.10
    sensor_noise: bool = True


ENSEMBLE_RANGES = EnsembleRanges()


def ensemble_scenario(object_name: str, run: int, ranges: EnsembleRanges = ENSEMBLE_RANGES,
                      base=None):
    """The scenario of ensemble run `run` of `object_name`: the object's scenario (or
    `base`) perturbed by a draw from seed TRAINING_BASE_SEED + run."""
    base = base or LoadScenario(name=object_name)
    seed = TRAINING_BASE_SEED + run
    rng = np.random.default_rng(seed)
    dx, dy = rng.uniform(-ranges.placement_xy_bound_m, ranges.placement_xy_bound_m, 2)
    yaw = rng.uniform(-ranges.yaw_bound_deg, ranges.yaw_bound_deg)
    mass, friction = 1.0 + rng.uniform(-1.0, 1.0, 2) * (ranges.mass_scale_bound,
                                                          ranges.friction_scale_bound)
    obj = dataclasses.replace(base.object, mass=base.object.mass * mass,
                              friction=base.object.friction * friction)
    scenario = dataclasses.replace(
        base, object=obj, random_seed=seed,
        object_offset=[base.object_offset[0] + dx, base.object_offset[1] + dy],
        object_yaw_deg=base.object_yaw_deg + yaw)
    if not ranges.sensor_noise:
        scenario = dataclasses.replace(
            scenario, tactile=dataclasses.replace(scenario.tactile, noise_std_n=0.0),
            vibration=dataclasses.replace(scenario.vibration, noise_std_mps2=0.0))
    return scenario


def run_events(log, scenario, object_name: str, nominal_object) -> dict[str, MemorizedEvent]:
    """One run's events, cut from its log with PRE_TRANSITION_S per transition."""
    events = physical_events(log, scenario.grasp.grip_force, scenario.object)
    missing = [name for name in EVENT_OF_TRANSITION.values() if events[name] is None]
    if missing:
        raise RecordEventsError(f"ensemble run of '{object_name}' (seed "
                                f"{scenario.random_seed}) shows no {', '.join(missing)}")
    cut = {}
    for transition, event_name in EVENT_OF_TRANSITION.items():
        trial = tactile_trial_from_log(log, {transition: events[event_name]})
        cut.update(extract_memorized_events(
            trial, object_name=object_name, sa_rate_hz=scenario.tactile.sample_rate_hz,
            ra_rate_hz=scenario.vibration.sample_rate_hz,
            pre_transition_s=PRE_TRANSITION_S[transition],
            scenario=f"ensemble run seed {scenario.random_seed}",
            package_versions=package_versions(),
            object_description=object_description(nominal_object)))
    return cut


def combine_runs(runs: list[dict[str, MemorizedEvent]], *, scenario_note: str
                 ) -> dict[str, MemorizedEvent]:
    """The ensemble's events: per transition, the mean of the runs' windows, max-normalised
    (module doc: why the mean). The transition time is the runs' mean."""
    if not runs:
        raise ValueError("an ensemble needs at least one run")
    combined = {}
    for transition in runs[0]:
        members = [run[transition] for run in runs]
        first = members[0]
        combined[transition] = dataclasses.replace(
            first, sa=normalize_by_max(np.mean([e.sa for e in members], axis=0)),
            ra=normalize_by_max(np.mean([e.ra for e in members], axis=0)),
            transition_time_s=float(np.mean([e.transition_time_s for e in members])),
            scenario=f"{scenario_note}; mean of {len(members)} runs")
    return combined


def record_ensemble_run(object_name: str, run: int, log_path=None,
                        ranges: EnsembleRanges = ENSEMBLE_RANGES):
    """Simulates ensemble run `run`; returns its events (and saves its log to log_path)."""
    scenario = ensemble_scenario(object_name, run, ranges)
    log, wall = run_ideal_grasp(scenario)
    logger.info("ensemble %s run %d: %.1f s wall", object_name, run, wall)
    if log_path is not None:
        log.meta["ensemble_run"] = run
        log.save(log_path)
    return run_events(log, scenario, object_name, LoadScenario(name=object_name).object)


# The runs whose mean makes the events (the package's ensembles: analysis/
# record_ensemble_events.py --template-runs 5).
TEMPLATE_RUNS = 5


def record_object_ensemble(object_name: str, scenario, runs: int = TEMPLATE_RUNS, *,
                           progress_of_run=None) -> dict[str, MemorizedEvent]:
    """The ensemble events of the object of `scenario` (a user's own object, or a built-in
    one): `runs` randomised ideal grasps around that scenario, combined by the mean.
    progress_of_run(k) gives run k's progress callback (or None). RecordEventsError when a
    run shows no physical event."""
    members = []
    for run in range(runs):
        perturbed = ensemble_scenario(object_name, run, base=scenario)
        log, wall = run_ideal_grasp(
            perturbed, progress=progress_of_run(run) if progress_of_run else None)
        logger.info("ensemble %s run %d: %.1f s wall", object_name, run, wall)
        members.append(run_events(log, perturbed, object_name, scenario.object))
    return combine_runs(members, scenario_note=(
        f"ensemble of ideal grasps of {object_name}, seeds {TRAINING_BASE_SEED}.."
        f"{TRAINING_BASE_SEED + runs - 1}"))
