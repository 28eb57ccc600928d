"""Rule closed_untouched (Reach): the gripper closed on nothing and no taxel counted a touch
in the whole close, nor did the Reach-Load event match: the object is not in the band of the
approach axis the pads swept, so Re-Reach forward, the pads' centres onto the nearest centre
an untouched object can have (contact_geometry.untouched_reach_m). Any other close on nothing
is the paper's closed_on_nothing (docs/controller.md, "A close that touched nothing searches
beyond the fingertips"). Not after a taxel touch or a finger strike at an earlier close of
the trial: that put the object within the pads' reach, so a close on nothing now means it
moved (pushed or toppled), not that it lies beyond; that close is the paper's."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import ReReach, decide, re_reach_allowed
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift


def closed_untouched(situation) -> bool:
    e = situation.estimate
    return (situation.obs.closed_on_nothing and e.first_touch_opening_m < 0.0
            and not e.reach_matched and not e.touched_before
            and re_reach_allowed(situation))


def search_beyond_fingertips(situation):
    reach_m = situation.estimate.untouched_reach_m
    return decide(ReReach(Shift(reach_m, 0.0)), Trigger.CORRECTIVE,
                  "the gripper closed on nothing with no pad touched: the object lies "
                  f"beyond the fingertips; move {1000 * reach_m:.1f} mm forward")


CLOSED_UNTOUCHED = Rule(
    "closed_untouched", (Mode.REACH,), 290, closed_untouched, search_beyond_fingertips,
    when="the gripper closed on nothing (gOBJ 3), no taxel touched in the close nor at an earlier "
    "one, no finger strike, no Reach-Load match; Re-Reaches left",
    then="ReReach(forward: the pads' distal reach plus the object's half depth)")
