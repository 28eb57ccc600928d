"""Rule approach_contact (Reach, in the approach): a pad touched the object for
re_reach.one_sided_contact_s before the close: back off and shift (moves.centring_shift),
approach again (docs/controller.md, "Approach contact")."""

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.control.rule_actions import re_reach_or_fail
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.hands import PRISMATIC_ONLY
from tegrasp_drake.control.taxel_aware.moves import centring_shift


def touches_in_approach(situation) -> bool:
    return (situation.estimate.approach_contact_s
            >= situation.config.re_reach.one_sided_contact_s)


def stop_back_off_and_shift(situation):
    pads = [name for name, touching in zip(("left", "right"), situation.obs.contact)
            if touching]
    return re_reach_or_fail(situation, centring_shift(situation),
                            f"the {' and '.join(pads) or 'a'} pad touched during the approach")


APPROACH_CONTACT = Rule(
    "approach_contact", (Mode.REACH,), 20, touches_in_approach, stop_back_off_and_shift,
    when="a pad touched for re_reach.one_sided_contact_s in the approach",
    then="ReReach(back off, the paper's shift) or Failed", hands=PRISMATIC_ONLY)
