"""Rule one_sided_at_width (closing): one finger alone, the gripper closed to within
one_sided_width_margin_m of the object's width: Load, before the paper's one_sided
(docs/controller.md, "One finger alone at the object's width loads")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Load, decide
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.hands import PRISMATIC_ONLY
from tegrasp_drake.control.transition_logic import one_sided, touching_finger


def closed_to_width(situation) -> bool:
    e = situation.estimate
    return one_sided(situation) and (
        e.opening_m <= e.object_width_m + situation.config.taxel_aware.one_sided_width_margin_m)


def load(situation):
    return decide(Load(), Trigger.CORRECTIVE,
                  f"only the {touching_finger(situation)} finger touches, the gripper closed "
                  "to the object's width: load")


ONE_SIDED_AT_WIDTH = Rule(
    "one_sided_at_width", (Mode.REACH,), 170, closed_to_width, load,
    when="one finger alone for re_reach.one_sided_contact_s, closed to the width + margin",
    then="Load", hands=PRISMATIC_ONLY)
