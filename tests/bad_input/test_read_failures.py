"""A file the system fails to read part-way (EIO: a failing disk, a network file system gone)
is said to be one that could not be read, with the system's error, never to be truncated,
corrupt or damaged: its content is not in question, and it is not to be remade."""

import errno
import pathlib
import shutil
import zipfile

import pytest

from tegrasp_drake.emulators.myrio_emulator import TactileRecordingError, load_tactile_recording
from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.bad_input.probes import assert_one_line_error, run_cli, trial_log_with

READ_FAILURE_WORDS = ("cannot be read (Input/output error); the system could not read it, "
                      "which says nothing of its content")


def _input_output_error(*args, **kwargs):
    raise OSError(errno.EIO, "Input/output error")


@pytest.fixture
def log_that_fails_part_way(tmp_path, monkeypatch):
    """A trial log whose zip directory reads, then whose members fail with EIO."""
    path = tmp_path / "trial.npz"
    load_trial_log(trial_log_with(tmp_path / "made.npz")).save(path)
    monkeypatch.setattr(zipfile.ZipExtFile, "read", _input_output_error)
    return path


@pytest.mark.parametrize("read, error", [(load_trial_log, TrialLogError),
                                         (load_tactile_recording, TactileRecordingError)],
                         ids=["trial-log", "tactile-recording"])
def test_a_trial_log_that_fails_part_way_is_not_called_corrupt(log_that_fails_part_way,
                                                              read, error):
    with pytest.raises(error) as refused:
        read(log_that_fails_part_way)
    text = str(refused.value)
    assert f"'{log_that_fails_part_way}' {READ_FAILURE_WORDS}" in text, text
    assert not any(word in text for word in ("corrupt", "truncated", "damaged", "remake")), text


def test_plot_names_the_read_failure_of_a_trial_log(log_that_fails_part_way, tmp_path, capfd):
    code, text = run_cli(["plot", "trial", str(log_that_fails_part_way), "--out",
                          str(tmp_path / "t.png")], capfd)
    assert_one_line_error(code, text, f"'{log_that_fails_part_way}' {READ_FAILURE_WORDS}")
    assert "corrupt" not in text


def test_a_spec_that_fails_part_way_is_a_file_that_cannot_be_read(tmp_path, capfd, monkeypatch):
    from tegrasp_drake.rig import typed_yaml
    spec = tmp_path / "sp.yaml"
    spec.write_text("objects: [box]\n")
    monkeypatch.setattr(typed_yaml, "read_bounded", _input_output_error)
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "o")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, f"{spec}: cannot read the sweep spec: Input/output "
                          "error; the system could not read it")
    assert "owner" not in text


@pytest.fixture
def json_reads_fail_part_way(monkeypatch):
    """Every bounded read of a JSON file (event files, indexes, trial records) fails with EIO."""
    from tegrasp_drake.rig import files
    monkeypatch.setattr(files, "read_bounded", _input_output_error)


def test_an_event_file_that_fails_part_way_is_neither_damaged_nor_its_owners(
        json_reads_fail_part_way):
    from tegrasp_drake.events.event_file import MemorizedEventError, read_memorized_event
    path = next((pathlib.Path(__file__).parents[2] / "events" / "box").glob("*.json"))
    with pytest.raises(MemorizedEventError) as refused:
        read_memorized_event(path)
    text = str(refused.value)
    assert "Input/output error" in text and "says nothing of its content" in text, text
    assert not any(word in text for word in ("owner", "corrupt", "damaged", "record-events"))


def test_a_trial_record_that_fails_part_way_is_neither_set_aside_nor_its_owners(
        tmp_path, json_reads_fail_part_way):
    from tegrasp_drake.rig.files import UserPathError
    from tegrasp_drake.sweep.records import read_record
    record = tmp_path / "memorized.box.m00.a0.json"
    shutil.copy(pathlib.Path(__file__).parents[2] / "analysis" / "results_seed0" / "trials"
                / record.name, record)
    with pytest.raises(UserPathError) as refused:
        read_record(record)
    text = str(refused.value)
    assert "Input/output error" in text and "says nothing of its content" in text, text
    assert "neither set aside nor run again" in text and "owner" not in text, text
