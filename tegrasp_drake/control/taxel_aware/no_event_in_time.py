"""Rules reach_timeout_both_pads and load_timeout_both_pads: no event came in time, yet
both pads hold the object. The paper's rule would Re-Reach a grasp that is already made (a
yawed box may never match the Reach-Load event): instead Load (after the Reach-Load
timeout, reach_event_timeout_s after closing) or Lift (after the Load-Lift timeout,
load_event_timeout_s in Load)."""

from tegrasp_drake.control.grasp_modes import Trigger
from tegrasp_drake.control.taxel_aware.decision import Lift, Load, Reason, Rule, decide


def reach_timed_out(situation) -> bool:
    return situation.obs.closing_s >= situation.config.reach_event_timeout_s


def reach_timeout_reason(situation) -> str:
    return f"no Reach-Load event {situation.config.reach_event_timeout_s:g} s after closing"


def load_timed_out(situation) -> bool:
    return situation.obs.time_in_mode >= situation.config.load_event_timeout_s


def load_timeout_reason(situation) -> str:
    return f"no Load-Lift event within {situation.config.load_event_timeout_s:g} s"


def both_pads(situation) -> bool:
    return all(situation.obs.contact)


REACH_TIMEOUT_BOTH_PADS = Rule(
    Reason.REACH_TIMEOUT_BOTH_PADS, lambda s: reach_timed_out(s) and both_pads(s),
    lambda s: decide(Load(), Trigger.CORRECTIVE,
                     f"{reach_timeout_reason(s)}, both pads hold the object: load"),
    when="no Reach-Load event reach_event_timeout_s after closing, both pads on",
    then="Load")
LOAD_TIMEOUT_BOTH_PADS = Rule(
    Reason.LOAD_TIMEOUT_BOTH_PADS, lambda s: load_timed_out(s) and both_pads(s),
    lambda s: decide(Lift(), Trigger.CORRECTIVE,
                     f"{load_timeout_reason(s)}, both pads hold the object: lift"),
    when="no Load-Lift event load_event_timeout_s in Load, both pads on",
    then="Lift")
