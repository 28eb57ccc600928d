"""Success per placement offset: Table I split by marker, on the committed seed-0 sweep."""

import pathlib
from collections import Counter

import pytest

from tegrasp_drake.sweep import load_records, table1_rows
from tegrasp_drake.sweep.offset_table import (offset_markdown, offset_rows, write_offset_table)

RESULTS = pathlib.Path(__file__).resolve().parents[2] / "analysis" / "results_seed0"


@pytest.fixture(scope="module")
def records():
    return list(load_records(RESULTS).records.values())


def test_markers_add_up_to_table1(records):
    rows = offset_rows(records)
    hold, unload, trials = Counter(), Counter(), Counter()
    for row in rows:
        placement = "well" if (row.marker_dx_mm, row.marker_dy_mm) == (0.0, 0.0) else "mis"
        key = (row.controller, row.object_name, placement)
        hold[key] += row.hold_successes
        unload[key] += row.unload_successes
        trials[key] += row.trials
    for row in table1_rows(records):
        if row.object_name == "average":
            continue
        for placement, (hold_cell, unload_cell) in (("well", row.cells[:2]),
                                                    ("mis", row.cells[2:])):
            key = (row.controller, row.object_name, placement)
            assert (hold[key], unload[key], trials[key]) == \
                (hold_cell.successes, unload_cell.successes, hold_cell.trials)


def test_each_controller_has_the_nine_markers(records):
    rows = offset_rows(records)
    for controller in {row.controller for row in rows}:
        markers = {(r.marker_dx_mm, r.marker_dy_mm) for r in rows if r.controller == controller}
        assert markers == {(dx, dy) for dx in (-10.0, 0.0, 10.0) for dy in (-15.0, 0.0, 15.0)}


def test_the_memorized_failures_are_where_the_readme_says(records):
    failed = [(r.object_name, r.marker_dx_mm, r.marker_dy_mm) for r in offset_rows(records)
              if r.controller == "memorized" and r.hold_successes < r.trials]
    # In the faithful world no memorized trial failed (docs/results.md, Table I).
    assert failed == []
    assert "| -10 | -15 | 3/3 | 3/3 |" in offset_markdown(offset_rows(records))


def test_written_files(records, tmp_path):
    markdown, table = write_offset_table(records, tmp_path)
    assert markdown.read_text().startswith("# Success per placement offset")
    assert len(table.read_text().splitlines()) == 1 + 3 * 3 * 9
