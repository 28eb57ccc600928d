"""The grasp state machine's rule engine: a controller's transitions as a table of rules.

A Rule applies in some modes (or in every mode), has a priority, a condition and an action
(rule_actions.py); a Guard holds named rules back while its condition holds; a
ReReachMove says how the table's Re-Reaches move and how many it allows. The paper's state
machine is one table (transition_logic.PAPER_TABLE); another controller's table extends it
(RuleTable.extended) by adding rules and guards, never by restating the paper's rules.

Each tick the state machine asks `table.next_mode(mode, observation, counters, config,
event_trigger=..., hold_s=...)`: of the rules that apply in the mode, lowest priority
first, the first whose condition holds and that no guard holds back decides. Its Decision
carries its action and the rule's name (Decision.code). Pure: no state, no side effects.

Imports no Drake (the controller registry, read at the command line's start, imports the
modules that define tables).
"""

import dataclasses
from collections.abc import Callable

from tegrasp_drake.control.grasp_modes import TERMINAL_MODES, Decision, Mode, Trigger
from tegrasp_drake.control.rule_actions import re_reach_or_fail

# The modes a rule can apply in (the terminal modes have no transitions).
LIVE_MODES = tuple(mode for mode in Mode if mode not in TERMINAL_MODES)


@dataclasses.dataclass(frozen=True)
class ReReachMove:
    """How a table's Re-Reaches move and how many a grasp may make.

    limit(situation): the most Re-Reaches; shift(situation): where the open gripper moves
    [m, world; a contact_geometry.Shift], None for the paper's shift along the stroke (the
    state machine works it out as it opens). shift_label, limit_label: both in words (the
    docs' tables)."""
    shift_label: str
    limit_label: str
    limit: Callable[["Situation"], int]
    shift: Callable[["Situation"], object] | None = None

    @property
    def label(self) -> str:
        return f"Re-Reach ({self.shift_label}; at most {self.limit_label})"


@dataclasses.dataclass(frozen=True)
class Situation:
    """What a rule reads: the mode, the tick's Observation (transition_logic.py; its
    `estimate`, what the controller's estimator sensed, or None), the corrections made so
    far (Counters), the controller's settings (its config), the event detector's trigger,
    how long to hold [s] and the table's Re-Reach move."""
    mode: Mode
    obs: object
    counters: object
    config: object
    event_trigger: Trigger
    hold_s: float
    re_reach_move: ReReachMove

    @property
    def estimate(self):
        return self.obs.estimate

    def re_reach_or_fail(self, reason: str, *, limit: int | None = None) -> Decision:
        """Re-Reach by the table's move for `reason`, or Failed when Re-Reach is off or
        `limit` (default: the table's) Re-Reaches are made (rule_actions.re_reach_or_fail)."""
        move = self.re_reach_move
        return re_reach_or_fail(self, None if move.shift is None else move.shift(self), reason,
                                limit=limit)


@dataclasses.dataclass(frozen=True)
class Rule:
    """One row of a table: in `modes` (None: every mode but Done and Failed), when
    condition(situation) holds and no guard holds it back, action(situation) is the
    Decision. Rules with a lower `priority` are asked first; no two rules of a table that
    apply in one mode share a priority. `when` and `then` say the condition and the action
    in words for the docs (`then` may name the table's Re-Reach move as {re_reach}, its
    shift as {re_reach_shift})."""
    name: str
    modes: tuple[Mode, ...] | None
    priority: int
    condition: Callable[[Situation], bool]
    action: Callable[[Situation], Decision]
    when: str
    then: str

    def applies_in(self, mode: Mode) -> bool:
        return mode in LIVE_MODES if self.modes is None else mode in self.modes


@dataclasses.dataclass(frozen=True)
class Guard:
    """While condition(situation) holds, the rules named in `holds_back` do not fire (the
    rules after them are asked). `when` says the condition in words for the docs."""
    name: str
    holds_back: tuple[str, ...]
    condition: Callable[[Situation], bool]
    when: str


