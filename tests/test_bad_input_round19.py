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


def _count_listings(monkeypatch):
    """A list that grows by one each time a sweep's trials are listed (expand_trials)."""
    from tegrasp_drake.sweep import runner, spec
    listed = []

    def counted(*args, **kwargs):
        listed.append(1)
        raise AssertionError("the trials were listed")
    monkeypatch.setattr(spec, "expand_trials", counted)
    monkeypatch.setattr(runner, "expand_trials", counted)
    return listed


# Rule: a study has a ceiling a confirmation cannot lift (its trials are listed in memory
# before the first runs): from the command line and from Python, refused before listing.
def test_a_study_over_the_ceiling_is_refused_even_confirmed(tmp_path, monkeypatch, capsys):
    from tegrasp_drake import cli
    from tegrasp_drake.sweep.runner import SweepError, run_sweep
    from tegrasp_drake.sweep.spec import SweepSpec
    from tests.fake_trials import fake_trial_with_events
    ceiling = 1_000_000  # MAX_CONFIRMED_TRIALS
    listed = _count_listings(monkeypatch)
    attempts = ceiling // 81 + 1  # 81 trials an attempt: 3 objects, 9 markers, 3 controllers
    code = cli.main(["sweep", "--objects", "box", "thick_cylinder", "thin_cylinder",
                     "--attempts", str(attempts), "--trial-function",
                     "tests.fake_trials:fake_trial_with_events",
                     "--workers", "1", "--no-progress", "--out", str(tmp_path / "o")])
    error = capsys.readouterr().err
    assert code != 0 and f"at most {ceiling} " in error and "split it" in error, error
    assert "Traceback" not in error and not listed, error
    with pytest.raises((ConfigError, SweepError, ValueError), match=f"{ceiling}"):
        run_sweep(SweepSpec(attempts=attempts), fake_trial_with_events, tmp_path / "p",
                  confirmed_trials=attempts * 81)
    assert not listed


def test_a_confirmation_over_the_ceiling_is_refused(tmp_path, capsys):
    from tegrasp_drake import cli
    code = cli.main(["sweep", "--confirm-trials", "1000001", "--objects", "box",
                     "--attempts", "1", "--trial-function",
                     "tests.fake_trials:fake_trial_with_events", "--workers", "1", "--no-progress",
                     "--out", str(tmp_path / "o")])
    error = capsys.readouterr().err
    assert code != 0 and "--confirm-trials" in error and "split" in error, error
