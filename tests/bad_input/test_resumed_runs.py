"""A run resumed into its folder must be the same run: a sweep resumed with other memorized
events and a sensitivity folder of another study (or of other points) are refused; one
whose points match resumes."""

import json
import shutil

import pytest

from tests.bad_input.probes import (FAKE_TRIALS, events_copy_with_index, folder_contents, run_cli,
                                    sweep_with_events)


# Rule: the memorized events a sweep's trials match against are a setting of the sweep, as
# its seeds and overrides are: each record names them (a content hash, and the folder), and a
# resume whose events differ is refused, naming both, before any trial runs. The same events
# in another folder (a copy) are the same setting.
def test_a_sweep_resumed_with_other_memorized_events_is_refused(tmp_path, capfd):
    from tegrasp_drake.sweep import load_records
    events = events_copy_with_index(tmp_path)
    other = tmp_path / "other_events"
    shutil.copytree(events, other)
    reach_load = other / "box" / "reach_load.json"
    event = json.loads(reach_load.read_text())  # the SA channels swapped: still a valid event
    samples = event["samples"]
    samples["sa_left"], samples["sa_right"] = samples["sa_right"], samples["sa_left"]
    reach_load.write_text(json.dumps(event))
    out = tmp_path / "out"
    code, text = sweep_with_events(tmp_path, out, events, capfd)
    assert code == 0, text
    records = load_records(out).records
    assert len(records) == 2 and all(r["events"]["sha256"] for r in records.values())
    first = sorted(records)[0]
    (out / "trials" / (sorted(records)[1].replace("/", ".") + ".json")).unlink()
    code, text = sweep_with_events(tmp_path, out, other, capfd)
    assert code == 2, text
    assert "other memorized events" in text and str(other) in text and str(events) in text
    assert sorted(load_records(out).records) == [first]  # nothing ran
    same = tmp_path / "same_events"  # a copy of the first events: the sweep resumes
    shutil.copytree(events, same)
    code, text = sweep_with_events(tmp_path, out, same, capfd)
    assert code == 0, text
    assert len(load_records(out).records) == 2

_SWEEP = ("sweep: {controllers: [memorized], attempts: 1, objects: [box], grid: [[0.0, 0.0]], "
          "base_seed: 600}\n")

_MODULUS = "parameters: [tactile.pad_modulus_pa]\n"

_FRICTION = "parameters: [gripper.pad_friction]\n"


@pytest.fixture
def stopped_studies(monkeypatch):
    """Sensitivity runs that stop where the first event recording would begin (run_transfer,
    after points.json is written), so nothing is simulated; the list of their out folders."""
    import tegrasp_drake.sensitivity.report as report
    import tegrasp_drake.transfer.matrix as matrix
    started = []

    def stopped(spec, trial_function, out_dir, **_):
        started.append(out_dir)
        return {}
    monkeypatch.setattr(matrix, "run_transfer", stopped)
    monkeypatch.setattr(report, "write_sensitivity_report", lambda *_, **__: [])
    return started


def _sensitivity(tmp_path, capfd, spec_text, *options, name="s.yaml"):
    spec = tmp_path / name
    spec.write_text(spec_text)
    return run_cli(["sensitivity", str(spec), "--out", str(tmp_path / "out"), "--workers",
                    "1", "--no-progress", *options, *FAKE_TRIALS], capfd)


def _contents(out):
    """The folder's files (a run holds the folder itself, leaving no lock file)."""
    return folder_contents(out)


def _refused_as_another_study(code, message, *words):
    """The sweep's resume refusal: exit 2, one line naming what differs and the remedy."""
    assert code == 2, message
    assert message.startswith("tegrasp: error: ") and message.count("\n") == 0, \
        message
    assert "another sensitivity study" in message and "give another --out" in message, message
    for word in words:
        assert word in message, message


# Rule: a sensitivity folder names its study (the design, one-at-a-time or a Latin hypercube
# of N points and its seed; the parameters and their ranges; where events are memorized and
# at which seed; the sweep), and a resume into it by another study is refused in one line naming what differs,
# before anything is written, exit 2 as a sweep's (docs/sweeps.md, "Resuming"); the folder's
# own study still resumes.
@pytest.mark.parametrize("second, options, words", [
    (_MODULUS + _SWEEP, ["--latin-hypercube", "4"],
     ["one-at-a-time", "a Latin hypercube of 4 points"]),
    (_FRICTION + _SWEEP, [], ["parameters", "tactile.pad_modulus_pa", "gripper.pad_friction"]),
    (_MODULUS + "events: default_point\n" + _SWEEP, [], ["events", "default_point"]),
    (_MODULUS + "events_seed: 650\n" + _SWEEP, [], ["events_seed 0 in the folder, not 650"]),
    (_MODULUS + _SWEEP.replace("attempts: 1", "attempts: 2"), [], ["sweep", "attempts"]),
])
def test_a_sensitivity_folder_of_another_study_is_refused(tmp_path, capfd, stopped_studies,
                                                          second, options, words):
    code, message = _sensitivity(tmp_path, capfd, _MODULUS + _SWEEP)
    assert code == 0 and len(stopped_studies) == 1, message
    before = _contents(tmp_path / "out")
    code, message = _sensitivity(tmp_path, capfd, second, *options, name="other.yaml")
    _refused_as_another_study(code, message.strip(), str(tmp_path / "out"), *words)
    assert len(stopped_studies) == 1  # nothing recorded or run
    assert _contents(tmp_path / "out") == before
    code, message = _sensitivity(tmp_path, capfd, _MODULUS + _SWEEP)  # its own study resumes
    assert code == 0 and len(stopped_studies) == 2, message


# Rule: a folder written before folders named their study (points.json a mapping of point
# names to assignments) resumes when its points are exactly the study's, and from then on
# names its study; with other points it is refused as another study's.
def test_a_sensitivity_folder_from_before_studies_were_named_resumes_if_its_points_match(
        tmp_path, capfd, stopped_studies):
    from tegrasp_drake.sensitivity.study import LoadSensitivitySpec, one_at_a_time
    spec = tmp_path / "s.yaml"
    spec.write_text(_MODULUS + _SWEEP)
    (tmp_path / "out").mkdir()
    old = {point.name: list(point.assignments())
           for point in one_at_a_time(LoadSensitivitySpec(spec))}
    (tmp_path / "out" / "points.json").write_text(json.dumps(old))
    code, message = _sensitivity(tmp_path, capfd, _MODULUS + _SWEEP)
    assert code == 0 and len(stopped_studies) == 1, message
    code, message = _sensitivity(tmp_path, capfd, _MODULUS + _SWEEP, "--latin-hypercube", "2")
    _refused_as_another_study(code, message.strip(), "one-at-a-time")
    assert len(stopped_studies) == 1


def test_a_sensitivity_folder_from_before_studies_were_named_with_other_points_is_refused(
        tmp_path, capfd, stopped_studies):
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "points.json").write_text(json.dumps(
        {"default": [], "gripper_pad_friction_low": ["gripper.pad_friction=0.91"]}))
    before = _contents(tmp_path / "out")
    code, message = _sensitivity(tmp_path, capfd, _MODULUS + _SWEEP)
    _refused_as_another_study(code, message.strip(), "gripper_pad_friction_low",
                              "tactile_pad_modulus_pa_low")
    assert not stopped_studies
    assert _contents(tmp_path / "out") == before
