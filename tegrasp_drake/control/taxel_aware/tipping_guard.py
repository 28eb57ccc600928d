"""Rule tipping_guard (Reach, at the Reach-Load event): the close has pushed the object past
its tipping limit (contact_geometry.release_topples); both pads hold it tilted on them, and
opening to re-centre it would let it fall. Load where it is, by the event: grasping it
off-centre holds it (open loop does), re-centring it knocks it over. It stands before
off_centre, which it holds back."""

from tegrasp_drake.control.taxel_aware.decision import Load, Reason, Rule, decide


def event_with_object_pushed_over(situation) -> bool:
    return situation.obs.event_matched and situation.estimate.topples_if_released


def load_where_it_is(situation):
    return decide(Load(), situation.event_trigger, "Reach-Load event")


TIPPING_GUARD = Rule(
    Reason.TIPPING_GUARD, event_with_object_pushed_over, load_where_it_is,
    when="Reach-Load event, the close pushed the object past its tipping limit",
    then="Load (event)")
