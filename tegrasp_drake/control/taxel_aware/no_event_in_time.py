"""Rules reach_timeout_both_pads (Load) and load_timeout_both_pads (Lift): no
event came in time, yet both pads hold the object; before the paper's timeouts, which
would Re-Reach a grasp already made. The lift asks more of the pads than contact: each pad's
sum above taxel_aware.lift_pad_sum_n, so that the drop check, reading the same sums in Lift
and Hold, does not find a held grip lost in the noise (docs/controller.md, "No event in
time")."""

from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Lift, Load, decide
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.transition_logic import (load_timed_out, load_timeout_reason,
                                                    reach_timed_out, reach_timeout_reason)


def both_pads(situation) -> bool:
    return all(situation.obs.contact)


def both_pads_lift(situation) -> bool:
    """Each pad's SA sum above taxel_aware.lift_pad_sum_n [N] (and in contact)."""
    threshold = situation.config.taxel_aware.lift_pad_sum_n
    return both_pads(situation) and min(situation.obs.estimate.sa_n[:2]) > threshold


REACH_TIMEOUT_BOTH_PADS = Rule(
    "reach_timeout_both_pads", (Mode.REACH,), 380,
    lambda s: reach_timed_out(s) and both_pads(s),
    lambda s: decide(Load(), Trigger.CORRECTIVE,
                     f"{reach_timeout_reason(s)}, both pads hold the object: load"),
    when="no Reach-Load event re_reach.reach_event_timeout_s after closing, both pads on",
    then="Load")
LOAD_TIMEOUT_BOTH_PADS = Rule(
    "load_timeout_both_pads", (Mode.LOAD,), 380,
    lambda s: load_timed_out(s) and both_pads_lift(s),
    lambda s: decide(Lift(), Trigger.CORRECTIVE,
                     f"{load_timeout_reason(s)}, both pads hold the object: lift"),
    when="no Load-Lift event load_event_timeout_s in Load, each pad's SA above "
    "taxel_aware.lift_pad_sum_n",
    then="Lift")
