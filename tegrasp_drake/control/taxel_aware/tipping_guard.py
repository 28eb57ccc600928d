"""Guard tipping_guard (Reach, at the Reach-Load event): the close has pushed the object
past its tipping limit (contact_geometry.release_topples); both pads hold it tilted on
them, and opening to re-centre it would let it fall. It holds back off_centre: the
paper's reach_event loads it where it is, since grasping it off-centre holds it (open
loop does) and re-centring it knocks it over."""

from tegrasp_drake.control.rule_engine import Guard


def pushed_over(situation) -> bool:
    return situation.estimate.topples_if_released


TIPPING_GUARD = Guard(
    "tipping_guard", ("off_centre",), pushed_over,
    when="the close pushed the object past its tipping limit")
