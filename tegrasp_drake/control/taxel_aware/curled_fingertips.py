"""Rule curled_fingertips (closing, the linkage hand): the close's first touch came at an
opening no flat pad reaches the object at (contact_geometry.curled_touch): the fingers met it
below their flip height and curled past it, and their fingertips now press its far side, the
object between the proximal links. Read as positions along the approach, the touching rows
(the distal ones) would move the hand forward into it. Stop the close and Re-Reach along the
approach by where the linkage's closed form puts the object's centre, from the opening and
the touching rows (gripper_hands.LinkageHand.hooked_object_offset): back, toward the palm
side (docs/controller.md, "Curled fingertips hook the object's far side")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import ReReach, decide, re_reach_allowed
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.taxel_aware.hands import LINKAGE_ONLY


def hooked(situation) -> bool:
    return situation.estimate.hooked_object_dx_m is not None and re_reach_allowed(situation)


def back_off_onto_it(situation):
    e = situation.estimate
    dx = e.hooked_object_dx_m
    return decide(ReReach(Shift(dx, 0.0)), Trigger.CORRECTIVE,
                  f"first touch at {1000 * e.first_touch_opening_m:.1f} mm open, the object "
                  f"{1000 * e.object_width_m:.1f} mm across: the fingertips curled past it; "
                  f"its centre lies {1000 * dx:+.1f} mm along the approach")


CURLED_FINGERTIPS = Rule(
    "curled_fingertips", (Mode.REACH,), 28, hooked, back_off_onto_it,
    when="the close's first touch at an opening below the object's width less both pads' "
    "elastomer (fingers curled past it); Re-Reaches left",
    then="ReReach(along the approach to the object's centre by the linkage's closed form)",
    hands=LINKAGE_ONLY)
