"""Where the search for each event transition's physical event starts on a trial's
timeline: judge_trial searches from there (trial_judge.physical_event_times), and a trial
result's physical events may not come before it (TrialResult)."""

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.events.transitions import event_transition

# The mode whose last entry before an event transition starts the search for its physical
# event: first contact and the settled grip after the last Reach (a close before a Re-Reach
# is let go), the table touch after the last Place.
SEARCH_FROM = {"reach_load": Mode.REACH, "load_lift": Mode.REACH, "place_unload": Mode.PLACE}


def physical_event_search_starts(transitions) -> dict[str, float]:
    """{event transition: the time [s] its physical event is searched from} for each one
    (events/transitions.REQUIRED_TRANSITIONS) the timeline `transitions` (Transitions, in
    order) takes: the last entry into its SEARCH_FROM mode before the last such transition
    (the one whose event a result keeps); the trial's start (0) for Reach, where it starts."""
    starts, entered = {}, {Mode.REACH: 0.0}
    for entry in transitions:
        name = event_transition(entry.from_mode.label, entry.to_mode.label)
        if name in SEARCH_FROM:
            starts[name] = entered.get(SEARCH_FROM[name], 0.0)
        entered[entry.to_mode] = entry.t
    return starts
