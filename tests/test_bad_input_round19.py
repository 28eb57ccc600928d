"""Bad inputs the nineteenth review found, one test per rule."""

import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
from tegrasp_drake.transfer.matrix import LoadTransferSpec

_TRANSFER = "worlds:\n  a: {scenario: faithful_world}\ncells:\n  memorize_in: [a]\n  run_in: [a]\n"


# Rule: a section of a transfer or sensitivity spec written as null is refused, as a null
# field of any configuration is; only a section left out takes its default (the paper's
# sweep, every uncertain parameter).
@pytest.mark.parametrize("text, field", [
    (_TRANSFER + "sweep: null\n", "sweep"),
], ids=["transfer-sweep"])
def test_a_null_section_of_a_transfer_spec_is_refused(tmp_path, text, field):
    spec = tmp_path / "t.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=f"field '{field}' is null: give a value, or leave"):
        LoadTransferSpec(spec)


@pytest.mark.parametrize("text, field", [
    ("parameters: [gripper.pad_friction]\nsweep: null\n", "sweep"),
    ("parameters: null\nsweep: {objects: [box]}\n", "parameters"),
], ids=["sweep", "parameters"])
def test_a_null_section_of_a_sensitivity_spec_is_refused(tmp_path, text, field):
    spec = tmp_path / "s.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=f"field '{field}' is null: give a value, or leave"):
        LoadSensitivitySpec(spec)
