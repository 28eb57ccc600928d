"""`tegrasp transfer` killed during its events stage (SIGKILL, as the OOM killer kills; SIGTERM,
as a scheduler stops a job), then run again into the same folder: nothing that had finished is
lost or redone, and nothing half-written is left. The recording is the package's events
(tests/fake_recording.py), the trials fake ones: the claim is the command's files."""

import hashlib
import signal
import subprocess
import sys

import pytest

from tegrasp_drake.events.events_folder import load_all_memorized_events, read_index
from tests.killed_runs import environment
from tests.transfer.test_matrix import transfer_arguments, write_spec

SPEC = """\
    worlds:
      ideal: {scenario: memorizing_world}
      faithful: {scenario: faithful_world}
    cells: [[ideal, faithful]]
    sweep:
      objects: [box, thin_cylinder]
      controllers: [memorized]
      grid: [[0.0, 0.0]]
      attempts: 1
      base_seed: 600
    """
OBJECTS = ("box", "thin_cylinder")
FILES_PER_OBJECT = 5  # an object's save renames its four event files and the index


def _transfer(tmp_path, kill: str) -> subprocess.CompletedProcess:
    out = tmp_path / "out"
    command = [sys.executable, "-m", "fake_recording", str(tmp_path / "recorded.txt"), kill,
               "--", *transfer_arguments(tmp_path / "transfer.yaml", out, "--trial-function",
                                         "tests.fake_trials:fake_trial_with_events")]
    return subprocess.run(command, env=environment(), capture_output=True, text=True,
                          timeout=300)


def _recorded(tmp_path) -> list[str]:
    """The objects recorded so far, in order, and the list emptied."""
    path = tmp_path / "recorded.txt"
    names = path.read_text().split() if path.exists() else []
    path.write_text("")
    return names


def _files(folder) -> dict:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("kill, code", [
    ("SIGKILL@record:2", -signal.SIGKILL),  # the second object is being recorded
    ("SIGKILL@commit:6", -signal.SIGKILL),  # its files staged, none renamed yet
    ("SIGKILL@commit:8", -signal.SIGKILL),  # two of its five files renamed
    ("SIGKILL@commit:3", -signal.SIGKILL),  # in the first object's save
    ("SIGTERM@record:2", 128 + signal.SIGTERM),
    ("SIGTERM@commit:8", 128 + signal.SIGTERM),  # held back until the save ends
])
def test_a_transfer_killed_in_its_events_stage_resumes_without_loss_or_redoing(
        tmp_path, kill, code):
    write_spec(tmp_path, SPEC)
    events = tmp_path / "out" / "events" / "ideal"
    killed = _transfer(tmp_path, kill)
    assert killed.returncode == code, killed.stderr
    saved = {entry["object"] for entry in read_index(events)} if (
        events / "index.json").is_file() else set()
    kept = {name: digest for name, digest in _files(events).items()
            if name.split("/")[0] in saved}
    where, n = kill.split("@")[1].split(":")
    at_object = int(n) if where == "record" else (int(n) - 1) // FILES_PER_OBJECT + 1
    assert _recorded(tmp_path) == list(OBJECTS[:at_object])

    resumed = _transfer(tmp_path, "none")
    assert resumed.returncode == 0, resumed.stderr
    assert _recorded(tmp_path) == [name for name in OBJECTS if name not in saved]
    after = _files(events)
    assert {name: after.get(name) for name in kept} == kept  # the saved objects untouched
    assert sorted(load_all_memorized_events(events)) == list(OBJECTS)
    leftovers = list((tmp_path / "out").rglob(".*"))
    assert not leftovers, leftovers
    assert "2 already finished" not in resumed.stdout  # no trial had run before the kill
    assert len(list((tmp_path / "out" / "cells" / "ideal-in-faithful" / "trials")
                    .glob("*.json"))) == 2
