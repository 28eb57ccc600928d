"""Memorizing the tactile events of the ideal grasp (Sec. III-A): the paper's campaign. The
ideal open-loop grasp of one object is cut into 0.5 s windows around the physical events of
EVENT_OF_TRANSITION (campaign.py, events/FORMAT.md); the lift must start with GRIP_FRACTION
of the settled grip on the weaker pad, else the recording says to lengthen grasp.load_s."""

import logging
from collections.abc import Callable
from typing import Annotated

from tegrasp_drake.recording.campaign import CampaignRun, RecordEventsError, cut_events
from tegrasp_drake.scenario.grasp_outcome import (GRIP_FRACTION, first_contact_time,
                                                  grip_fraction_at, object_sa, physical_events,
                                                  scripted_lift_start)
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.scenario.scenario import Scenario
from tegrasp_drake.rig.api_boundary import public_api
from tegrasp_drake.rig.event_matching import EventMatchingConfig
from tegrasp_drake.rig.objects import OBJECT_NAME

logger = logging.getLogger(__name__)

__all__ = ["EVENT_OF_TRANSITION", "RecordEventsError", "grasp_event_times", "record_events"]

EVENT_OF_TRANSITION = {"reach_load": "first_contact", "load_lift": "lift_start",
                       "place_unload": "table_touch"}
# [s] of the window before the physical event (else the paper's centred 0.25 s): Load-Lift's
# ends at the lift's start, on which the controller lifts.
PRE_TRANSITION_S = {"load_lift": 0.5}
# [s] of the approach that measures each RA channel's noise floor (the live floor's quiet
# period); an RA window within it is stored flat, "expects no change" (ra_noise_floor.py).
QUIET_APPROACH_S = EventMatchingConfig().ra_noise_quiet_s


def lift_grip_fraction(log, scenario) -> float | None:
    """The weaker pad's force at the script's lift as a fraction of the settled grip, or None."""
    lift = scripted_lift_start(log)
    if lift is None:
        return None
    return grip_fraction_at(log, lift, scenario.grasp.grip_force)


def grasp_event_times(log, scenario) -> dict[str, float | None]:
    """When the transitions' physical events happened in a run [s] (None: not seen), from the
    simulation's truth; Load-Lift is not seen when the lift starts before the grip settled."""
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
        sa = object_sa(log)
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
def record_events(object_name: Annotated[str, OBJECT_NAME], scenario: Scenario | None = None,
                  *, progress: Callable | None = None):
    """Runs the ideal grasp of one object (built-in by name, or `scenario`'s); returns its
    MemorizedEvents; RecordEventsError when a physical event is missing."""
    scenario = scenario or LoadScenario(name=object_name)
    log, _ = run_ideal_grasp(scenario, progress=progress)
    return events_of_ideal_grasp(log, scenario, object_name)


def events_of_ideal_grasp(log, scenario: Scenario, object_name: str):
    """The MemorizedEvents cut from `log`, the TrialLog of `scenario`'s ideal grasp (what
    record_events does after simulating it); RecordEventsError when a physical event is
    missing."""
    times = grasp_event_times(log, scenario)
    logger.info("%s: physical events of the ideal grasp at %s; the lift starts with %s of "
                "the settled grip", object_name, times, lift_grip_fraction(log, scenario))
    run = CampaignRun("the ideal grasp", scenario)
    return cut_events(log, run, times, object_name=object_name,
                      nominal_object=scenario.object, pre_transition_s=PRE_TRANSITION_S,
                      note=scenario_to_yaml(scenario), quiet_ra_s=QUIET_APPROACH_S,
                      advice=lambda transition: missing_event_advice(transition, log,
                                                                     scenario))
