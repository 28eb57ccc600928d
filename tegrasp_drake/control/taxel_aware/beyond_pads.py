"""Rule beyond_pads (closing, and the first Load): the first touch on one pad's
distal row alone and the close would topple the object: stop and Re-Reach forward
(contact_geometry.beyond_pads_shift). With no Re-Reach left it stands aside (docs/controller.md,
"A first touch beyond the pads stops the close")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.taxel_aware.contact_geometry import beyond_pads_shift
from tegrasp_drake.control.rule_actions import ReReach, decide, re_reach_allowed
from tegrasp_drake.control.rule_engine import Rule


def touched_beyond(situation) -> bool:
    return situation.estimate.touched_beyond_pads and re_reach_allowed(situation)


def stop_move_forward_and_centre(situation):
    e = situation.estimate
    shift = beyond_pads_shift(finger=e.first_touch_finger,
                              first_touch_opening_m=e.first_touch_opening_m,
                              object_width_m=e.object_width_m,
                              taxel_config=situation.config.taxel_aware)
    return decide(ReReach(shift), Trigger.CORRECTIVE,
                  f"the {e.first_touch_finger} pad's distal row alone touched first, the "
                  "close would push the object over: stop, move forward and centre")


BEYOND_PADS = Rule(
    "beyond_pads", (Mode.REACH, Mode.LOAD), 30, touched_beyond, stop_move_forward_and_centre,
    when="the first touch on one pad's distal row alone, the close would topple the "
    "object; Re-Reaches left",
    then="ReReach(forward half a pad, the push toward the pad)")
