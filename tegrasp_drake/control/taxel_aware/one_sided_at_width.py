"""Rule one_sided_at_width (Reach while closing): one finger alone has touched for
one_sided_contact_s while the gripper has closed to within one_sided_width_margin_m of the
object's width. The object is between the fingers already, the other finger's contact off
its pad or light: Load (the squeeze brings the second pad on), never a Re-Reach that would
shift by almost nothing and close on the same contact."""

from tegrasp_drake.control.grasp_modes import Trigger
from tegrasp_drake.control.taxel_aware.decision import Load, Reason, Rule, decide


def one_sided(situation) -> bool:
    """One finger alone has touched for one_sided_contact_s while closing."""
    return situation.obs.one_sided_s >= situation.config.one_sided_contact_s


def touching_finger(situation) -> str:
    return "left" if situation.obs.contact[0] else "right"


def closed_to_width(situation) -> bool:
    e = situation.estimate
    return one_sided(situation) and (
        e.opening_m <= e.object_width_m + situation.taxel.one_sided_width_margin_m)


def load(situation):
    return decide(Load(), Trigger.CORRECTIVE,
                  f"only the {touching_finger(situation)} finger touches, the gripper closed "
                  "to the object's width: load")


ONE_SIDED_AT_WIDTH = Rule(
    Reason.ONE_SIDED_AT_WIDTH, closed_to_width, load,
    when="one finger alone for one_sided_contact_s, closed to the width + margin",
    then="Load")
