"""Public dataclasses accept their fields only: a misspelt or moved setting assigned in a
script is refused naming its class and what to write, never kept and ignored."""

import dataclasses
import subprocess
import sys
import typing

import pytest

from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_class
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.scenario.scenario import Scenario, scenario_to_yaml


def assignment_error_in_a_fresh_interpreter(module: str, cls: str, statement: str) -> str:
    """The AttributeError's text of `cls().<statement>` in a Python that imports only
    `module` (asserting the scenario package stays unimported)."""
    code = (f"import sys\nfrom {module} import {cls}\n"
            "assert 'tegrasp_drake.scenario' not in sys.modules\n"
            f"try:\n    {cls}().{statement}\nexcept AttributeError as error:\n"
            "    print(error)\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True).stdout.strip()


def _reachable_dataclasses():
    """Every dataclass a scenario can hold, whichever controller and station it names."""
    roots = [Scenario, HardwareStationConfig] + [controller_class(name)
                                                 for name in CONTROLLER_NAMES]
    found = []
    pending = list(roots)
    while pending:
        cls = pending.pop()
        if cls in found:
            continue
        found.append(cls)
        hints = typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            hint = hints.get(field.name)
            pending += [member for member in (hint, *typing.get_args(hint))
                        if isinstance(member, type) and dataclasses.is_dataclass(member)]
    return found


@pytest.mark.parametrize("cls", _reachable_dataclasses(), ids=lambda cls: cls.__name__)
def test_a_setting_that_is_not_a_field_is_refused(cls):
    instance = cls()
    with pytest.raises(AttributeError, match=f"{cls.__name__} has no field 'no_such_setting'"):
        instance.no_such_setting = 1.0
    for field in dataclasses.fields(cls)[:1]:  # a field is assigned as ever
        setattr(instance, field.name, getattr(instance, field.name))


@pytest.mark.parametrize("statement, advice", [
    ("scenario.object_offset = (0.01, 0.0)", "it is now 'placement.offset'"),
    ("scenario.controller.re_reach_enabled = False", "it is now 're_reach.enabled'"),
    ("scenario.vibration.mode_mass_kg = 0.03", "it is now 'film.mode_mass_kg'"),
    ("scenario.controller.re_reach.enabld = False", "did you mean 'enabled'?"),
])
def test_a_moved_or_misspelt_setting_names_what_to_write(statement, advice):
    scenario = Scenario()
    with pytest.raises(AttributeError) as raised:
        exec(statement, {"scenario": scenario})
    assert str(raised.value).endswith(advice)
    assert scenario_to_yaml(scenario) == scenario_to_yaml(Scenario())


def _frozen_public_dataclasses():
    """The frozen dataclasses of the package's public API (`tegrasp_drake.__all__`)."""
    import tegrasp_drake
    found = [getattr(tegrasp_drake, name) for name in tegrasp_drake.__all__]
    return [cls for cls in found if isinstance(cls, type) and dataclasses.is_dataclass(cls)
            and cls.__dataclass_params__.frozen]


def test_the_public_api_has_frozen_dataclasses():
    assert len(_frozen_public_dataclasses()) >= 3


@pytest.mark.parametrize("cls", _frozen_public_dataclasses(), ids=lambda cls: cls.__name__)
def test_a_frozen_field_assigned_says_how_to_make_a_changed_copy(cls):
    instance = object.__new__(cls)  # the refusal reads no field: no need to build one
    field = dataclasses.fields(cls)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError) as raised:
        setattr(instance, field, 1)
    message = str(raised.value)
    assert message.startswith(f"{cls.__name__}.{field} cannot be changed: make a changed copy "
                              "with dataclasses.replace(")
    assert message.endswith(f", {field}=...)") and "\n" not in message
    with pytest.raises(dataclasses.FrozenInstanceError, match="cannot be changed"):
        delattr(instance, field)


@pytest.mark.parametrize("cls", _frozen_public_dataclasses(), ids=lambda cls: cls.__name__)
def test_a_frozen_class_names_its_fields_for_an_attribute_that_is_not_one(cls):
    with pytest.raises(dataclasses.FrozenInstanceError,
                       match=f"^{cls.__name__} has no field 'no_such_setting': "):
        object.__new__(cls).no_such_setting = 1


def test_the_advice_calls_the_instance_by_its_class_names_last_word():
    from tegrasp_drake import MemorizedEvent
    with pytest.raises(dataclasses.FrozenInstanceError) as raised:
        object.__new__(MemorizedEvent).object_name = "box"
    assert str(raised.value) == (
        "MemorizedEvent.object_name cannot be changed: make a changed copy with "
        "dataclasses.replace(event, object_name=...)")
