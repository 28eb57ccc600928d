"""Rules held_tilted (Hold: tilted for tilt_sustain_s, put it down) and
regrasp_after_place (Place: open and close again without a shift), at most max_regrasps, and
the guard regrasp_set_down (a re-grasp's Place ends by regrasp_after_place alone)
(docs/controller.md, "Held tilted: re-grasp")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Regrasp, ReReach, decide
from tegrasp_drake.control.rule_engine import Guard, Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.taxel_aware.set_down import set_down


def tilted_for_long(situation) -> bool:
    regrasp = situation.config.taxel_aware.regrasp
    return (regrasp.enabled and situation.estimate.tilted_s >= regrasp.tilt_sustain_s
            and situation.counters.regrasps < regrasp.max_regrasps)


def put_down(situation):
    return decide(Regrasp(), Trigger.CORRECTIVE, "held tilted: put down to re-grasp")


def regrasp_place(situation) -> bool:
    """This Place puts a tilted object down to grasp it again."""
    return situation.obs.regrasp_pending


def set_down_to_regrasp(situation) -> bool:
    """A re-grasp's Place has set the object down (set_down.set_down: the Place move has
    ended, then the Place-Unload event or its timeout)."""
    return regrasp_place(situation) and set_down(situation)


def open_and_close_again(situation):
    return decide(ReReach(Shift(0.0, 0.0), counted=False), Trigger.CORRECTIVE,
                  "re-grasp: open and close again")


HELD_TILTED = Rule(
    "held_tilted", (Mode.HOLD,), 150, tilted_for_long, put_down,
    when="held tilted for regrasp.tilt_sustain_s; re-grasps left",
    then="Regrasp (Place)")
REGRASP_AFTER_PLACE = Rule(
    "regrasp_after_place", (Mode.PLACE,), 50, set_down_to_regrasp, open_and_close_again,
    when="a re-grasp's Place: the arm's Place move ended (the object set down), then the "
    "Place-Unload event or place.event_timeout_s", then="ReReach(no shift, not counted)")
REGRASP_SET_DOWN = Guard(
    "regrasp_set_down", ("place_event", "place_timeout"), regrasp_place,
    when="a re-grasp's Place: it ends by regrasp_after_place, never by letting go")
