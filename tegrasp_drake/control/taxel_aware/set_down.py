"""When a Place lets go: once the arm's Place move has ended, the object set down on the table
(set_down, which the re-grasp's Place also waits for), and the guard place_set_down that holds
the paper's place_event back until then (docs/controller.md, "Place: let go once set down")."""

from tegrasp_drake.control.rule_engine import Guard
from tegrasp_drake.control.transition_logic import placed


def place_move_ended(situation) -> bool:
    """The arm's Place move has ended: place_press below the height the object was picked up
    from, so a held object stands on the table (the robot's knowledge of the object's height
    without a table sensor)."""
    return situation.obs.motion_done


def set_down(situation) -> bool:
    """The Place move has ended, then the Place-Unload event or its timeout. The event alone
    is not enough: on the linkage hand its thresholds also pass on a held object's rest
    signals in the air."""
    return place_move_ended(situation) and placed(situation.obs, situation.config)


PLACE_SET_DOWN = Guard(
    "place_set_down", ("place_event",), lambda situation: not place_move_ended(situation),
    when="Place: the arm's Place move has not ended (the object not yet set down); "
    "place_timeout already counts from its end")
