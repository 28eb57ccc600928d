"""Bad inputs the fourteenth hostile pass found in resumed studies, one test per rule."""

import json

import pytest

from tests.test_bad_input import folder_contents, run_cli
from tests.test_bad_input_round14 import _FAKE_TRIALS

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
                    "1", "--no-progress", *options, *_FAKE_TRIALS], capfd)


def _contents(out):
    """The folder's files (a run holds the folder itself, leaving no lock file)."""
    return folder_contents(out)


def _refused_as_another_study(code, message, *words):
    """The sweep's resume refusal: exit 2, one line naming what differs and the remedy."""
    assert code == 2, message
    assert message.startswith("tegrasp sensitivity: error: ") and message.count("\n") == 0, \
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
