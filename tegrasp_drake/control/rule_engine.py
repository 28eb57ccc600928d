"""The grasp state machine's rule engine, pure and Drake-free: Rules (modes, priority,
condition, action), Guards that hold named rules back, and RuleTables that extend another.
Each tick, of the mode's rules, lowest priority first, the first that holds and is not held
back decides; its Decision carries the rule's name. A rule or guard may be kept to some
hand models (`hands`); RuleTable.for_hand is the table a hand runs."""

import dataclasses
from collections.abc import Callable

from tegrasp_drake.control.grasp_modes import (CODE_MAX_LENGTH, TERMINAL_MODES, Decision, Mode,
                                               Trigger)
from tegrasp_drake.control.rule_actions import re_reach_or_fail
from tegrasp_drake.robotiq.hand_models import GRIPPER_MODELS

# The modes a rule can apply in (the terminal modes have no transitions).
LIVE_MODES = tuple(mode for mode in Mode if mode not in TERMINAL_MODES)


def _check_hands(kind: str, name: str, hands) -> None:
    """ValueError unless `hands` is None or a non-empty tuple of GRIPPER_MODELS names."""
    if hands is None:
        return
    if not isinstance(hands, tuple) or not hands or any(h not in GRIPPER_MODELS for h in hands):
        raise ValueError(f"{kind} '{name}': hands {hands!r} is not a tuple of hand models "
                         f"({', '.join(GRIPPER_MODELS)}); give None for every hand")


def _check_hand(table: str, hand) -> None:
    if hand not in GRIPPER_MODELS:
        raise ValueError(f"rule table '{table}': no hand model {hand!r}; the hand models are "
                         f"{', '.join(GRIPPER_MODELS)}")


@dataclasses.dataclass(frozen=True)
class ReReachMove:
    """How a table's Re-Reaches move: limit(situation), the most Re-Reaches; shift(situation),
    a Shift [m, world] or None for the paper's; the labels word both for the docs."""
    shift_label: str
    limit_label: str
    limit: Callable[["Situation"], int]
    shift: Callable[["Situation"], object] | None = None

    @property
    def label(self) -> str:
        return f"Re-Reach ({self.shift_label}; at most {self.limit_label})"


@dataclasses.dataclass(frozen=True)
class Situation:
    """What a rule reads: the mode, the tick's Observation, the Counters, the controller's
    config, the detector's trigger, the hold time [s] and the table's Re-Reach move."""
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
    """One row: in `modes` (None: every live mode), when condition(situation) holds and no
    guard holds it back, action(situation) is the Decision; lower `priority` first, unique per
    mode. `when` and `then` word it for the docs. `hands`: the hand models (GRIPPER_MODELS)
    it applies on, None every one (ValueError for another name)."""
    name: str
    modes: tuple[Mode, ...] | None
    priority: int
    condition: Callable[[Situation], bool]
    action: Callable[[Situation], Decision]
    when: str
    then: str
    hands: tuple[str, ...] | None = None

    def __post_init__(self):
        _check_hands("rule", self.name, self.hands)

    def applies_in(self, mode: Mode) -> bool:
        return mode in LIVE_MODES if self.modes is None else mode in self.modes

    def applies_on(self, hand: str) -> bool:
        return self.hands is None or hand in self.hands


@dataclasses.dataclass(frozen=True)
class Guard:
    """While condition(situation) holds, the rules in `holds_back` do not fire; `when` words it.
    `hands`: the hand models it applies on, None every one (as Rule's)."""
    name: str
    holds_back: tuple[str, ...]
    condition: Callable[[Situation], bool]
    when: str
    hands: tuple[str, ...] | None = None

    def __post_init__(self):
        _check_hands("guard", self.name, self.hands)

    def applies_on(self, hand: str) -> bool:
        return self.hands is None or hand in self.hands


@dataclasses.dataclass(frozen=True)
class RuleTable:
    """A controller's rules and guards added to those of `base` (None: none), and how its
    Re-Reaches move. ValueError on a repeated or over-long (CODE_MAX_LENGTH) name, two rules
    of one mode with one priority, or a guard of a rule the table lacks."""
    name: str
    rules: tuple[Rule, ...]
    re_reach_move: ReReachMove
    guards: tuple[Guard, ...] = ()
    base: "RuleTable | None" = None

    def __post_init__(self):
        rules, guards = self.all_rules(), self.all_guards()
        names = [rule.name for rule in rules] + [guard.name for guard in guards]
        long = [name for name in names if len(name) > CODE_MAX_LENGTH]
        if long:
            raise ValueError(f"rule table '{self.name}': the names {long} are longer than "
                             f"{CODE_MAX_LENGTH} characters (a timeline entry's code)")
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
        """This table with `rules` and `guards` added, as the table called `name`."""
        return RuleTable(name=name, rules=tuple(rules), guards=tuple(guards),
                         re_reach_move=re_reach_move or self.re_reach_move, base=self)

    def for_hand(self, hand: str) -> "RuleTable":
        """The table `hand` (GRIPPER_MODELS) runs: this one, with its names and bases, without
        the rules and guards kept to other hands; a guard no longer holds back a rule dropped,
        and is dropped when it holds none back. ValueError for an unknown hand."""
        _check_hand(self.name, hand)
        base = self.base.for_hand(hand) if self.base else None
        rules = tuple(rule for rule in self.rules if rule.applies_on(hand))
        kept = {rule.name for rule in (base.all_rules() if base else ()) + rules}
        guards = []
        for guard in self.guards:
            holds_back = tuple(name for name in guard.holds_back if name in kept)
            if guard.applies_on(hand) and holds_back:
                guards.append(dataclasses.replace(guard, holds_back=holds_back))
        return RuleTable(name=self.name, rules=rules, re_reach_move=self.re_reach_move,
                         guards=tuple(guards), base=base)

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
        """The rules of `mode` in the order asked, each with its guards."""
        return self._ordered.get(mode, ())

    def first_match(self, situation: Situation) -> tuple[Rule, Decision] | None:
        """(rule, decision) of the first rule that holds and is not held back, or None."""
        for rule, guards in self.ordered(situation.mode):
            if rule.condition(situation) and not any(guard.condition(situation)
                                                     for guard in guards):
                return rule, rule.action(situation)
        return None

    def next_mode(self, mode: Mode, obs, counters, config, *, event_trigger: Trigger,
                  hold_s: float) -> Decision | None:
        """The first matching rule's decision out of `mode` this tick, or None to stay."""
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
