"""A key set twice through KEY=VALUE settings is refused however it is written: a mapping
setting (`object={mass: 0.1}`) sets each key it holds, nested ones too, as a dotted one
does, and replaces its section, so a key an earlier setting set inside it and the mapping
leaves out would be lost. One rule (typed_yaml.key_set_twice) for LoadScenario's and
LoadHardwareConfig's overrides, --set and --config-set, and a spec's lists."""

import pytest

from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tests.bad_input.probes import assert_one_line_error, run_cli

SET_TWICE = [
    (["object={mass: 0.1}", "object.mass=0.2"], "object.mass", False),
    (["object.mass=0.2", "object={mass: 0.1}"], "object.mass", False),
    (["object={name: box, mass: 0.1}", "object={mass: 0.2}"], "object.mass", False),
    (["gripper={pad_friction: 1.0}", "grasp.hold_s=2.0", "gripper.pad_friction=0.9"],
     "gripper.pad_friction", False),
    (["placement={offset: [0.0, 0.01]}", "placement.offset=[0.0, 0.0]"], "placement.offset",
     False),
    (["object.mass=0.2", "object={name: box}"], "object.mass", True),
    (["object.mass=0.2", "object={}"], "object.mass", True),
    (["object.mass=0.2", "object=null"], "object", False),
]
IDS = ["mapping-then-dotted", "dotted-then-mapping", "two-mappings", "with-others-between",
       "a-list-value", "mapping-drops-dotted", "empty-mapping-drops-dotted", "null-section"]


@pytest.mark.parametrize("overrides, key, dropped", SET_TWICE, ids=IDS)
def test_load_scenario_refuses_a_key_set_twice_however_written(overrides, key, dropped):
    with pytest.raises(ConfigError) as refused:
        LoadScenario(overrides=overrides)
    message = str(refused.value)
    assert message.startswith(f"LoadScenario: argument 'overrides' sets {key} twice ("), message
    assert "\n" not in message and message.count(" at [") == 2, message
    assert ("which replaces the whole section" in message) == dropped, message


@pytest.mark.parametrize("overrides", [
    ["object={name: box}", "object.mass=0.2"],  # a mapping, then a key it does not hold
    ["object={}", "object.mass=0.2"],
    ["object={mass: 0.2}", "object.mass=0.2"],  # the same value twice
    ["object.mass=0.2", "object={name: box, mass: 0.2}"],
], ids=["refines-a-mapping", "refines-an-empty-mapping", "same-value", "mapping-keeps-it"])
def test_settings_that_refine_a_mapping_or_repeat_a_value_load(overrides):
    assert LoadScenario(overrides=overrides).object.mass == 0.2


def test_hardware_config_overrides_refuse_a_key_set_by_a_mapping_and_a_dotted_one(tmp_path):
    path = tmp_path / "hw.yaml"
    path.write_text("gripper: {port: /dev/ttyUSB3}\n")
    for overrides in (["watchdog={arm_timeout: 0.2}", "watchdog.arm_timeout=0.3"],
                      ["watchdog.arm_timeout=0.3", "watchdog={arm_timeout: 0.2}"]):
        with pytest.raises(ConfigError, match="argument 'overrides' sets "
                                              "watchdog.arm_timeout twice"):
            LoadHardwareConfig(path, overrides)


@pytest.mark.parametrize("argv, words", [
    (["trial", "--set", "object={mass: 0.1}", "--set", "object.mass=0.2"],
     "--set sets object.mass twice ('object={mass: 0.1}', then 'object.mass=0.2'); set it once"),
    (["trial", "--set", "object.mass=0.1", "--set", "object={name: box}"],
     "--set sets object.mass twice ('object.mass=0.1', then 'object={name: box}', which "
     "replaces the whole section object without it); set it once: in that mapping, or after it"),
    (["hardware", "--config-set", "watchdog={arm_timeout: 0.2}", "--config-set",
      "watchdog.arm_timeout=0.3"], "--config-set sets watchdog.arm_timeout twice"),
], ids=["set", "set-dropped", "config-set"])
def test_the_command_line_refuses_a_key_set_by_a_mapping_and_a_dotted_setting(
        argv, words, tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, words)
    assert code == 2, text


def test_a_sweep_specs_overrides_refuse_a_key_set_by_a_mapping_and_a_dotted_one(tmp_path):
    spec = tmp_path / "s.yaml"
    spec.write_text("objects: [box]\nscenario_overrides: ['grasp={hold_s: 2.0}', "
                    "'grasp.hold_s=3.0']\n")
    with pytest.raises(ConfigError, match=r"field 'scenario_overrides' sets grasp.hold_s twice "
                                          r"\('grasp=\{hold_s: 2.0\}' at \[0\]"):
        LoadSweepSpec(spec)
