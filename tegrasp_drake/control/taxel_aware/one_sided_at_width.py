"""Rule one_sided_at_width (Reach while closing): one finger alone has touched for
re_reach.one_sided_contact_s while the gripper has closed to within
one_sided_width_margin_m of the object's width. The object is between the fingers already,
the other finger's contact off its pad or light: Load (the squeeze brings the second pad
on), never a Re-Reach that would shift by almost nothing and close on the same contact. It
comes before the paper's one_sided (priority 200)."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Load, decide
from tegrasp_drake.control.rule_engine import Rule
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
    then="Load")
