"""Rules of an object caged behind the pads (contact_geometry.caged_behind_pads):
Load, then Lift, at the event timeouts; the guard `caged` holds back object_lost, avoid_hit
and lift_load, which a caged object would trip (docs/controller.md, "Caged behind the pads")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Lift, Load, decide
from tegrasp_drake.control.rule_engine import Guard, Rule
from tegrasp_drake.control.taxel_aware.hands import PRISMATIC_ONLY
from tegrasp_drake.control.transition_logic import (load_timed_out, load_timeout_reason,
                                                    reach_timed_out, reach_timeout_reason)


def caged(situation) -> bool:
    return situation.estimate.caged_behind_pads


REACH_TIMEOUT_CAGED = Rule(
    "reach_timeout_caged", (Mode.REACH,), 390, lambda s: reach_timed_out(s) and caged(s),
    lambda s: decide(Load(), Trigger.CORRECTIVE, f"{reach_timeout_reason(s)}, the fingers "
                     "closed on the object behind the pads: load it there"),
    when="no Reach-Load event in time, the object caged behind the pads",
    then="Load", hands=PRISMATIC_ONLY)
LOAD_TIMEOUT_CAGED = Rule(
    "load_timeout_caged", (Mode.LOAD,), 390, lambda s: load_timed_out(s) and caged(s),
    lambda s: decide(Lift(), Trigger.CORRECTIVE, f"{load_timeout_reason(s)}, the fingers "
                     "hold the object behind the pads: lift"),
    when="no Load-Lift event in time, the object caged behind the pads",
    then="Lift", hands=PRISMATIC_ONLY)
CAGED = Guard(
    "caged", ("object_lost", "avoid_hit", "lift_load"), caged,
    when="the object caged behind the pads", hands=PRISMATIC_ONLY)
