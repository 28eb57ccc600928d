"""The rule tables' shared decision of a Re-Reach: take it by the table's move, or give up
when it is switched off or its limit is reached."""

import dataclasses

from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Failed, ReReach, re_reach_allowed, re_reach_or_fail
from tegrasp_drake.control.transition_logic import PAPER_RE_REACH

CONFIG = GraspControllerConfig()  # re_reach.max_re_reaches 2


@dataclasses.dataclass(frozen=True)
class Situation:
    """What re_reach_or_fail reads of a rule engine's Situation."""
    counters: Counters = Counters()
    config: GraspControllerConfig = dataclasses.field(default_factory=GraspControllerConfig)
    re_reach_move: object = PAPER_RE_REACH


def test_re_reach_until_its_attempts_are_used_up():
    decision = re_reach_or_fail(Situation(Counters(re_reaches=1)), None,
                                "only the left finger touched")
    assert (decision.mode, decision.trigger, decision.reason, decision.action) == (
        Mode.RE_REACH, Trigger.CORRECTIVE, "only the left finger touched", ReReach())
    used_up = re_reach_or_fail(Situation(Counters(re_reaches=2)), None, "closed on nothing")
    assert (used_up.mode, used_up.trigger, used_up.action) == (
        Mode.FAILED, Trigger.CORRECTIVE, Failed())
    assert used_up.reason == "closed on nothing, after 2 Re-Reach attempts"
    assert not re_reach_allowed(Situation(Counters(re_reaches=2)))


def test_a_limit_given_overrides_the_tables():
    situation = Situation(Counters(re_reaches=2))
    assert re_reach_or_fail(situation, None, "late", limit=3).mode == Mode.RE_REACH
    assert re_reach_allowed(situation, limit=3)


def test_re_reach_switched_off_fails_at_once():
    off = Situation(config=dataclasses.replace(
        CONFIG, re_reach=dataclasses.replace(CONFIG.re_reach, enabled=False)))
    decision = re_reach_or_fail(off, None, "closed on nothing")
    assert decision.mode == Mode.FAILED
    assert decision.reason == "closed on nothing; Re-Reach is switched off"
    assert not re_reach_allowed(off)


def test_the_re_reach_carries_its_shift_and_count():
    shift = object()
    decision = re_reach_or_fail(Situation(), shift, "off centre")
    assert decision.action == ReReach(shift, counted=True)
