"""The rule engine: priority decides among rules whose conditions hold, a guard holds its
rules back (and only those), an extension adds rules without restating its base's, and a
table that could not decide one way is refused. On a small table of its own; the
controllers' tables have their rules' tests (tests/control/test_transition_logic.py,
control/test_taxel_aware_rules.py, control/test_fixed_load_time.py)."""

import dataclasses
import pathlib
import re
import subprocess
import sys

import pytest

from tegrasp_drake.control.controller_registry import CONTROLLERS
from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger
from tegrasp_drake.control.rule_engine import Guard, ReReachMove, Rule, RuleTable

ROOT = pathlib.Path(__file__).resolve().parents[2]


@dataclasses.dataclass(frozen=True)
class Flags:
    """A stand-in Observation: which conditions hold."""
    a: bool = False
    b: bool = False
    blocked: bool = False
    estimate: object = None


def going_to(mode: Mode, name: str) -> Rule:
    """A rule of Hold that goes to `mode` when the flag `name` is set."""
    return Rule(name, (Mode.HOLD,), 0, lambda s: getattr(s.obs, name),
                lambda s: Decision(mode, Trigger.TIMER, name), when=name, then=mode.label)


MOVE = ReReachMove("none", "none", limit=lambda s: 0)
A = dataclasses.replace(going_to(Mode.PLACE, "a"), priority=10)
B = dataclasses.replace(going_to(Mode.AVOID, "b"), priority=20)
BASE = RuleTable(name="base", rules=(B, A), re_reach_move=MOVE)


def decide(table: RuleTable, mode=Mode.HOLD, **flags):
    return table.next_mode(mode, Flags(**flags), None, None, event_trigger=Trigger.TIMER,
                           hold_s=3.0)


def test_the_lowest_priority_whose_condition_holds_decides_whatever_the_listing_order():
    assert decide(BASE, a=True, b=True).code == "a"
    assert decide(BASE, b=True).code == "b"
    assert decide(BASE) is None


def test_a_rule_applies_only_in_its_modes_and_none_in_the_terminal_ones():
    assert decide(BASE, mode=Mode.LIFT, a=True) is None
    anywhere = dataclasses.replace(A, modes=None)
    table = RuleTable(name="anywhere", rules=(anywhere,), re_reach_move=MOVE)
    assert decide(table, mode=Mode.LIFT, a=True).code == "a"
    assert decide(table, mode=Mode.DONE, a=True) is None


def test_a_guard_holds_back_its_rules_and_the_next_one_decides():
    guarded = BASE.extended("guarded", guards=(
        Guard("blocker", ("a",), lambda s: s.obs.blocked, when="blocked"),))
    assert decide(guarded, a=True, b=True, blocked=True).code == "b"
    assert decide(guarded, a=True, blocked=True) is None
    assert decide(guarded, a=True, b=True).code == "a"
    assert decide(BASE, a=True, b=True, blocked=True).code == "a"  # the base has no guard


def test_an_extension_adds_rules_among_its_base_ones_by_priority():
    first = dataclasses.replace(going_to(Mode.FAILED, "blocked"), priority=5)
    extended = BASE.extended("extended", rules=(first,))
    assert decide(extended, a=True, blocked=True).code == "blocked"
    assert [rule.name for rule, _ in extended.ordered(Mode.HOLD)] == ["blocked", "a", "b"]
    assert (extended.origin("a"), extended.origin("blocked")) == ("base", "extended")
    assert extended.re_reach_move is MOVE


@pytest.mark.parametrize("rules,guards,message", [
    ((A, dataclasses.replace(B, name="a")), (), "given twice"),
    ((A, dataclasses.replace(B, priority=10)), (), "share the priority 10 in Hold"),
    ((A, dataclasses.replace(B, priority=10, modes=None)), (), "share the priority 10"),
    ((A,), (Guard("g", ("c",), lambda s: True, when=""),), "does not have"),
    ((A, dataclasses.replace(B, name="b" * 41)), (), "longer than 40 characters"),
])
def test_a_table_that_could_not_decide_one_way_is_refused(rules, guards, message):
    with pytest.raises(ValueError, match=message):
        RuleTable(name="bad", rules=rules, guards=guards, re_reach_move=MOVE)


# A prismatic-only rule of Hold and its guard, and a guard that holds back it and `a`.
ONLY_PRISMATIC = dataclasses.replace(going_to(Mode.FAILED, "blocked"), priority=5,
                                     hands=("prismatic",))
HELD = BASE.extended("held", rules=(ONLY_PRISMATIC,), guards=(
    Guard("on_prismatic", ("blocked",), lambda s: s.obs.b, when="b"),
    Guard("on_both", ("blocked", "a"), lambda s: s.obs.b, when="b")))


