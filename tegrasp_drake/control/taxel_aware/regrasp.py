"""Rules held_tilted (Hold: tilted for tilt_sustain_s, put it down) and
regrasp_after_place (Place: open and close again without a shift), at most max_regrasps
(docs/controller.md, "Held tilted: re-grasp")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Regrasp, ReReach, decide
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.transition_logic import placed


def tilted_for_long(situation) -> bool:
    regrasp = situation.config.taxel_aware.regrasp
    return (regrasp.enabled and situation.estimate.tilted_s >= regrasp.tilt_sustain_s
            and situation.counters.regrasps < regrasp.max_regrasps)


def put_down(situation):
    return decide(Regrasp(), Trigger.CORRECTIVE, "held tilted: put down to re-grasp")


def placed_to_regrasp(situation) -> bool:
    return situation.obs.regrasp_pending and placed(situation.obs, situation.config)


def open_and_close_again(situation):
    return decide(ReReach(Shift(0.0, 0.0), counted=False), Trigger.CORRECTIVE,
                  "re-grasp: open and close again")


HELD_TILTED = Rule(
    "held_tilted", (Mode.HOLD,), 150, tilted_for_long, put_down,
    when="held tilted for regrasp.tilt_sustain_s; re-grasps left",
    then="Regrasp (Place)")
REGRASP_AFTER_PLACE = Rule(
    "regrasp_after_place", (Mode.PLACE,), 50, placed_to_regrasp, open_and_close_again,
    when="a re-grasp's Place: the object stands again",
    then="ReReach(no shift, not counted)")
