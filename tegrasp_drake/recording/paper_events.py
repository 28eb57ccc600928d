"""Memorizing the tactile events of the ideal grasp (Sec. III-A): the paper's campaign.

For one object, the ideal open-loop grasp is simulated once on its scenario, the SA (Eq. 1,
at the taxel rate) and RA (Eq. 2, at 1 kHz) channels are cut into 0.5 s windows around the
physical events that mark the transitions (EVENT_OF_TRANSITION: first contact ->
reach_load, the scripted start of the lift -> load_lift, table touch -> place_unload) and
normalised by their maxima (format: tegrasp_drake/events/FORMAT.md; the cutting:
campaign.py).

Load-Lift is anchored where the paper cuts it: at a transition point of the pre-programmed
grasp, the end of its Load phase (the script's segment times), not at a force threshold.
The grip must have settled by then: the lift must start with at least GRIP_FRACTION of the
settled grip on the weaker pad (grasp_outcome.grip_fraction_at), else the Load phase
(grasp.load_s) is too short for the gripper's drive and the recording stops and says so.
`tegrasp record-events` stores them in the events folder with an index.
"""

import logging
from collections.abc import Callable

from tegrasp_drake.recording.campaign import CampaignRun, RecordEventsError, cut_events
from tegrasp_drake.runs.grasp_outcome import (GRIP_FRACTION, first_contact_time,
                                              grip_fraction_at, physical_events,
                                              scripted_lift_start, true_sa)
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.scenario.scenario import Scenario
from tegrasp_drake.rig.api_boundary import public_api
from tegrasp_drake.rig.event_matching import EventMatchingConfig

logger = logging.getLogger(__name__)

__all__ = ["EVENT_OF_TRANSITION", "RecordEventsError", "grasp_event_times", "record_events"]

EVENT_OF_TRANSITION = {"reach_load": "first_contact", "load_lift": "lift_start",
                       "place_unload": "table_touch"}
# [s] of the 0.5 s window before the physical event (extraction.py; the paper's centred
# 0.25 s where not given). Load-Lift's window ends at the start of the lift: the controller
# triggers the lift on this event, so it cannot feel the lift before it matches, and the
# lift's first 0.25 s in a centred window kept a settled Load from matching in closed loop
# (on the box, dev seed 600: RA at most 0.72 and 0.57 against the paper's 0.7).
PRE_TRANSITION_S = {"load_lift": 0.5}
# [s] of the ideal grasp's approach on which each RA channel's noise floor is measured; an
# RA window that stays within it (Load-Lift's held grip: only the converter's noise) is
# stored flat, "expects no change" (extraction.py, ra_noise_floor.py): the live floor's
# default quiet period (controller.matching.ra_noise_quiet_s), within the approach.
QUIET_APPROACH_S = EventMatchingConfig().ra_noise_quiet_s


def lift_grip_fraction(log, scenario) -> float | None:
    """The weaker pad's true force when the script starts the lift, as a fraction of the
    settled grip (grasp_outcome.grip_fraction_at); None without a scripted lift."""
    lift = scripted_lift_start(log)
    if lift is None:
        return None
    return grip_fraction_at(log, lift, scenario.grasp.grip_force)


def grasp_event_times(log, scenario) -> dict[str, float | None]:
    """When the grasp's transitions' physical events happened in a run [s] (None: not
    seen), from the simulation's truth (grasp_outcome.physical_events). Load-Lift counts as
    not seen when the lift starts before the grip has settled (module doc)."""
    events = physical_events(log, scenario.grasp.grip_force, scenario.object)
    times = {transition: events[event] for transition, event in EVENT_OF_TRANSITION.items()}
    fraction = lift_grip_fraction(log, scenario)
    if fraction is None or fraction < GRIP_FRACTION:
        times["load_lift"] = None
    return times


def missing_event_advice(transition: str, log, scenario) -> str:
    """Why the ideal grasp showed no physical event of `transition`, and what to change."""
    grip = scenario.grasp.grip_force
    fraction = lift_grip_fraction(log, scenario)
    if transition == "load_lift" and fraction is not None and fraction > 0.0:
        return (f"the lift starts at {scripted_lift_start(log):.3f} s with {fraction:.0%} of "
                f"the settled grip on the weaker pad (first contact at "
                f"{first_contact_time(log):.3f} s): the grip has not settled by the end of "
                f"Load; lengthen grasp.load_s (now {scenario.grasp.load_s:g} s from the close "
                "command)")
    if transition == "load_lift":
        sa = true_sa(log)
        peak = float(sa.min(axis=1).max()) if len(sa) else 0.0
        return (f"the weaker pad's force peaked at {peak:.2f} N (commanded grasp.grip_force = "
                f"{grip:g} N): the fingers never squeezed the object with both pads, so "
                "check object.size against the gripper's 85 mm stroke and placement.offset")
    if transition == "reach_load":
        return ("the fingers never touched the object: check object.size, placement.offset and "
                "placement.expected_xy")
    return ("the object never came back to the table after a lift: check that the grasp "
            "lifts it (object.mass, object.friction, grasp.grip_force)")


@public_api
def record_events(object_name: str, scenario: Scenario | None = None, *,
                  progress: Callable | None = None):
    """Runs the ideal grasp of one object (a built-in one by name, or the object of
    `scenario`); returns its MemorizedEvents. progress: as run_ideal_grasp's.
    RecordEventsError when a physical event is missing."""
    scenario = scenario or LoadScenario(name=object_name)
    log, _ = run_ideal_grasp(scenario, progress=progress)
    times = grasp_event_times(log, scenario)
    logger.info("%s: physical events of the ideal grasp at %s; the lift starts with %s of "
                "the settled grip", object_name, times, lift_grip_fraction(log, scenario))
    run = CampaignRun("the ideal grasp", scenario)
    return cut_events(log, run, times, object_name=object_name,
                      nominal_object=scenario.object, pre_transition_s=PRE_TRANSITION_S,
                      note=scenario_to_yaml(scenario), quiet_ra_s=QUIET_APPROACH_S,
                      advice=lambda transition: missing_event_advice(transition, log,
                                                                     scenario))
