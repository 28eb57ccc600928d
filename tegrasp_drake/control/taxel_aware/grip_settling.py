"""Guard grip_settling (Load): the Load-Lift event lifts only a settled grip, both pads
above contact_force_n and the 2F-85 reporting its fingers stopped on the object while closing
(gOBJ 2). Until then the event is held back; with both pads on, load_timeout_both_pads
(no_event_in_time.py) still lifts at the Load timeout. docs/controller.md, "Lift a settled
grip"."""

from tegrasp_drake.control.rule_engine import Guard


def grip_settled(contact: tuple, stopped_on_object: bool) -> bool:
    """Whether the grip has settled: both pads touch ((left, right) SA above contact_force_n,
    what the object_lost check reads in Lift) and the gripper stopped on the object while
    closing. The 2F-85 stops only when its motor reaches the requested grip force through the
    linkage; an object pushed by one finger alone slides or tips long before that."""
    return all(contact) and stopped_on_object


def grip_settling(situation) -> bool:
    return situation.estimate.grip_settling


GRIP_SETTLING = Guard(
    "grip_settling", ("load_lift_event",), grip_settling,
    when="the grip has not settled: a pad at or below contact_force_n, or the fingers not "
    "stopped on the object (gOBJ 2)")
