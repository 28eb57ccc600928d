"""Rule off_centre (Reach, at the Reach-Load event a pad's touch confirms,
touch_confirmed.reach_load_confirmed): the contact is more than centre_tolerance_m off the
pads' centres along the approach axis: Re-Reach to centre it along both axes before loading
(docs/controller.md, "Re-Reach along both axes")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.taxel_aware.contact_geometry import approach_shift
from tegrasp_drake.control.rule_actions import ReReach, decide, re_reach_allowed
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.moves import centring_shift
from tegrasp_drake.control.taxel_aware.touch_confirmed import reach_load_confirmed


def event_off_centre(situation) -> bool:
    return (reach_load_confirmed(situation) and re_reach_allowed(situation)
            and approach_shift(situation.estimate.shape, situation.config.taxel_aware,
                               situation.estimate.pad_travel_to_grasp_m) != 0.0)


def centre_first(situation):
    offset = situation.estimate.shape.approach_offset_m
    return decide(ReReach(centring_shift(situation)), Trigger.CORRECTIVE,
                  f"contact {1000 * offset:+.1f} mm from the pads' centres along the "
                  "approach axis")


OFF_CENTRE = Rule(
    "off_centre", (Mode.REACH,), 90, event_off_centre, centre_first,
    when="Reach-Load event a pad's touch confirms, the contact off the pads' centres along "
    "the approach axis; "
    "Re-Reaches left",
    then="ReReach(centring, both axes)")
