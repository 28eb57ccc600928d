"""A section of any configuration file written as null (`gripper:` with nothing after it,
`object: null`) is refused naming the file and the section, by one rule that every loader
shares (typed_yaml.refuse_null_section): a null is neither the section's defaults nor an
error about a mapping's type."""

import pytest

from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.transfer.matrix import LoadTransferSpec

_EMPTY = "is empty (null): give its fields, or remove the section to use the defaults"
_REQUIRED = "is empty (null): give its fields"
_TRANSFER = "worlds: {a: {scenario: default}}\ncells: [[a, a]]\n"


def _scenario(path):
    return LoadScenario(path, name="mine")


@pytest.mark.parametrize("load, text, field, words", [
    (LoadHardwareConfig, "gripper:\n", "gripper", _EMPTY),
    (LoadHardwareConfig, "arm: {tracker: null}\n", "arm.tracker", _EMPTY),
    (_scenario, "mine:\n  object: null\n", "object", _EMPTY),
    (_scenario, "mine:\n  placement:\n  random_seed: 1\n", "placement", _EMPTY),
    (_scenario, "mine:\n  station: ~\n", "station", _EMPTY),
    (_scenario, "mine:\n  simulator_config: null\n", "simulator_config", _EMPTY),
    (LoadSweepSpec, "objects: [box]\nrandomisation:\n", "randomisation", _EMPTY),
    (LoadSweepSpec, "objects: [box]\ngrid: null\n", "grid", _EMPTY),
    (LoadSweepSpec, "objects: [box]\nuser_objects: null\n", "user_objects", _EMPTY),
    (LoadTransferSpec, _TRANSFER + "sweep:\n", "sweep", _EMPTY),
    (LoadTransferSpec, "worlds:\ncells: [[a, a]]\n", "worlds", _REQUIRED),
    (LoadTransferSpec, "worlds: {a: null}\ncells: [[a, a]]\n", "worlds.a", _REQUIRED),
    (LoadTransferSpec, "worlds: {a: {scenario: default}}\ncells: null\n", "cells", _REQUIRED),
    (LoadSensitivitySpec, "sweep: null\n", "sweep", _EMPTY),
    (LoadSensitivitySpec, "sweep: {objects: [box], randomisation: null}\n",
     "randomisation", _EMPTY),
], ids=["hardware-gripper", "hardware-arm.tracker", "scenario-object", "scenario-placement",
        "scenario-station", "scenario-drake-section", "sweep-randomisation", "sweep-grid",
        "sweep-user_objects", "transfer-sweep", "transfer-worlds", "transfer-world",
        "transfer-cells", "sensitivity-sweep", "sensitivity-sweep-section"])
def test_a_section_given_as_null_is_refused_naming_file_and_field(load, text, field, words,
                                                                   tmp_path):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as caught:
        load(path)
    message = str(caught.value)
    assert message.startswith(str(path)) and "\n" not in message
    assert f"field '{field}' {words}" in message, message
    if words == _REQUIRED:
        assert "remove the section" not in message


def test_a_section_set_to_null_by_an_override_names_the_override(tmp_path):
    with pytest.raises(ConfigError, match=f"--set object=null: field 'object' {_EMPTY[:9]}"):
        LoadScenario(overrides=["object=null"])
