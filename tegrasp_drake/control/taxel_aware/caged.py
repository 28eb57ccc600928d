"""Rules of an object caged behind the pads (contact_geometry.caged_behind_pads): the
fingers closed past an object that the first touch put on the pads' palm side and stopped
short on it, no pad touching it. It stands between the fingers' inner links and the palm,
and lifting carries it; no event comes (no taxel sees it), and a Re-Reach learns nothing
(its shift is zero, it closes the same way again).

  reach_timeout_caged  Reach, no Reach-Load event in time: Load it there
  load_timeout_caged   Load, no Load-Lift event in time: Lift it
  caged_lift_ended     Lift: Hold when the lift motion ends ...
  caged_no_lift_load   ... and no Lift-Load before: squeezing harder cannot stop a slip
                       of an object no pad touches
The object_lost and avoid_hit rules also stand aside for a caged object (its pads'
contact and RA say nothing about it)."""

from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger
from tegrasp_drake.control.taxel_aware.decision import Lift, Load, Reason, Rule, decide
from tegrasp_drake.control.taxel_aware.no_event_in_time import (
    load_timeout_reason, load_timed_out, reach_timed_out, reach_timeout_reason)


def caged(situation) -> bool:
    return situation.estimate.caged_behind_pads


REACH_TIMEOUT_CAGED = Rule(
    Reason.REACH_TIMEOUT_CAGED, lambda s: reach_timed_out(s) and caged(s),
    lambda s: decide(Load(), Trigger.CORRECTIVE, f"{reach_timeout_reason(s)}, the fingers "
                     "closed on the object behind the pads: load it there"),
    when="no Reach-Load event in time, the object caged behind the pads",
    then="Load")
LOAD_TIMEOUT_CAGED = Rule(
    Reason.LOAD_TIMEOUT_CAGED, lambda s: load_timed_out(s) and caged(s),
    lambda s: decide(Lift(), Trigger.CORRECTIVE, f"{load_timeout_reason(s)}, the fingers "
                     "hold the object behind the pads: lift"),
    when="no Load-Lift event in time, the object caged behind the pads",
    then="Lift")
CAGED_LIFT_ENDED = Rule(
    Reason.CAGED_LIFT_ENDED, lambda s: caged(s) and s.obs.motion_done,
    lambda s: Decision(Mode.HOLD, Trigger.TIMER, "lift motion ended"),
    when="caged, the lift motion ended",
    then="Hold")
CAGED_NO_LIFT_LOAD = Rule(
    Reason.CAGED_NO_LIFT_LOAD, caged, lambda s: None,
    when="caged",
    then="Stay (no Lift-Load)")
