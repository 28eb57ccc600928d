"""The taxel-aware controller's transitions as a rule table: per mode, an ordered list of
rules (name, condition, action) of which the first whose condition holds decides; the rows
of ANY_MODE come first in every mode. A rule's Decision carries its action (ReReach with
its shift, Load, Lift, Regrasp, Failed) and, set here, its Reason code; the state machine
only carries it out. What the rules read is the tick's Observation and the
ContactEstimator's ContactEstimate (estimator.py).

`rows()` lists the table (mode, order, name, condition, action) in words, for the docs;
each rule module's docstring says why.
"""

import dataclasses

from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import TERMINAL_MODES, Decision, Mode, Trigger
from tegrasp_drake.control.taxel_aware import paper_rules as paper
from tegrasp_drake.control.taxel_aware.approach_contact import APPROACH_CONTACT
from tegrasp_drake.control.taxel_aware.beyond_pads import BEYOND_PADS
from tegrasp_drake.control.taxel_aware.bracketing import BRACKET_RECENTRE, BRACKETED_AT_EXTENT
from tegrasp_drake.control.taxel_aware.caged import (CAGED_LIFT_ENDED, CAGED_NO_LIFT_LOAD,
                                                     LOAD_TIMEOUT_CAGED, REACH_TIMEOUT_CAGED)
from tegrasp_drake.control.taxel_aware.decision import Rule, Situation
from tegrasp_drake.control.taxel_aware.finger_strike import FINGER_STRIKE
from tegrasp_drake.control.taxel_aware.no_event_in_time import (LOAD_TIMEOUT_BOTH_PADS,
                                                                REACH_TIMEOUT_BOTH_PADS)
from tegrasp_drake.control.taxel_aware.off_centre import OFF_CENTRE
from tegrasp_drake.control.taxel_aware.one_sided_at_width import ONE_SIDED_AT_WIDTH
from tegrasp_drake.control.taxel_aware.regrasp import HELD_TILTED, REGRASP_AFTER_PLACE
from tegrasp_drake.control.taxel_aware.tipping_guard import TIPPING_GUARD

ANY_MODE: tuple[Rule, ...] = (paper.DEVICE_FAULT, paper.GRIPPER_FAULT, paper.OBJECT_LOST)

TABLE: dict[Mode, tuple[Rule, ...]] = {
    Mode.REACH: (FINGER_STRIKE, APPROACH_CONTACT, BEYOND_PADS, TIPPING_GUARD, OFF_CENTRE,
                 paper.REACH_EVENT, ONE_SIDED_AT_WIDTH, BRACKETED_AT_EXTENT,
                 BRACKET_RECENTRE, paper.ONE_SIDED, paper.CLOSED_ON_NOTHING,
                 REACH_TIMEOUT_BOTH_PADS, REACH_TIMEOUT_CAGED, paper.REACH_TIMEOUT),
    Mode.RE_REACH: (paper.RE_CENTRED,),
    Mode.LOAD: (BEYOND_PADS, paper.LOAD_LIFT_EVENT, paper.RELIFT, LOAD_TIMEOUT_BOTH_PADS,
                LOAD_TIMEOUT_CAGED, paper.LOAD_TIMEOUT),
    Mode.LIFT: (CAGED_LIFT_ENDED, CAGED_NO_LIFT_LOAD, paper.LIFT),
    Mode.HOLD: (paper.AVOID_HIT, HELD_TILTED, paper.HOLD_TIME),
    Mode.AVOID: (paper.AVOID_ENDED,),
    Mode.PLACE: (REGRASP_AFTER_PLACE, paper.PLACE),
    Mode.UNLOAD: (paper.RELEASED,),
}


def first_match(mode: Mode, situation: Situation) -> tuple[Rule, Decision | None] | None:
    """The first rule of the mode's rows (ANY_MODE's first) whose condition holds, and its
    decision (None: stay); None when no rule matches."""
    for rule in (*ANY_MODE, *TABLE[mode]):
        if rule.condition(situation):
            return rule, rule.action(situation)
    return None


def next_mode(mode: Mode, obs, counters: Counters, config, *, event_trigger: Trigger,
              hold_s: float) -> Decision | None:
    """The transition out of `mode` this tick, or None to stay: the decision of the first
    matching rule, with its Reason code. obs: an Observation with the ContactEstimate;
    config: a GraspControllerConfig; hold_s: how long to hold [s]."""
    if mode in TERMINAL_MODES:
        return None
    situation = Situation(mode=mode, obs=obs, counters=counters, config=config,
                          event_trigger=event_trigger, hold_s=hold_s)
    match = first_match(mode, situation)
    if match is None or match[1] is None:
        return None
    rule, decision = match
    return dataclasses.replace(decision, code=rule.code)


def rows() -> list[tuple[str, int, str, str, str]]:
    """The table as (mode, order, rule name, condition, action) rows, in words."""
    return [(mode.label if mode is not None else "any", k, rule.name, rule.when, rule.then)
            for mode, rules in ((None, ANY_MODE), *TABLE.items())
            for k, rule in enumerate(rules, start=1)]
