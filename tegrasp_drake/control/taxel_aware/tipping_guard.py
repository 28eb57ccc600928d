"""Guard tipping_guard: the close pushed the object past its tipping limit
(contact_geometry.release_topples), so off_centre is held back and the paper's reach_event
loads it where it is (docs/controller.md, "Not after a push past the tipping limit")."""

from tegrasp_drake.control.rule_engine import Guard
from tegrasp_drake.control.taxel_aware.hands import PRISMATIC_ONLY


def pushed_over(situation) -> bool:
    return situation.estimate.topples_if_released


TIPPING_GUARD = Guard(
    "tipping_guard", ("off_centre",), pushed_over,
    when="the close pushed the object past its tipping limit", hands=PRISMATIC_ONLY)
