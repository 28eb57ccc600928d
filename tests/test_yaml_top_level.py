"""Every YAML file kind the project reads (scenario file, sweep, transfer and sensitivity
specs, hardware config, tactile calibration) whose top level is a list or a scalar is refused
in one line naming the file, its kind and that its top level must be a mapping, not as a
missing key or an unnamed shape (typed_yaml.require_mapping)."""

import pytest

from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.hardware.myrio.tactile_calibration import LoadTactileCalibration
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario import LoadScenario
from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.transfer.matrix import LoadTransferSpec

LOADERS = {"the scenario file": LoadScenario, "the sweep spec": LoadSweepSpec,
           "the transfer spec": LoadTransferSpec, "the sensitivity spec": LoadSensitivitySpec,
           "the hardware config": LoadHardwareConfig,
           "the tactile calibration": LoadTactileCalibration}


@pytest.mark.parametrize("top_level", ["- box\n- cylinder\n", "42\n", "just words\n"])
@pytest.mark.parametrize("what", sorted(LOADERS))
def test_a_file_whose_top_level_is_not_a_mapping_says_so(what, top_level, tmp_path):
    path = tmp_path / "file.yaml"
    path.write_text(top_level)
    with pytest.raises(ConfigError) as refused:
        LOADERS[what](path)
    message = str(refused.value)
    assert message.startswith(f"{path}: {what}'s top level must be a mapping of "), message
    assert "\n" not in message


def test_a_scenario_file_says_its_keys_are_scenario_names(tmp_path):
    path = tmp_path / "list.yaml"
    path.write_text("- default\n")
    with pytest.raises(ConfigError, match="must be a mapping of scenario names"):
        LoadScenario(path)


# The tag each loader's file may carry at its top level (None: none, the scenario file being
# a mapping of names, no one class's).
OWN_TAGS = {"the scenario file": None, "the sweep spec": "!SweepSpec",
            "the transfer spec": "!TransferSpec", "the sensitivity spec": "!SensitivitySpec",
            "the hardware config": "!HardwareStationConfig",
            "the tactile calibration": "!TactileCalibration"}


@pytest.mark.parametrize("what, foreign", [
    (what, foreign) for what in sorted(LOADERS)
    for foreign in ("!Scenario", "!HardwareStationConfig", "!SweepSpec", "!SensitivitySpec")
    if foreign != OWN_TAGS[what]])
def test_a_file_tagged_as_another_kind_is_refused_not_read_as_untagged(what, foreign, tmp_path):
    path = tmp_path / "file.yaml"
    path.write_text(f"{foreign}\nzero_samples: 100\nobjects: [box]\n")
    with pytest.raises(ConfigError) as refused:
        LOADERS[what](path)
    message = str(refused.value)
    assert message.startswith(f"{path}: the file is tagged {foreign}, but it is read as "), message
    assert ("remove the tag" in message and "\n" not in message), message
