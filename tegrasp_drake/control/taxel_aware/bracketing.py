"""Rules bracketed_at_extent (closed to within one_sided_width_margin_m of the
faces' extent: Load) and bracket_recentre (else Re-Reach to the faces' midpoint): one finger
touches alone after the other touched at an earlier close (docs/controller.md, "Fingers
touching alone in turn bracket the object")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Load, decide, re_reach_or_fail
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.taxel_aware.hands import PRISMATIC_ONLY
from tegrasp_drake.control.taxel_aware.moves import centring_shift
from tegrasp_drake.control.transition_logic import one_sided, touching_finger


def closed_to_extent(situation) -> bool:
    e = situation.estimate
    extent = e.bracketed_width_m
    return (one_sided(situation) and extent > e.object_width_m
            and e.opening_m <= extent + situation.config.taxel_aware.one_sided_width_margin_m)


def load(situation):
    return decide(Load(), Trigger.CORRECTIVE,
                  f"only the {touching_finger(situation)} finger touches, the gripper closed "
                  f"to the object's extent between both fingers' touches "
                  f"({1000 * situation.estimate.bracketed_width_m:.1f} mm): load")


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


BRACKETED_AT_EXTENT = Rule(
    "bracketed_at_extent", (Mode.REACH,), 180, closed_to_extent, load,
    when="one finger alone, the other's face remembered, closed to their extent + margin",
    then="Load", hands=PRISMATIC_ONLY)
BRACKET_RECENTRE = Rule(
    "bracket_recentre", (Mode.REACH,), 190, bracketed, recentre,
    when="one finger alone, the other's face remembered",
    then="ReReach(to the faces' midpoint) or Failed", hands=PRISMATIC_ONLY)
