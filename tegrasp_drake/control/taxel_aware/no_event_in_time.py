"""Rules reach_timeout_both_pads and load_timeout_both_pads: no event came in time, yet
both pads hold the object. The paper's rule would Re-Reach a grasp that is already made (a
yawed box may never match the Reach-Load event): instead Load (after the Reach-Load
timeout, re_reach.reach_event_timeout_s after closing) or Lift (after the Load-Lift timeout,
load_event_timeout_s in Load). Both come before the paper's timeouts (priority 400)."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Lift, Load, decide
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.transition_logic import (load_timed_out, load_timeout_reason,
                                                    reach_timed_out, reach_timeout_reason)


def both_pads(situation) -> bool:
    return all(situation.obs.contact)


REACH_TIMEOUT_BOTH_PADS = Rule(
    "reach_timeout_both_pads", (Mode.REACH,), 380,
    lambda s: reach_timed_out(s) and both_pads(s),
    lambda s: decide(Load(), Trigger.CORRECTIVE,
                     f"{reach_timeout_reason(s)}, both pads hold the object: load"),
    when="no Reach-Load event re_reach.reach_event_timeout_s after closing, both pads on",
    then="Load")
LOAD_TIMEOUT_BOTH_PADS = Rule(
    "load_timeout_both_pads", (Mode.LOAD,), 380,
    lambda s: load_timed_out(s) and both_pads(s),
    lambda s: decide(Lift(), Trigger.CORRECTIVE,
                     f"{load_timeout_reason(s)}, both pads hold the object: lift"),
    when="no Load-Lift event load_event_timeout_s in Load, both pads on",
    then="Lift")
