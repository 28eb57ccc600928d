"""Bad inputs the twelfth review found, one test per rule."""

import pytest

import tegrasp_drake as T
from tegrasp_drake.rig.typed_yaml import ConfigError


def _refused(call, *words) -> str:
    """The one-line ConfigError of `call()`, which names each of `words`."""
    with pytest.raises(ConfigError) as refused:
        call()
    message = str(refused.value)
    assert "\n" not in message and len(message) < 400, message
    for word in words:
        assert word in message, message
    return message


# Rule: an empty text or list is a value only where the field declares what empty means
# (an empty LCM URL would be LCM's default bus, an empty port no device); a list of a fixed
# length (one value per joint) holds that many in every config that has it.
@pytest.mark.parametrize("text, field", [
    ("arm: {tracker: {continuous_joints: []}}\n", "arm.tracker.continuous_joints"),
    ("arm: {tracker: {continuous_joints: [true]}}\n", "arm.tracker.continuous_joints"),
    ('arm: {lcm_url: ""}\n', "arm.lcm_url"),
    ('gripper: {port: ""}\n', "gripper.port"),
    ('tactile: {port: ""}\n', "tactile.port"),
])
def test_a_hardware_config_refuses_an_empty_or_short_value(tmp_path, text, field):
    path = tmp_path / "hardware.yaml"
    path.write_text(text)
    _refused(lambda: T.LoadHardwareConfig(path), str(path), f"'{field}'")


def test_an_empty_value_is_kept_where_the_field_declares_what_empty_means(tmp_path):
    path = tmp_path / "hardware.yaml"
    path.write_text('tactile: {port: /dev/ttyACM0, calibration_file: ""}\n')
    assert T.LoadHardwareConfig(path).tactile.calibration_file == ""
    _refused(lambda: T.LoadScenario(name="box", overrides=["object.shape=''"]),
             "'object.shape'")
    assert T.LoadScenario(name="box", overrides=[
        "controller.event_object_may_differ=[]"]).controller.event_object_may_differ == []
