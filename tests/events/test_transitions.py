"""Transition names and the states they join."""

from tegrasp_drake.events.transitions import (REQUIRED_TRANSITIONS, TRANSITIONS,
                                              event_transition, transition_name,
                                              transition_states)


def test_a_transition_name_joins_its_two_states():
    assert transition_name("Reach", "Load") == "reach_load"
    for name in TRANSITIONS:
        assert transition_name(*transition_states(name)) == name
    assert transition_states("place_unload") == ("Place", "Unload")


def test_only_the_required_transitions_are_event_triggered():
    assert [event_transition(*transition_states(n)) for n in REQUIRED_TRANSITIONS] == \
        list(REQUIRED_TRANSITIONS)
    assert event_transition("Lift", "Hold") is None  # memorized, but ended by a timer
    assert event_transition("Reach", "Re-Reach") is None
