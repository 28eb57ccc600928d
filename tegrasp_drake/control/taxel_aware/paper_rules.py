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


def _avoid(situation):
    s = situation
    return paper.hold_avoid(s.obs, s.counters, s.config, s.event_trigger, s.hold_s)


def _load_timeout(situation):
    reason = load_timeout_reason(situation)
    if situation.counters.lift_loads:
        return decide(Failed(), Trigger.CORRECTIVE, f"{reason} after Lift-Load")
    return re_reach_or_fail(situation, centring_shift(situation), reason,
                            limit=situation.config.max_re_reaches)


DEVICE_FAULT = Rule(Reason.DEVICE_FAULT, lambda s: bool(s.obs.device_fault),
                    lambda s: paper.device_failure(s.obs),
    when='a watchdog reports a device fault',
    then='Failed (fault)')
GRIPPER_FAULT = Rule(Reason.GRIPPER_FAULT, lambda s: bool(s.obs.gripper_fault),
                     lambda s: paper.device_failure(s.obs),
    when='the gripper reports a fault',
    then='Failed (fault)')
OBJECT_LOST = Rule(
    Reason.OBJECT_LOST,
    lambda s: not _caged(s) and paper.object_lost(s.mode, s.obs, s.config) is not None,
    lambda s: paper.object_lost(s.mode, s.obs, s.config),
    when="holding, no pad's SA above contact_force_n, not caged",
    then='Failed')
REACH_EVENT = Rule(Reason.REACH_EVENT, lambda s: s.obs.event_matched,
                   lambda s: decide(Load(), s.event_trigger, "Reach-Load event"),
    when='Reach-Load event',
    then='Load (event)')
ONE_SIDED = Rule(Reason.ONE_SIDED, one_sided, lambda s: re_reach_or_fail(
    s, centring_shift(s), f"only the {touching_finger(s)} finger touched"),
    when='one finger alone for one_sided_contact_s',
    then='ReReach(centring) or Failed')
CLOSED_ON_NOTHING = Rule(Reason.CLOSED_ON_NOTHING, lambda s: s.obs.closed_on_nothing,
                         lambda s: re_reach_or_fail(s, centring_shift(s),
                                                    "the gripper closed on nothing"),
    when='the gripper closed to its request on nothing',
    then='ReReach(centring) or Failed')
REACH_TIMEOUT = Rule(Reason.REACH_TIMEOUT, reach_timed_out, lambda s: re_reach_or_fail(
    s, centring_shift(s), reach_timeout_reason(s)),
    when='no Reach-Load event in time',
    then='ReReach(centring) or Failed')
LOAD_LIFT_EVENT = Rule(Reason.LOAD_LIFT_EVENT, lambda s: s.obs.event_matched,
                       lambda s: decide(Lift(), s.event_trigger, "Load-Lift event"),
    when='Load-Lift event',
    then='Lift (event)')
RELIFT = _paper_rule(Reason.RELIFT, lambda obs, counters, config, *_: relift_after_lift_load(
    grip_reached=obs.grip_reached, slip_quiet=obs.slip_quiet,
    time_in_load_s=obs.time_in_mode, counters=counters, config=config),
    when='after a Lift-Load: raised grip reached, slip quiet, relift_settle_s',
    then='Lift')
LOAD_TIMEOUT = Rule(Reason.LOAD_TIMEOUT, load_timed_out, _load_timeout,
    when='no Load-Lift event in time',
    then='Failed after a Lift-Load, else ReReach(centring) or Failed (max_re_reaches)')
LIFT = _paper_rule(Reason.LIFT, paper.PAPER_RULES[Mode.LIFT],
    when="the paper's Lift: slip (Lift-Load, or Failed when used up), or the lift motion ended",
    then='Load / Failed / Hold')
AVOID_HIT = Rule(Reason.AVOID_HIT, lambda s: not _caged(s) and _avoid(s) is not None, _avoid,
    when='a hit (RA threshold or memorized hit event), not caged',
    then='Avoid')
HOLD_TIME = _paper_rule(Reason.HOLD_TIME, paper.hold_time,
    when='hold_s in Hold',
    then='Place')
PLACE = _paper_rule(Reason.PLACE, paper.PAPER_RULES[Mode.PLACE],
    when='Place-Unload event, or its timeout after the arm stopped',
    then='Unload')
RE_CENTRED = _paper_rule(Reason.RE_CENTRED, paper.PAPER_RULES[Mode.RE_REACH],
    when='the gripper opened and moved',
    then='Reach (close again)')
AVOID_ENDED = _paper_rule(Reason.AVOID_ENDED, paper.PAPER_RULES[Mode.AVOID],
    when='the avoiding motion ended',
    then='Hold')
RELEASED = _paper_rule(Reason.RELEASED, paper.PAPER_RULES[Mode.UNLOAD],
    when='released and retracted',
    then='Done')