@dataclasses.dataclass(frozen=True)
class RuleTable:
    """A controller's rules: its own `rules` and `guards` added to those of `base` (None:
    none), and how its Re-Reaches move. ValueError on two rules of one name, two rules of
    one mode with one priority, or a guard of a rule the table lacks."""
    name: str
    rules: tuple[Rule, ...]
    re_reach_move: ReReachMove
    guards: tuple[Guard, ...] = ()
    base: "RuleTable | None" = None

    def __post_init__(self):
        rules, guards = self.all_rules(), self.all_guards()
        names = [rule.name for rule in rules] + [guard.name for guard in guards]
        repeated = sorted({name for name in names if names.count(name) > 1})
        if repeated:
            raise ValueError(f"rule table '{self.name}': the names {repeated} are given twice")
        known = {rule.name for rule in rules}
        for guard in guards:
            unknown = [name for name in guard.holds_back if name not in known]
            if unknown:
                raise ValueError(f"rule table '{self.name}': the guard '{guard.name}' holds "
                                 f"back {unknown}, which the table does not have")
        ordered = {}
        for mode in LIVE_MODES:
            applying = sorted((rule for rule in rules if rule.applies_in(mode)),
                              key=lambda rule: rule.priority)
            for first, second in zip(applying, applying[1:]):
                if first.priority == second.priority:
                    raise ValueError(
                        f"rule table '{self.name}': '{first.name}' and '{second.name}' share "
                        f"the priority {first.priority} in {mode.label}; give one another")
            ordered[mode] = tuple(
                (rule, tuple(guard for guard in guards if rule.name in guard.holds_back))
                for rule in applying)
        object.__setattr__(self, "_ordered", ordered)

    def extended(self, name: str, *, rules: tuple[Rule, ...] = (),
                 guards: tuple[Guard, ...] = (),
                 re_reach_move: ReReachMove | None = None) -> "RuleTable":
        """This table with `rules` and `guards` added (and another Re-Reach move), as the
        table called `name`."""
        return RuleTable(name=name, rules=tuple(rules), guards=tuple(guards),
                         re_reach_move=re_reach_move or self.re_reach_move, base=self)

    def all_rules(self) -> tuple[Rule, ...]:
        """Its rules and its base's."""
        return (self.base.all_rules() if self.base else ()) + self.rules

    def all_guards(self) -> tuple[Guard, ...]:
        """Its guards and its base's."""
        return (self.base.all_guards() if self.base else ()) + self.guards

    def origin(self, name: str) -> str:
        """The name of the table that added the rule or guard called `name`."""
        if any(item.name == name for item in (*self.rules, *self.guards)):
            return self.name
        if self.base is None:
            raise KeyError(f"rule table '{self.name}' has no rule or guard '{name}'")
        return self.base.origin(name)

    def rule(self, name: str) -> Rule:
        """The rule called `name` (KeyError)."""
        for rule in self.all_rules():
            if rule.name == name:
                return rule
        raise KeyError(f"rule table '{self.name}' has no rule '{name}'")

    def ordered(self, mode: Mode) -> tuple[tuple[Rule, tuple[Guard, ...]], ...]:
        """The rules that apply in `mode`, in the order they are asked, each with the
        guards that can hold it back; () in Done and Failed."""
        return self._ordered.get(mode, ())

    def first_match(self, situation: Situation) -> tuple[Rule, Decision] | None:
        """The first rule of the situation's mode whose condition holds and that no guard
        holds back, and its decision; None when none does."""
        for rule, guards in self.ordered(situation.mode):
            if rule.condition(situation) and not any(guard.condition(situation)
                                                     for guard in guards):
                return rule, rule.action(situation)
        return None

    def next_mode(self, mode: Mode, obs, counters, config, *, event_trigger: Trigger,
                  hold_s: float) -> Decision | None:
        """The transition out of `mode` this tick, or None to stay: the first matching
        rule's decision, with the rule's name as its code. obs: an Observation; counters:
        the Counters; config: the controller's config; event_trigger: its event detector's
        trigger; hold_s: how long to hold [s]."""
        if mode in TERMINAL_MODES:
            return None
        situation = Situation(mode=mode, obs=obs, counters=counters, config=config,
                              event_trigger=event_trigger, hold_s=hold_s,
                              re_reach_move=self.re_reach_move)
        match = self.first_match(situation)
        if match is None:
            return None
        rule, decision = match
        return dataclasses.replace(decision, code=rule.name)
