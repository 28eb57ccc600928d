"""Bad inputs the nineteenth review found, one test per rule."""

import json
import logging

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


# Rule: what an --overwrite replaces or removes of the earlier run is said under -v (INFO),
# each file by name.
def test_an_overwrite_says_what_it_replaced_and_removed(tmp_path, caplog):
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    for name in ("trial.npz", "states.png", "notes.txt"):
        (folder / name).write_bytes(b"earlier")
    (folder / "result.json").write_text(json.dumps({"log": str(folder / "trial.npz")}))
    with caplog.at_level(logging.INFO, logger=run_folder.__name__):
        with run_folder.staged_run(folder) as stage:
            (stage / "trial.npz").write_bytes(b"new")
            run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    said = "\n".join(record.getMessage() for record in caplog.records)
    assert "replaced the earlier run's result.json, trial.npz" in said, said
    assert "removed the earlier run's states.png" in said, said
    assert "notes.txt" not in said, said
