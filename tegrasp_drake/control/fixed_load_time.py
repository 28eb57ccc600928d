"""The example controller of docs/controller.md, "Adding a controller": the paper's state
machine lifting load_time_s after entering Load, by the clock, instead of on the Load-Lift
event; its config class and its rule table (the paper's with a rule and a guard added)."""

import dataclasses
import typing

from tegrasp_drake.control.controller_config import EventTriggeredConfig
from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger
from tegrasp_drake.control.rule_engine import Guard, Rule, RuleTable
from tegrasp_drake.rig.ranges import bounded


@dataclasses.dataclass
class FixedLoadTimeControllerConfig(EventTriggeredConfig):
    """The memorized controller's settings (it reads the same events) and the fixed Load
    time."""
    name: typing.ClassVar[str] = "fixed_load_time"
    events_folder: typing.ClassVar[str | None] = ""  # the paper's memorized events
    extra_time_s: typing.ClassVar[float] = 0.0
    # Lift this long after entering Load [s]: the script's dwell after first contact is
    # 0.56-1.06 s (GraspScriptConfig.load_s), so the grip has settled.
    load_time_s: float = bounded(1.0, low=0.0, low_open=True, high=10.0, unit="s",
                                 below="must be positive [s]")


def _first_load(situation) -> bool:
    """The first Load: no Lift-Load has re-loaded the object."""
    return not situation.counters.lift_loads


LOAD_TIME = Rule(
    "load_time", (Mode.LOAD,), 90,
    lambda s: _first_load(s) and s.obs.time_in_mode >= s.config.load_time_s,
    lambda s: Decision(Mode.LIFT, Trigger.TIMER, f"loaded for {s.config.load_time_s:g} s"),
    when="load_time_s in the first Load", then="Lift (timer)")
NO_LOAD_LIFT_EVENT = Guard(
    "no_load_lift_event", ("load_lift_event",), _first_load,
    when="the first Load (the Load-Lift event is not read)")


def rule_table() -> RuleTable:
    """The paper's rule table with the first Load ended by the clock, before the Load-Lift
    event could (priority 90 against its 100), which is not read there."""
    from tegrasp_drake.control.transition_logic import PAPER_TABLE  # loads Drake: on use
    return PAPER_TABLE.extended("fixed_load_time", rules=(LOAD_TIME,),
                                guards=(NO_LOAD_LIFT_EVENT,))
