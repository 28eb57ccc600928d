"""The controllers, one entry each: everything the package asks about "which controller?"
(config class and YAML tag, builder, rule table, estimator, label and colour). Adding one is
a module and an entry in CONTROLLERS (docs/controller.md, "Adding a controller"). Entries
name their behaviour as "module:function", loaded on use, so this module imports no Drake
(the command line's help reads it)."""

import copy
import dataclasses
import functools
import importlib
import typing
from collections.abc import Callable

from tegrasp_drake.control.controller_config import (HeuristicControllerConfig,
                                                     MemorizedControllerConfig,
                                                     OpenLoopControllerConfig,
                                                     TaxelAwareControllerConfig)
from tegrasp_drake.control.fixed_load_time import FixedLoadTimeControllerConfig
from tegrasp_drake.rig.api_boundary import public_api, public_dataclass

_BUILDERS = "tegrasp_drake.control.grasp_controller"
STATE_MACHINE = f"{_BUILDERS}:AddStateMachineController"  # channels, detector, state machine
SCRIPTED_GRASP = f"{_BUILDERS}:AddScriptedGraspController"  # the open-loop script
EVENT_MATCHER = f"{_BUILDERS}:add_event_matcher_detector"  # memorized events, Eq. 3
HEURISTIC_THRESHOLDS = f"{_BUILDERS}:add_heuristic_detector"  # hand-set thresholds
PAPER_RULES = "tegrasp_drake.control.transition_logic:rule_table"  # the paper's state machine


@public_dataclass
@dataclasses.dataclass(frozen=True)
class ControllerEntry:
    """One controller. config: its config class (YAML tag `!<class>`); label, title, color:
    how tables and figures show it. add_systems, detector, rules, estimator: "module:function"
    references (the builder, the event detector, () -> RuleTable, (config, plan, *,
    sa_rate_hz) -> ContactEstimator), None when absent. senses_finger_strike: reads the
    arm's wrench at G; in_paper: in Table I's comparison."""
    config: type
    label: str
    title: str
    color: str
    add_systems: str = STATE_MACHINE
    detector: str | None = EVENT_MATCHER
    rules: str | None = PAPER_RULES
    estimator: str | None = None
    senses_finger_strike: bool = False
    in_paper: bool = False

    @property
    def name(self) -> str:
        return self.config.name

    @property
    def closed_loop(self) -> bool:
        """It runs a state machine on the tactile signals (the open-loop script does not)."""
        return self.rules is not None

    @property
    def event_triggered(self) -> bool:
        """It reads memorized events (its config's events_folder is not None)."""
        return self.config.events_folder is not None

    @property
    def reads_memorized_events(self) -> bool:
        """It can match memorized events: its own (event_triggered) or, as every state
        machine can, the corrective ones its config's memorized_corrective names."""
        return self.event_triggered or self.closed_loop

    def triggers(self) -> frozenset:
        """The Triggers its transitions can carry: the open-loop script's timer alone; a
        state machine's every trigger but an event detector's (grasp_modes.Trigger.is_event:
        its rules, faults and corrective events, which every state machine's config can
        name), and the one its own detector fires (the builder's grasp_modes.detects)."""
        from tegrasp_drake.control.grasp_modes import Trigger
        if not self.closed_loop:
            return frozenset({Trigger.TIMER})
        return (frozenset(t for t in Trigger if not t.is_event)
                | {self.load("detector").trigger})

    def rule_table(self):
        """Its state machine's RuleTable; None without one."""
        rules = self.load("rules")
        return None if rules is None else rules()

    def load(self, field: str) -> Callable | None:
        """The function that `field` (add_systems, detector, rules, estimator) names."""
        reference = getattr(self, field)
        if reference is None:
            return None
        module, _, attribute = reference.partition(":")
        return getattr(importlib.import_module(module), attribute)


