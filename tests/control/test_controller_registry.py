"""The controller registry is the one place that says which controller is which: every entry
is complete, and no other module asks a controller config its class."""

import pathlib
import re
import subprocess
import sys

import pytest

import tegrasp_drake
from tegrasp_drake.control import controller_config
from tegrasp_drake.control.controller_registry import (CONTROLLER_NAMES, CONTROLLERS,
                                                       UnknownControllerError,
                                                       controller_entry, controller_label,
                                                       rule_codes)
from tegrasp_drake.control.rule_engine import RuleTable

PACKAGE = pathlib.Path(tegrasp_drake.__file__).parent
REGISTRY = PACKAGE / "control" / "controller_registry.py"
# The names of the controller config classes (those with a ClassVar `name`, and the bases
# they share): an isinstance on any of them asks "which controller?".
CONTROLLER_CONFIG_NAMES = sorted(
    name for name, value in vars(controller_config).items()
    if isinstance(value, type) and name.endswith("Config")
    and (hasattr(value, "name") or name in ("GraspControllerConfig", "EventTriggeredConfig")))


def test_the_config_class_names_are_found():
    # The grep below is only as good as this list.
    assert {"MemorizedControllerConfig", "OpenLoopControllerConfig", "GraspControllerConfig",
            "EventTriggeredConfig", "TaxelAwareControllerConfig"} <= set(CONTROLLER_CONFIG_NAMES)


def test_no_module_but_the_registry_asks_a_controller_config_its_class():
    pattern = re.compile(r"isinstance\([^)]*\b(" + "|".join(CONTROLLER_CONFIG_NAMES) + r")\b")
    offenders = [f"{path.relative_to(PACKAGE)}:{number}: {line.strip()}"
                 for path in sorted(PACKAGE.rglob("*.py")) if path != REGISTRY
                 for number, line in enumerate(path.read_text().splitlines(), 1)
                 if pattern.search(line)]
    assert not offenders, "ask controller_registry.controller_entry instead:\n" + "\n".join(
        offenders)


def test_no_module_but_the_registry_keeps_a_table_of_controller_names():
    # A dict literal keyed by two controller names is a second registry.
    names = "|".join(CONTROLLER_NAMES)
    pattern = re.compile(rf'"({names})"\s*:.*"({names})"\s*:')
    offenders = [str(path.relative_to(PACKAGE)) for path in sorted(PACKAGE.rglob("*.py"))
                 if path != REGISTRY and pattern.search(path.read_text().replace("\n", " "))]
    assert not offenders


@pytest.mark.parametrize("entry", CONTROLLERS, ids=lambda entry: entry.name)
def test_every_entry_names_functions_that_exist(entry):
    assert callable(entry.load("add_systems"))
    for field in ("detector", "rules", "estimator"):
        reference = getattr(entry, field)
        assert reference is None or callable(entry.load(field))
    assert entry.closed_loop == (entry.detector is not None)
    assert entry.rules is None or isinstance(entry.rule_table(), RuleTable)
    assert re.fullmatch(r"#[0-9a-f]{6}", entry.color)


def test_an_entry_is_found_by_name_config_or_class():
    entry = CONTROLLERS[0]
    assert controller_entry(entry.name) is entry
    assert controller_entry(entry.config) is entry
    assert controller_entry(entry.config()) is entry
    with pytest.raises(UnknownControllerError, match="not one of"):
        controller_entry("no_such_controller")


@pytest.mark.parametrize("controller", [None, 3, object])
def test_something_not_a_controller_is_refused_naming_the_argument(controller):
    with pytest.raises(UnknownControllerError,
                       match=r"^controller_entry: argument 'controller': .* not one of"):
        controller_entry(controller)


def test_a_caller_names_what_held_the_controller():
    with pytest.raises(UnknownControllerError, match=r"^scenario: field 'controller': "):
        controller_entry(None, "scenario: field 'controller'")


def test_an_unregistered_name_is_shown_as_it_is():
    assert controller_label("an_old_controller") == "an_old_controller"
    assert controller_label("memorized") == "memorized triggers"


def test_the_registry_imports_no_drake():
    code = ("import sys; import tegrasp_drake.control.controller_registry; "
            "print('pydrake' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"


def test_the_rule_codes_are_the_names_of_every_registered_tables_rules():
    tables = [entry.rule_table() for entry in CONTROLLERS if entry.rules is not None]
    names = {rule.name for table in tables for rule in table.all_rules()}
    assert rule_codes() == names
    assert {"reach_event", "closed_on_nothing", "finger_strike", "load_time"} <= names
    guards = {guard.name for table in tables for guard in table.all_guards()}
    assert guards and not guards & rule_codes()  # a guard holds rules back, it decides nothing


def test_each_controller_fires_the_triggers_its_builders_and_rules_give():
    """The open-loop script times its phases; a state machine fires every trigger but an
    event detector's, and its own detector's (the builder's mark); the committed records'
    triggers lie within these (tests/sweep/test_records.py loads them all)."""
    from tegrasp_drake.control.grasp_modes import Trigger
    fired = {entry.name: entry.triggers() for entry in CONTROLLERS}
    assert fired["open_loop"] == {Trigger.TIMER}
    shared = {Trigger.TIMER, Trigger.THRESHOLD, Trigger.CORRECTIVE, Trigger.FAULT,
              Trigger.CORRECTIVE_EVENT}
    assert fired["heuristic"] == shared | {Trigger.HEURISTIC_EVENT}
    for name in ("memorized", "taxel_aware", "fixed_load_time"):
        assert fired[name] == shared | {Trigger.MEMORIZED_EVENT}, name
