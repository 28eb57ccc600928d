"""Rule bracket_recentre: one finger touches alone after the other touched at an earlier
close: Re-Reach to the faces' midpoint (docs/controller.md, "Fingers touching alone in turn
bracket the object")."""

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.control.rule_actions import re_reach_or_fail
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.taxel_aware.hands import PRISMATIC_ONLY
from tegrasp_drake.control.taxel_aware.moves import centring_shift
from tegrasp_drake.control.transition_logic import one_sided, touching_finger


def bracketed(situation) -> bool:
    return one_sided(situation) and situation.estimate.bracketed_width_m > 0.0


def midpoint_shift(situation) -> Shift:
    """The centring Re-Reach with its move along the stroke to the faces' midpoint [m, world]."""
    e = situation.estimate
    return Shift(centring_shift(situation).dx_m, e.bracket[0] - e.gripper_y_m)


def recentre(situation):
    return re_reach_or_fail(
        situation, midpoint_shift(situation),
        f"only the {touching_finger(situation)} finger touched, the other before it: "
        f"re-centre between the two faces ({1000 * situation.estimate.bracketed_width_m:.1f}"
        " mm apart)")


BRACKET_RECENTRE = Rule(
    "bracket_recentre", (Mode.REACH,), 190, bracketed, recentre,
    when="one finger alone, the other's face remembered",
    then="ReReach(to the faces' midpoint) or Failed", hands=PRISMATIC_ONLY)
