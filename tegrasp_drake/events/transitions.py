"""The grasp transitions that memorized tactile events can trigger, in grasp order.

Each transition is anchored on a physical event of the ideal grasp; the memorized window
is cut around the time of that physical event (extraction.py). The paper triggers
Reach-Load, Load-Lift and Place-Unload by tactile events (its Fig. 9); every object's
memorized events include those three. Lift-Hold is optional: record it where the lift-off
leaves a clear tactile trace.
"""

TRANSITIONS = {
    "reach_load": "first contact of the fingers with the object",
    "load_lift": "target grip force reached",
    "lift_hold": "the object lifts off the table",
    "place_unload": "the object touches the table",
}
REQUIRED_TRANSITIONS = ("reach_load", "load_lift", "place_unload")


def transition_order(name: str) -> int:
    """Position of transition `name` in the grasp; ValueError for an unknown name."""
    try:
        return list(TRANSITIONS).index(name)
    except ValueError:
        raise ValueError(
            f"unknown transition '{name}'; known: {', '.join(TRANSITIONS)}") from None
