"""The grasp transitions that memorized tactile events can trigger, in grasp order, each
anchored on a physical event of the ideal grasp (extraction.py). A name is `from_to` in
lower case (reach_load)."""

# The value of an `expected_event` or `scored_event` port when no event is expected.
NO_EVENT = -1

TRANSITIONS = {
    "reach_load": "first contact of the fingers with the object",
    "load_lift": "the lift starts (the end of the ideal grasp's Load phase)",
    "lift_hold": "the object lifts off the table",
    "place_unload": "the object touches the table",
    # Corrective events (recording/corrective_events.py): the situations that
    # start a corrective action, memorized in their own folder (events/corrective/).
    "lift_load": "the pads slip up along the object during Lift",
    "hold_avoid": "an external hit on the held object",
}
# The transitions the state machine triggers by an event, in grasp order.
REQUIRED_TRANSITIONS = ("reach_load", "load_lift", "place_unload")
# The corrective events a corrective events folder holds for each object, in order.
CORRECTIVE_TRANSITIONS = ("lift_load", "hold_avoid")
# The transitions of the grasp itself, in grasp order: an object's events of these come from
# one grasp (one_grasp.py); each corrective event comes from runs of its own.
GRASP_TRANSITIONS = tuple(name for name in TRANSITIONS if name not in CORRECTIVE_TRANSITIONS)


def transition_order(name: str) -> int:
    """Position of transition `name` in the grasp; ValueError for an unknown name."""
    try:
        return list(TRANSITIONS).index(name)
    except ValueError:
        raise ValueError(
            f"unknown transition '{name}'; known: {', '.join(TRANSITIONS)}") from None


def transition_name(from_state: str, to_state: str) -> str:
    """`from_to` in lower case, e.g. ("Reach", "Load") -> reach_load."""
    return f"{from_state}_{to_state}".lower()


def transition_states(name: str) -> tuple[str, str]:
    """The (from, to) state names of transition `name`, e.g. reach_load -> (Reach, Load)."""
    from_state, to_state = name.split("_")
    return from_state.capitalize(), to_state.capitalize()


def event_transition(from_state: str, to_state: str) -> str | None:
    """The REQUIRED_TRANSITIONS name of from_state -> to_state (e.g. place_unload), else None."""
    name = transition_name(from_state, to_state)
    return name if name in REQUIRED_TRANSITIONS else None
