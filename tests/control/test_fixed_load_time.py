"""The example controller of docs/controller.md ("Adding a controller"): the paper's rule
table with a Load-Lift by the clock; the rule and the guard it adds (fires, does not
fire), then a closed-loop trial."""

import pathlib
import re

import pytest

from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.fixed_load_time import FixedLoadTimeControllerConfig, rule_table
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.transition_logic import Observation

ROOT = pathlib.Path(__file__).resolve().parents[2]
CONFIG = FixedLoadTimeControllerConfig()
EVENT = Trigger.MEMORIZED_EVENT
TABLE = rule_table()


def decide(mode, counters=Counters(), **observed):
    return TABLE.next_mode(mode, Observation(**observed), counters, CONFIG, event_trigger=EVENT,
                           hold_s=3.0)


def test_the_load_time_lifts_by_the_clock_not_before():
    assert decide(Mode.LOAD, time_in_mode=CONFIG.load_time_s).code == "load_time"
    assert decide(Mode.LOAD, time_in_mode=0.9 * CONFIG.load_time_s) is None


def test_the_guard_holds_the_load_lift_event_back_in_the_first_load_only():
    assert decide(Mode.LOAD, event_matched=True) is None
    assert decide(Mode.LOAD, Counters(lift_loads=1), event_matched=True).code == \
        "load_lift_event"


# The rules and guards the table adds to the paper's, and their fires / does-not-fire tests.
CASES = {"load_time": test_the_load_time_lifts_by_the_clock_not_before,
         "no_load_lift_event": test_the_guard_holds_the_load_lift_event_back_in_the_first_load_only}


def test_every_rule_and_guard_it_adds_has_a_case():
    assert {item.name for item in (*TABLE.rules, *TABLE.guards)} == set(CASES)
    assert TABLE.base.name == "paper"


def test_the_load_lift_event_does_not_lift():
    assert decide(Mode.LOAD, event_matched=True, time_in_mode=0.5 * CONFIG.load_time_s) is None


def test_the_load_time_lifts_by_the_clock():
    decision = decide(Mode.LOAD, time_in_mode=CONFIG.load_time_s)
    assert (decision.mode, decision.trigger) == (Mode.LIFT, Trigger.TIMER)


def test_a_device_fault_in_load_fails_before_the_clock_lifts():
    decision = decide(Mode.LOAD, time_in_mode=CONFIG.load_time_s, device_fault="watchdog")
    assert decision.mode == Mode.FAILED


def test_a_re_load_after_lift_load_is_the_papers():
    # After a Lift-Load the paper's relift rule decides (grip reached, RA quiet, settled).
    counters = Counters(lift_loads=1)
    assert decide(Mode.LOAD, counters, time_in_mode=CONFIG.load_time_s) is None
    decision = decide(Mode.LOAD, counters, grip_reached=True, slip_quiet=True,
                      time_in_mode=CONFIG.load_time_s)
    assert (decision.mode, decision.trigger) == (Mode.LIFT, Trigger.CORRECTIVE)


def test_the_other_modes_keep_the_papers_events():
    decision = decide(Mode.REACH, event_matched=True)
    assert (decision.mode, decision.trigger) == (Mode.LOAD, EVENT)


@pytest.mark.slow
def test_a_closed_loop_box_trial_lifts_by_the_clock_and_holds():
    from tegrasp_drake.runs.trial import run_trial
    from tegrasp_drake.scenario.scenario import LoadScenario
    scenario = LoadScenario(name="box", controller="fixed_load_time",
                            overrides=["random_seed=650"])
    # Hold begins after Reach (about 3 s), Load (1 s) and Lift (1.5 s): stop in Hold.
    transitions = run_trial(scenario, max_time=7.0).transitions
    load, lift = (next(t for t in transitions if (t.from_mode, t.to_mode) == pair)
                  for pair in ((Mode.REACH, Mode.LOAD), (Mode.LOAD, Mode.LIFT)))
    assert lift.trigger == Trigger.TIMER
    # The machine ticks every update_period_s: the Lift comes on the first tick past it.
    assert 0.0 <= lift.t - load.t - CONFIG.load_time_s <= CONFIG.update_period_s + 1e-9
    assert Mode.HOLD in [t.to_mode for t in transitions]
    assert Mode.FAILED not in [t.to_mode for t in transitions]


def test_the_docs_show_the_examples_code_as_it_is():
    page = (ROOT / "docs" / "controller.md").read_text()
    section = page[page.index("## Adding a controller"):page.index("## Judging a trial")]
    blocks = re.findall(r"```\n(.*?)```", section, re.DOTALL)
    code = "".join((ROOT / "tegrasp_drake" / "control" / name).read_text()
                   for name in ("fixed_load_time.py", "controller_registry.py"))
    assert len(blocks) == 3
    for block in blocks:
        assert block in code, f"docs/controller.md shows code the package does not hold:\n{block}"
