"""Rules of an object caged behind the pads (contact_geometry.caged_behind_pads): the
fingers closed past an object that the first touch put on the pads' palm side and stopped
short on it, no pad touching it. It stands between the fingers' inner links and the palm,
and lifting carries it; no event comes (no taxel sees it), and a Re-Reach learns nothing
(its shift is zero, it closes the same way again).

  reach_timeout_caged  Reach, no Reach-Load event in time: Load it there
  load_timeout_caged   Load, no Load-Lift event in time: Lift it
  guard caged          holds back the paper's object_lost (no pad touches a caged object,
                       yet it is held), avoid_hit (its pads feel it rattle in the cage, not
                       a hit) and lift_load (squeezing harder cannot stop a slip of an
                       object no pad touches): the lift ends in Hold as the paper's does
"""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Lift, Load, decide
from tegrasp_drake.control.rule_engine import Guard, Rule
from tegrasp_drake.control.transition_logic import (load_timed_out, load_timeout_reason,
                                                    reach_timed_out, reach_timeout_reason)


def caged(situation) -> bool:
    return situation.estimate.caged_behind_pads


REACH_TIMEOUT_CAGED = Rule(
    "reach_timeout_caged", (Mode.REACH,), 390, lambda s: reach_timed_out(s) and caged(s),
    lambda s: decide(Load(), Trigger.CORRECTIVE, f"{reach_timeout_reason(s)}, the fingers "
                     "closed on the object behind the pads: load it there"),
    when="no Reach-Load event in time, the object caged behind the pads",
    then="Load")
LOAD_TIMEOUT_CAGED = Rule(
    "load_timeout_caged", (Mode.LOAD,), 390, lambda s: load_timed_out(s) and caged(s),
    lambda s: decide(Lift(), Trigger.CORRECTIVE, f"{load_timeout_reason(s)}, the fingers "
                     "hold the object behind the pads: lift"),
    when="no Load-Lift event in time, the object caged behind the pads",
    then="Lift")
CAGED = Guard(
    "caged", ("object_lost", "avoid_hit", "lift_load"), caged,
    when="the object caged behind the pads")
