"""The transfer matrix's reports (transfer/report.py): a cell with trials still to run is
marked as such in the table and on the heat map; a cell with none is named."""

import shutil
import textwrap

import pytest
from tests.fake_trials import fake_trial_with_events
from tests.transfer.test_matrix import TWO_WORLDS

from tegrasp_drake.transfer.matrix import LoadTransferSpec, cell_folder, run_transfer
from tegrasp_drake.transfer.report import (cell_rows, heatmap_label, not_run_note,
                                           transfer_markdown, write_transfer_reports)
from tegrasp_drake.rig import paths

SPEC = TWO_WORLDS.replace("cells: [[ideal, faithful]]",
                          "cells: [[ideal, faithful], [faithful, faithful]]")


@pytest.fixture(scope="module")
def finished_transfer(tmp_path_factory):
    """Both cells run by the fake trial function (2 trials each): (spec, its out folder)."""
    folder = tmp_path_factory.mktemp("transfer")
    (folder / "transfer.yaml").write_text(textwrap.dedent(SPEC))
    spec = LoadTransferSpec(folder / "transfer.yaml")
    out = folder / "out"
    for world in ("ideal", "faithful"):  # events there already: nothing is recorded
        shutil.copytree(paths.package_events_dir(), out / "events" / world,
                        ignore=shutil.ignore_patterns("ensemble", "corrective", "prismatic"))
    run_transfer(spec, fake_trial_with_events, out, workers=1, progress=False)
    return spec, out


@pytest.fixture
def transfer_copy(finished_transfer, tmp_path):
    """A copy of the finished transfer's folder that a test may change: (spec, out)."""
    spec, out = finished_transfer
    return spec, shutil.copytree(out, tmp_path / "out")


def drop_one_record(spec, out, memorizing, running):
    records = sorted((cell_folder(out, memorizing, running) / "trials").glob("*.json"))
    records[0].unlink()


def test_a_cell_with_trials_still_to_run_is_marked_in_the_table(transfer_copy):
    spec, out = transfer_copy
    drop_one_record(spec, out, "ideal", "faithful")
    rows = {(row.memorizing, row.running): row for row in cell_rows(spec, out)}
    partial, whole = rows["ideal", "faithful"], rows["faithful", "faithful"]
    assert (partial.trials, partial.planned, partial.partly_run) == (1, 2, True)
    assert (whole.trials, whole.planned, whole.partly_run) == (2, 2, False)
    table = transfer_markdown(list(rows.values()))
    assert "| ideal | faithful | memorized | 1/2 run |" in table
    assert "| faithful | faithful | memorized | 2 |" in table


def test_a_partly_run_cell_carries_its_count_on_the_heat_map(transfer_copy):
    spec, out = transfer_copy
    drop_one_record(spec, out, "ideal", "faithful")
    rows = {(row.memorizing, row.running): row for row in cell_rows(spec, out)}
    assert heatmap_label(rows["ideal", "faithful"], 1.0) == "100\n1/2 run"
    assert heatmap_label(rows["faithful", "faithful"], 0.5) == "50"


def test_a_cell_with_no_finished_trial_is_named_as_not_run(transfer_copy):
    spec, out = transfer_copy
    for _ in range(2):
        drop_one_record(spec, out, "ideal", "faithful")
    rows = cell_rows(spec, out)
    assert [(row.memorizing, row.running) for row in rows] == [("faithful", "faithful")]
    assert "Not run yet (no finished trial): ideal-in-faithful." in not_run_note(spec, rows)
    written = write_transfer_reports(spec, out)
    assert "ideal-in-faithful." in (out / "transfer.md").read_text()
    assert len(written) == 2


def test_a_finished_matrix_has_no_not_run_note(transfer_copy):
    spec, out = transfer_copy
    assert not_run_note(spec, cell_rows(spec, out)) == ""