# In the tables' order; the first is the scenario's default controller.
CONTROLLERS = (
    ControllerEntry(MemorizedControllerConfig, label="memorized triggers",
                    title="memorized triggers (the paper's method)", color="#c0392b",
                    in_paper=True),
    ControllerEntry(HeuristicControllerConfig, label="heuristic thresholds",
                    title="heuristic thresholds (Romano et al. 2011 style)", color="#8e44ad",
                    detector=HEURISTIC_THRESHOLDS, in_paper=True),
    ControllerEntry(OpenLoopControllerConfig, label="open loop", title="open loop",
                    color="#7f8c8d", add_systems=SCRIPTED_GRASP, detector=None, rules=None,
                    in_paper=True),
    ControllerEntry(TaxelAwareControllerConfig, label="taxel-aware, ensemble events",
                    title="taxel-aware corrections, ensemble events", color="#1f77b4",
                    rules="tegrasp_drake.control.taxel_aware:rule_table",
                    estimator="tegrasp_drake.control.taxel_aware:estimator_for_plan",
                    senses_finger_strike=True),
    ControllerEntry(FixedLoadTimeControllerConfig, label="fixed Load time",
                    title="the paper's, Load-Lift after a fixed time", color="#d35400",
                    rules="tegrasp_drake.control.fixed_load_time:rule_table"),
)

# The scenario's `controller` field: the first (the default) when untagged.
ControllerConfig = typing.Union[tuple(entry.config for entry in CONTROLLERS)]
CONTROLLER_CLASSES = tuple(entry.config for entry in CONTROLLERS)
# Their names (results, sweeps, --controller), in the tables' order.
CONTROLLER_NAMES = tuple(entry.name for entry in CONTROLLERS)
# The paper's comparison (Table I).
PAPER_CONTROLLERS = tuple(entry.name for entry in CONTROLLERS if entry.in_paper)
_ENTRY_OF_NAME = {entry.name: entry for entry in CONTROLLERS}
_ENTRY_OF_CLASS = {entry.config: entry for entry in CONTROLLERS}
if len(_ENTRY_OF_NAME) != len(CONTROLLERS) or len(_ENTRY_OF_CLASS) != len(CONTROLLERS):
    raise ImportError("controller_registry: two entries share a name or a config class")
# yaml_dump_typed would save a class derived from another entry's as that one.
_DERIVED = [(a.name, b.name) for a in CONTROLLERS for b in CONTROLLERS
            if a is not b and issubclass(a.config, b.config)]
if _DERIVED:
    raise ImportError(f"controller_registry: config classes derived from another entry's "
                      f"(derive from its base instead): {_DERIVED}")


def rule_tables() -> dict:
    """The state-machine controllers' RuleTables by their names, in the registry's order
    (controllers sharing a table: once)."""
    tables = {}
    for entry in CONTROLLERS:
        table = entry.rule_table()
        if table is not None:
            tables.setdefault(table.name, table)
    return tables


@functools.cache
def rule_codes() -> frozenset[str]:
    """The names of every registered table's rules: the codes a timeline entry can carry
    (grasp_modes.Transition.code). Loading the tables imports the controllers (and Drake)."""
    return frozenset(rule.name for table in rule_tables().values()
                     for rule in table.all_rules())


class UnknownControllerError(ValueError):
    """A controller name that names no controller config class."""


@public_api
def controller_entry(controller: typing.Any,
                     what: str = "controller_entry: argument 'controller'") -> ControllerEntry:
    """The entry of a controller's name, config or config class; UnknownControllerError
    naming `what` (the argument, or e.g. "scenario: field 'controller'") if none."""
    if isinstance(controller, str):
        entry = _ENTRY_OF_NAME.get(controller)
    elif isinstance(controller, type):
        entry = _ENTRY_OF_CLASS.get(controller)
    else:
        entry = _ENTRY_OF_CLASS.get(type(controller))
    if entry is None:
        from tegrasp_drake.rig.echo import given
        shown = repr(controller) if isinstance(controller, str) else given(controller)
        raise UnknownControllerError(
            f"{what}: {shown} is not one of {', '.join(CONTROLLER_NAMES)} (a controller's "
            "name, its config or its config class)")
    return entry


def controller_label(name: str) -> str:
    """The controller's label (an unregistered name: itself)."""
    entry = _ENTRY_OF_NAME.get(name)
    return entry.label if entry is not None else name


def controller_title(name: str) -> str:
    """The controller's title (an unregistered name: itself)."""
    entry = _ENTRY_OF_NAME.get(name)
    return entry.title if entry is not None else name


def controller_color(name: str, default: str) -> str:
    """The controller's colour (an unregistered name: `default`)."""
    entry = _ENTRY_OF_NAME.get(name)
    return entry.color if entry is not None else default