def test_a_hands_table_drops_the_rules_kept_to_other_hands_and_their_guards_references():
    linkage = HELD.for_hand("linkage")
    assert [rule.name for rule, _ in linkage.ordered(Mode.HOLD)] == ["a", "b"]
    assert {guard.name: guard.holds_back for guard in linkage.all_guards()} == {
        "on_both": ("a",)}
    assert (linkage.name, linkage.origin("a"), linkage.base.name) == ("held", "base", "base")
    assert decide(linkage, blocked=True, a=True).code == "a"
    assert decide(HELD.for_hand("prismatic"), blocked=True, a=True).code == "blocked"
    assert [rule.name for rule, _ in HELD.for_hand("prismatic").ordered(Mode.HOLD)] == [
        "blocked", "a", "b"]


def test_a_guard_kept_to_a_hand_is_dropped_on_the_others():
    kept = BASE.extended("kept", guards=(
        Guard("blocker", ("a",), lambda s: s.obs.blocked, when="blocked",
              hands=("prismatic",)),))
    assert decide(kept.for_hand("prismatic"), a=True, blocked=True) is None
    assert decide(kept.for_hand("linkage"), a=True, blocked=True).code == "a"


def test_a_guard_holding_back_only_dropped_rules_is_dropped():
    only = BASE.extended("only", rules=(ONLY_PRISMATIC,), guards=(
        Guard("on_prismatic", ("blocked",), lambda s: s.obs.b, when="b"),))
    assert only.for_hand("linkage").all_guards() == ()
    assert [g.name for g in only.for_hand("prismatic").all_guards()] == ["on_prismatic"]


@pytest.mark.parametrize("hands", [("gecko",), "prismatic", ()])
def test_a_rule_or_guard_kept_to_no_known_hand_is_refused(hands):
    with pytest.raises(ValueError, match=r"^rule 'a': hands .*\(linkage, prismatic\)"):
        dataclasses.replace(A, hands=hands)
    with pytest.raises(ValueError, match=r"^guard 'g': hands .*\(linkage, prismatic\)"):
        Guard("g", ("a",), lambda s: True, when="", hands=hands)


def test_an_unknown_hand_has_no_table():
    with pytest.raises(ValueError, match=r"^rule table 'held': no hand model 'gecko'; the hand "
                                         r"models are linkage, prismatic$"):
        HELD.for_hand("gecko")


def test_the_docs_name_the_hands_a_rule_or_guard_is_kept_to():
    from tegrasp_drake.control.rule_docs import markdown
    page = markdown(HELD)
    assert "| `blocked` | held | prismatic |" in page and "| `a` | base | both |" in page
    assert "| `on_both` | held | both | `blocked`, `a` |" in page
    assert "hands" not in markdown(BASE)  # no rule or guard of it is kept to a hand


def test_the_decision_names_its_rule_and_keeps_its_action():
    decision = decide(BASE, b=True)
    assert (decision.mode, decision.trigger, decision.reason, decision.code) == (
        Mode.AVOID, Trigger.TIMER, "b", "b")


# The modules that test each registered table's rules and guards (fires, does not fire):
# a controller with a table of its own needs one.
RULE_TESTS = {"paper": "control/test_transition_logic.py",
              "taxel_aware": "control/test_taxel_aware_rules.py",
              "fixed_load_time": "control/test_fixed_load_time.py"}


def test_every_registered_table_has_a_module_testing_its_rules():
    tables = {entry.rule_table().name for entry in CONTROLLERS if entry.rules is not None}
    assert tables == set(RULE_TESTS)
    for module in RULE_TESTS.values():
        text = (ROOT / "tests" / module).read_text()
        assert re.search(r"def test_every_rule_.*_has_a_case", text), module


def test_the_docs_rule_tables_are_the_engines():
    """docs/controller.md shows each table as `python -m tegrasp_drake.control.rule_docs
    --write docs/controller.md` generates it."""
    from tegrasp_drake.control.controller_registry import rule_tables
    from tegrasp_drake.control.rule_docs import updated_page
    page = (ROOT / "docs" / "controller.md").read_text()
    tables = rule_tables()
    updated, shown = updated_page(page, tables)
    assert set(shown) == set(tables), "every controller's table is in the docs"
    assert updated == page, ("docs/controller.md's rule tables differ from the engine's: run "
                             "`python -m tegrasp_drake.control.rule_docs --write "
                             "docs/controller.md`")


def test_the_docs_command_checks_a_stale_page(tmp_path):
    page = (ROOT / "docs" / "controller.md").read_text()
    stale = tmp_path / "controller.md"
    stale.write_text(page.replace("| `reach_event` |", "| `the_reach_event` |", 1))
    command = [sys.executable, "-m", "tegrasp_drake.control.rule_docs"]
    checked = subprocess.run([*command, "--check", str(stale)], capture_output=True, text=True)
    assert checked.returncode == 1 and "--write" in checked.stdout
    subprocess.run([*command, "--write", str(stale)], check=True, capture_output=True)
    assert stale.read_text() == page
