"""A diagonal cell of the transfer matrix is the ordinary sweep of its world: the events
`tegrasp transfer` records equal `tegrasp record-events` in that world's preset, and the
cell's trial equals `tegrasp sweep` of the same trial with the world's settings."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tegrasp_drake.transfer.matrix import TransferWorld, world_assignments
from tests.cheap_contact import CHEAP_CONTACT, cheap_contact_arguments, cheap_contact_yaml

TESTS = Path(__file__).resolve().parents[1]
REPOSITORY = TESTS.parent
TIMEOUT_S = 900
TIMING = {"cpu_time_s", "real_time_factor", "wall_time_s"}
SWEEP = {"objects": ["box"], "controllers": ["memorized"], "grid": [[0.0, 0.015]],
         "attempts": 1, "base_seed": 600}


def run(*arguments):
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        e for e in (str(REPOSITORY), os.environ.get("PYTHONPATH", "")) if e)}
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake.cli", *map(str, arguments)],
                          env=environment, capture_output=True, text=True,
                          timeout=TIMEOUT_S)
    assert done.returncode == 0, done.stderr
    return done


def only_record(folder: Path) -> dict:
    (record,) = folder.glob("*.json")
    return json.loads(record.read_text())


def without_timing(result: dict) -> dict:
    return {key: value for key, value in result.items() if key not in TIMING}


# The cheap contact in the world, the recording and the sweep alike: the claim is that the
# transfer machinery gives what the ordinary commands give, the same in whichever contact.
@pytest.mark.slow
def test_the_faithful_diagonal_is_the_ordinary_sweep_of_the_faithful_world(tmp_path):
    spec = tmp_path / "transfer.yaml"
    spec.write_text(textwrap.dedent(f"""\
        worlds:
          faithful: {{scenario: faithful_world, overrides: {cheap_contact_yaml()}}}
        cells: [[faithful, faithful]]
        sweep: {json.dumps(SWEEP)}
        """))
    out = tmp_path / "transfer"
    run("transfer", spec, "--out", out, "--workers", "1", "--no-progress")

    events = tmp_path / "events"
    run("record-events", "--scenario-name", "faithful_world", "--events", events, "-q",
        *cheap_contact_arguments())
    for recorded in (out / "events" / "faithful" / "box").glob("*.json"):
        mine = json.loads((events / "box" / recorded.name).read_text())
        theirs = json.loads(recorded.read_text())
        assert mine["samples"] == theirs["samples"], recorded.name
        assert mine["transition_time_s"] == theirs["transition_time_s"], recorded.name

    sweep_spec = tmp_path / "sweep.yaml"
    sweep_spec.write_text(json.dumps(SWEEP))  # JSON is YAML
    assignments = world_assignments(TransferWorld("faithful_world", CHEAP_CONTACT))
    sweep_out = tmp_path / "sweep"
    run("sweep", "--spec", sweep_spec, "--events", events, "--out", sweep_out, "--workers",
        "1", "--no-progress", *[a for assignment in assignments
                                for a in ("--set", assignment)])

    cell = only_record(out / "cells" / "faithful-in-faithful" / "trials")
    ordinary = only_record(sweep_out / "trials")
    assert cell["trial"] == ordinary["trial"]
    assert without_timing(cell["result"]) | {"events_dir": None} == \
        without_timing(ordinary["result"]) | {"events_dir": None}
    assert cell["result"]["transitions"], "the trial made no transition: nothing compared"
