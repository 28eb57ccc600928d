"""Durable trial records: round trip, and detection of partial or corrupt files."""

import json
import pathlib

import numpy as np
import pytest

from tegrasp_drake.sweep.records import (
    RecordError,
    load_records,
    make_record,
    read_record,
    record_path,
    remove_stale_staging_files,
    write_record,
)
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tests.fake_trials import fake_trial


@pytest.fixture
def trials():
    return [t.to_dict() for t in expand_trials(SweepSpec(objects=("box",), attempts=1))]


def test_record_round_trip(tmp_path, trials):
    written = {}
    for trial in trials[:5]:
        record = make_record(trial, result=fake_trial(trial))
        path = write_record(tmp_path, record)
        assert path == record_path(tmp_path, trial["trial_id"])
        written[trial["trial_id"]] = record
    loaded = load_records(tmp_path)
    assert loaded.corrupt == {}
    assert loaded.records == written
    assert loaded.records[trials[0]["trial_id"]]["trial"] == trials[0]


def test_error_record_round_trip(tmp_path, trials):
    error = {"type": "RuntimeError", "message": "diverged", "traceback": "Traceback ..."}
    write_record(tmp_path, make_record(trials[0], error=error))
    record = load_records(tmp_path).records[trials[0]["trial_id"]]
    assert record["status"] == "error" and record["error"] == error
    assert record["result"] is None


def test_writing_leaves_no_temporary_file(tmp_path, trials):
    write_record(tmp_path, make_record(trials[0], result=fake_trial(trials[0])))
    assert [p.name for p in (tmp_path / "trials").iterdir()] == [
        "memorized.box.m00.a0.json"]


def test_numpy_values_are_stored_as_plain_json(tmp_path, trials):
    result = {**fake_trial(trials[0]), "hold_success": np.bool_(True),
              "sim_time_s": np.float64(2.5), "forces": np.array([1.0, 2.0])}
    write_record(tmp_path, make_record(trials[0], result=result))
    stored = load_records(tmp_path).records[trials[0]["trial_id"]]["result"]
    assert stored["hold_success"] is True and stored["forces"] == [1.0, 2.0]


def test_nan_and_objects_cannot_be_recorded(trials):
    with pytest.raises(RecordError, match="JSON"):
        make_record(trials[0], result={**fake_trial(trials[0]), "sim_time_s": float("nan")})
    with pytest.raises(RecordError, match="JSON"):
        make_record(trials[0], result={**fake_trial(trials[0]), "plant": object()})


def _one_record(tmp_path, trials):
    trial = trials[0]
    path = write_record(tmp_path, make_record(trial, result=fake_trial(trial)))
    return path


def test_truncated_record_is_corrupt(tmp_path, trials):
    path = _one_record(tmp_path, trials)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    loaded = load_records(tmp_path)
    assert loaded.records == {}
    assert "not valid JSON" in loaded.corrupt[path]


def test_empty_record_is_corrupt(tmp_path, trials):
    path = _one_record(tmp_path, trials)
    path.write_bytes(b"")
    assert path in load_records(tmp_path).corrupt


def test_flipped_byte_in_a_number_fails_the_checksum(tmp_path, trials):
    path = _one_record(tmp_path, trials)
    text = path.read_text()
    # Flip one bit of the seed's last digit: still valid JSON, different content.
    seed_text = str(trials[0]["seed"])
    position = (text.index(f'"seed": {seed_text}', text.index('"trial": '))  # the trial's
                + len('"seed": ') + len(seed_text) - 1)
    data = bytearray(path.read_bytes())
    data[position] ^= 0x01
    path.write_bytes(bytes(data))
    record = json.loads(path.read_text())  # Parses...
    assert record["trial"]["seed"] != trials[0]["seed"]
    record, reason = read_record(path)     # ...but is caught.
    assert record is None and "checksum" in reason


def test_flipped_boolean_fails_the_checksum(tmp_path, trials):
    path = _one_record(tmp_path, trials)
    text = path.read_text()
    flipped = (text.replace('"hold_success": true', '"hold_success": false')
               if '"hold_success": true' in text
               else text.replace('"hold_success": false', '"hold_success": true'))
    path.write_text(flipped)
    assert "checksum" in load_records(tmp_path).corrupt[path]


def test_record_under_another_trials_name_is_corrupt(tmp_path, trials):
    path = _one_record(tmp_path, trials)
    moved = path.with_name("memorized.box.m22.a0.json")
    path.rename(moved)
    assert "does not belong" in load_records(tmp_path).corrupt[moved]


def test_record_of_another_format_version_is_corrupt(tmp_path, trials):
    path = _one_record(tmp_path, trials)
    record = json.loads(path.read_text())
    record["format_version"] = 99
    path.write_text(json.dumps(record))
    assert "format_version" in load_records(tmp_path).corrupt[path]


def test_staging_files_are_ignored_then_removed(tmp_path, trials):
    from tests.commands.test_run_folder import _ended_process_id
    path = _one_record(tmp_path, trials)
    stray = path.parent / f".{path.name}.abcd1234.{_ended_process_id()}.staging"
    stray.write_text('{"format": "tegrasp-sw')
    loaded = load_records(tmp_path)
    assert len(loaded.records) == 1 and loaded.corrupt == {}
    assert remove_stale_staging_files(tmp_path, [trials[0]["trial_id"]]) == [stray]
    assert not stray.exists() and path.exists()


def test_every_committed_record_loads():
    """Every record committed under analysis/ passes the checks a record is read with (its
    result's relations, its trial's seed and draws): none is set aside as corrupt."""
    root = pathlib.Path(__file__).resolve().parents[2] / "analysis"
    folders = sorted({path.parent for path in root.glob("**/trials")})
    assert len(folders) >= 50
    for folder in folders:
        loaded = load_records(folder)
        assert loaded.records and loaded.corrupt == {}, folder
