"""Memorizing the tactile events of the ideal grasp (Sec. III-A).

For one object, the ideal open-loop grasp is simulated on its scenario, the SA (Eq. 1, at
the taxel rate) and RA (Eq. 2, at 1 kHz) channels are cut into 0.5 s windows around the
physical events that mark the transitions (EVENT_OF_TRANSITION: first contact ->
reach_load, grip force reached -> load_lift, table touch -> place_unload) and normalised
by their maxima (format: tegrasp_drake/events/FORMAT.md). `tegrasp record-events` stores
them in the events folder with an index.
"""

import logging

from tegrasp_drake.events import extract_memorized_events, tactile_trial_from_log
from tegrasp_drake.experiments.grasp_outcome import physical_events
from tegrasp_drake.experiments.ideal_grasp import run_ideal_grasp
from tegrasp_drake.experiments.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.experiments.trial_logging import package_versions

logger = logging.getLogger(__name__)

EVENT_OF_TRANSITION = {"reach_load": "first_contact", "load_lift": "grip_force_reached",
                       "place_unload": "table_touch"}


def record_events(object_name: str, scenario=None, *, progress=None):
    """Runs the ideal grasp of one object (a built-in one by name, or the object of
    `scenario`); returns its MemorizedEvents. progress: as run_ideal_grasp's."""
    scenario = scenario or LoadScenario(name=object_name)
    log, _ = run_ideal_grasp(scenario, progress=progress)
    events = physical_events(log, scenario.grasp.grip_force, scenario.object)
    logger.info("%s: physical events of the ideal grasp at %s", object_name,
                {name: events[name] for name in EVENT_OF_TRANSITION.values()})
    missing = [name for name in EVENT_OF_TRANSITION.values() if events[name] is None]
    if missing:
        raise RuntimeError(f"the ideal grasp of {object_name} shows no {', '.join(missing)}")
    trial = tactile_trial_from_log(log, {transition: events[event] for transition, event
                                         in EVENT_OF_TRANSITION.items()})
    return extract_memorized_events(
        trial, object_name=object_name, sa_rate_hz=scenario.tactile.sample_rate_hz,
        ra_rate_hz=scenario.vibration.sample_rate_hz, scenario=scenario_to_yaml(scenario),
        package_versions=package_versions())
