"""`tegrasp transfer` and `tegrasp sensitivity` tell of their event recordings as `tegrasp
sweep` tells of its trials: results on stdout, the steps logged at INFO (on stderr) under
-v and nowhere without it. The recordings are stand-ins (the package's events), so nothing is
simulated."""

import textwrap

import pytest

from tegrasp_drake.cli import main
from tegrasp_drake.events import load_memorized_events
from tegrasp_drake.recording import ensemble_events, paper_events
from tegrasp_drake.recording.ensemble_events import ENSEMBLE_FOLDER
from tegrasp_drake.rig import paths
from tests.transfer.test_matrix import TWO_WORLDS

SENSITIVITY = """\
    parameters: [tactile.capacitive.decimation]
    events: each_point
    sweep:
      objects: [box]
      controllers: [memorized]
      grid: [[0.0, 0.0]]
      attempts: 1
      base_seed: 600
    """


@pytest.fixture
def recordings(monkeypatch):
    """Stands in for the ideal-grasp recordings; the objects asked for, in order."""
    asked = []

    def record_events(object_name, scenario, **_):
        asked.append(object_name)
        return load_memorized_events(paths.package_events_dir(), object_name)

    def record_object_ensemble(object_name, scenario, runs, **_):
        asked.append(object_name)
        return load_memorized_events(paths.package_events_dir() / ENSEMBLE_FOLDER, object_name)

    monkeypatch.setattr(paper_events, "record_events", record_events)
    monkeypatch.setattr(ensemble_events, "record_object_ensemble", record_object_ensemble)
    return asked


@pytest.mark.parametrize("command, spec_text, world", [
    ("transfer", TWO_WORLDS, "ideal"),
    ("sensitivity", SENSITIVITY, "default"),
])
@pytest.mark.parametrize("verbose", [True, False])
def test_the_recordings_are_logged_under_verbose_and_not_printed(
        command, spec_text, world, verbose, recordings, tmp_path, monkeypatch, capsys, caplog):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.yaml").write_text(textwrap.dedent(spec_text))
    argv = [command, "spec.yaml", "--out", "out", "--workers", "1", "--trial-function",
            "tests.fake_trials:fake_trial_with_events"] + (["-v"] if verbose else [])
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 0, err
    assert recordings, "nothing was recorded: the test saw no recording to tell of"
    line = f"recording the events of box in world {world}"
    assert line not in out  # stdout holds the results
    info = [record.getMessage() for record in caplog.records
            if record.levelname == "INFO" and record.name.startswith("tegrasp_drake")]
    assert any(line in message for message in info) == verbose, info