def controllers_help() -> str:
    """The controllers for --help: "name: title" each."""
    return "; ".join(f"{entry.name}: {entry.title}" for entry in CONTROLLERS)


def controller_class(name: str):
    """The config class of the controller called `name` (UnknownControllerError)."""
    if not isinstance(name, str) or name not in _ENTRY_OF_NAME:  # a list or mapping too
        raise UnknownControllerError(
            f"'{name}' is not one of {', '.join(CONTROLLER_NAMES)}")
    return _ENTRY_OF_NAME[name].config


def _fields(cls) -> set[str]:
    return {f.name for f in dataclasses.fields(cls)}


def controller_named(name: str, like=None):
    """The config of controller `name`, with the settings of `like` its class also has."""
    cls = controller_class(name)
    settings = _fields(like) if like is not None else set()
    return cls(**{field: copy.deepcopy(getattr(like, field)) for field in _fields(cls)
                  if field in settings})


def _leaf_paths(key: str, value) -> list[str]:
    """The dotted paths a YAML `controller` entry sets (a section: each setting in it)."""
    if isinstance(value, dict) and value:
        return [path for sub, item in value.items()
                for path in _leaf_paths(f"{key}.{sub}", item)]
    return [key]


def foreign_setting(section: dict) -> tuple[str, tuple[str, ...]] | None:
    """A setting of a scenario's YAML `controller` section (tagged or not) that its
    controller lacks but others have: (its dotted path, the names of those that have it)."""
    if not isinstance(section, dict):
        return None
    tag = section.get("_tag")
    cls = next((c for c in CONTROLLER_CLASSES if tag == f"!{c.__name__}"),
               CONTROLLER_CLASSES[0] if tag is None else None)
    if cls is None:
        return None
    own = _fields(cls)
    for key, value in section.items():
        owners = tuple(other.name for other in CONTROLLER_CLASSES if key in _fields(other))
        if key not in own and owners:
            return _leaf_paths(key, value)[0], owners
    return None


def selected_controller(section) -> str | None:
    """The name of the controller a scenario's YAML `controller` section selects, by its
    `name` or else by its tag (`!HeuristicControllerConfig`: 'heuristic'); None when it
    selects none (no section, neither a name nor a known tag)."""
    if not isinstance(section, dict):
        return None
    if section.get("name") is not None:
        return section["name"]
    entry = next((entry for entry in CONTROLLERS
                  if section.get("_tag") == f"!{entry.config.__name__}"), None)
    return entry.name if entry is not None else None


class ControllerTagError(ValueError):
    """A controller section whose YAML tag and `name` select different controllers."""


def controller_tag_problem(section) -> str | None:
    """Words for a `controller` section of YAML data whose tag and name select different
    controllers (`!HeuristicControllerConfig {name: memorized}`), else None: neither may
    silently win."""
    if not isinstance(section, dict) or "name" not in section or "_tag" not in section:
        return None
    name, tag = section["name"], section["_tag"]
    if not isinstance(name, str) or name not in _ENTRY_OF_NAME:
        return None  # an unknown name: controller_class names it
    if tag == f"!{_ENTRY_OF_NAME[name].config.__name__}":
        return None
    return (f"its tag {str(tag)[:80]} and its name '{name}' "
            f"(!{_ENTRY_OF_NAME[name].config.__name__}) select different controllers: give "
            "one of them, the tag or controller.name (to run another controller: "
            "--controller NAME)")


def select_controller_tag(data: dict, *, drop_others: bool = False) -> list[str]:
    """Turns `controller: {name: NAME, ...}` of YAML data, in place, into NAME's tag; with
    drop_others, drops the other controllers' settings NAME lacks and returns their paths.
    ControllerTagError when the section's own tag selects another controller."""
    section = data.get("controller") if isinstance(data, dict) else None
    if not isinstance(section, dict) or "name" not in section:
        return []
    problem = controller_tag_problem(section)
    if problem:
        raise ControllerTagError(problem)
    cls = controller_class(section.pop("name"))
    section["_tag"] = f"!{cls.__name__}"
    if not drop_others:
        return []
    own = _fields(cls)
    others = set().union(*(_fields(other) for other in CONTROLLER_CLASSES))
    dropped = [key for key in section if key in others - own]
    return [path for key in dropped for path in _leaf_paths(key, section.pop(key))]
