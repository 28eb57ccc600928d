"""The paper's rules (transition_logic.py) as rows of the taxel-aware table: the faults and
the lost object in any mode, the events, the Re-Reach of one-sided contact, of a close on
nothing and of the timeouts, Lift-Load, Avoid and the timers. Where a row Re-Reaches, it
moves as the taxel-aware controller centres (moves.centring_shift), within
taxel_aware.max_re_reaches (the Load timeout keeps the paper's max_re_reaches)."""

from tegrasp_drake.control import transition_logic as paper
from tegrasp_drake.control.corrective_actions import relift_after_lift_load
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.taxel_aware.decision import (Failed, Lift, Load, Reason, Rule,
                                                        decide, re_reach_or_fail)
from tegrasp_drake.control.taxel_aware.moves import centring_shift
from tegrasp_drake.control.taxel_aware.no_event_in_time import (
    load_timed_out, load_timeout_reason, reach_timed_out, reach_timeout_reason)
from tegrasp_drake.control.taxel_aware.one_sided_at_width import one_sided, touching_finger


def _paper_rule(code: Reason, rule, *, when: str, then: str) -> Rule:
    """A row that takes the paper's decision `rule(obs, counters, config, event_trigger,
    hold_s)` when it makes one."""
    def action(s):
        return rule(s.obs, s.counters, s.config, s.event_trigger, s.hold_s)
    return Rule(code, lambda s: action(s) is not None, action, when=when, then=then)


def _caged(situation) -> bool:
    return situation.estimate.caged_behind_pads


def _device_fault(situation) -> bool:
    return bool(situation.obs.device_fault)


def _gripper_fault(situation) -> bool:
    return bool(situation.obs.gripper_fault)


def _fail_on_fault(situation):
    return paper.device_failure(situation.obs)


def _lost(situation):
    return paper.object_lost(situation.mode, situation.obs, situation.config)


def _lost_and_not_caged(situation) -> bool:
    return not _caged(situation) and _lost(situation) is not None


def _event(situation) -> bool:
    return situation.obs.event_matched


def _load_on_event(situation):
    return decide(Load(), situation.event_trigger, "Reach-Load event")


def _lift_on_event(situation):
    return decide(Lift(), situation.event_trigger, "Load-Lift event")


def _re_reach_one_sided(situation):
    return re_reach_or_fail(situation, centring_shift(situation),
                            f"only the {touching_finger(situation)} finger touched")


def _closed_on_nothing(situation) -> bool:
    return situation.obs.closed_on_nothing


def _re_reach_closed_on_nothing(situation):
    return re_reach_or_fail(situation, centring_shift(situation),
                            "the gripper closed on nothing")


def _re_reach_late(situation):
    return re_reach_or_fail(situation, centring_shift(situation),
                            reach_timeout_reason(situation))


def _relift(obs, counters, config, *_):
    return relift_after_lift_load(grip_reached=obs.grip_reached, slip_quiet=obs.slip_quiet,
                                  time_in_load_s=obs.time_in_mode, counters=counters,
                                  config=config)


def _avoid(situation):
    s = situation
    return paper.hold_avoid(s.obs, s.counters, s.config, s.event_trigger, s.hold_s)


def _hit_and_not_caged(situation) -> bool:
    return not _caged(situation) and _avoid(situation) is not None


def _load_timeout(situation):
    reason = load_timeout_reason(situation)
    if situation.counters.lift_loads:
        return decide(Failed(), Trigger.CORRECTIVE, f"{reason} after Lift-Load")
    return re_reach_or_fail(situation, centring_shift(situation), reason,
                            limit=situation.config.max_re_reaches)


DEVICE_FAULT = Rule(Reason.DEVICE_FAULT, _device_fault, _fail_on_fault,
                    when="a watchdog reports a device fault", then="Failed (fault)")
GRIPPER_FAULT = Rule(Reason.GRIPPER_FAULT, _gripper_fault, _fail_on_fault,
                     when="the gripper reports a fault", then="Failed (fault)")
OBJECT_LOST = Rule(Reason.OBJECT_LOST, _lost_and_not_caged, _lost,
                   when="holding, no pad's SA above contact_force_n, not caged",
                   then="Failed")
REACH_EVENT = Rule(Reason.REACH_EVENT, _event, _load_on_event,
                   when="Reach-Load event", then="Load (event)")
ONE_SIDED = Rule(Reason.ONE_SIDED, one_sided, _re_reach_one_sided,
                 when="one finger alone for one_sided_contact_s",
                 then="ReReach(centring) or Failed")
CLOSED_ON_NOTHING = Rule(Reason.CLOSED_ON_NOTHING, _closed_on_nothing,
                         _re_reach_closed_on_nothing,
                         when="the gripper closed to its request on nothing",
                         then="ReReach(centring) or Failed")
REACH_TIMEOUT = Rule(Reason.REACH_TIMEOUT, reach_timed_out, _re_reach_late,
                     when="no Reach-Load event in time", then="ReReach(centring) or Failed")
LOAD_LIFT_EVENT = Rule(Reason.LOAD_LIFT_EVENT, _event, _lift_on_event,
                       when="Load-Lift event", then="Lift (event)")
RELIFT = _paper_rule(Reason.RELIFT, _relift,
                     when="after a Lift-Load: raised grip reached, slip quiet, "
                     "relift_settle_s", then="Lift")
LOAD_TIMEOUT = Rule(Reason.LOAD_TIMEOUT, load_timed_out, _load_timeout,
                    when="no Load-Lift event in time",
                    then="Failed after a Lift-Load, else ReReach(centring) or Failed "
                    "(max_re_reaches)")
LIFT = _paper_rule(Reason.LIFT, paper.PAPER_RULES[Mode.LIFT],
                   when="the paper's Lift: slip, or the lift motion ended",
                   then="Load (Lift-Load), Failed (used up) or Hold")
AVOID_HIT = Rule(Reason.AVOID_HIT, _hit_and_not_caged, _avoid,
                 when="a hit (RA threshold or memorized hit event), not caged", then="Avoid")
HOLD_TIME = _paper_rule(Reason.HOLD_TIME, paper.hold_time, when="hold_s in Hold",
                        then="Place")
PLACE = _paper_rule(Reason.PLACE, paper.PAPER_RULES[Mode.PLACE],
                    when="Place-Unload event, or its timeout after the arm stopped",
                    then="Unload")
RE_CENTRED = _paper_rule(Reason.RE_CENTRED, paper.PAPER_RULES[Mode.RE_REACH],
                         when="the gripper opened and moved", then="Reach (close again)")
AVOID_ENDED = _paper_rule(Reason.AVOID_ENDED, paper.PAPER_RULES[Mode.AVOID],
                          when="the avoiding motion ended", then="Hold")
RELEASED = _paper_rule(Reason.RELEASED, paper.PAPER_RULES[Mode.UNLOAD],
                       when="released and retracted", then="Done")
