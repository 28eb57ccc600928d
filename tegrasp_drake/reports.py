"""Everything a results folder's records yield: Table I, statistics, the results table
(summary.md), success per offset, and the figures (success maps, Table I against the paper,
detection latencies)."""

from pathlib import Path
from collections.abc import Sequence
from typing import Annotated

from tegrasp_drake.sweep.offset_table import offset_table_starts, write_offset_table
from tegrasp_drake.sweep.records import load_records, results_parsed_once
from tegrasp_drake.sweep.summary import SUMMARY_FILE, SUMMARY_START, write_summary
from tegrasp_drake.sweep.table import (statistics_starts, table1_starts, write_statistics,
                                       write_table1)
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS
from tegrasp_drake.rig.api_boundary import UPDATED_FOLDER, PathLike, public_api
from tegrasp_drake.rig.ranges import Choice
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.files import UserPathError
from tegrasp_drake.rig.report_files import foreign_report_problem

# The figures' file stems: success maps, Table I against the paper, detection latencies.
FIGURE_STEMS = ("success_maps", "table1_vs_paper", "latency")


def report_starts() -> dict[str, str]:
    """The text reports write_reports writes, by file name, and how each starts
    (rig.report_files: an existing file under one of these names is replaced only when it
    starts so)."""
    return {**table1_starts(), **statistics_starts(), SUMMARY_FILE: SUMMARY_START,
            **offset_table_starts()}


@public_api
def write_reports(out_dir: Annotated[PathLike, UPDATED_FOLDER],
                  trial_ids: Sequence[str] | None = None, *,
                  figure_format: Annotated[str, Choice(FIGURE_FORMATS)] = "png") -> list[Path]:
    """Writes Table I, the statistics, the summary, success by offset and the figures
    (`figure_format`) into `out_dir`, from the records only (with `trial_ids`, those trials');
    corrupt records are skipped, figures need a finished trial; ValueError (nothing written)
    for a folder with no readable record; UserPathError (nothing written) when a file there
    under a report's name is not that report (rig.report_files), the user's own."""
    # Imported here: matplotlib loads only when a report is written.
    from tegrasp_drake.figures.figure_files import figure_path
    from tegrasp_drake.figures.latency import latency_samples, plot_latency_distributions
    from tegrasp_drake.figures.sweep import write_success_maps
    from tegrasp_drake.figures.table1 import plot_table1
    own = None if trial_ids is None else set(trial_ids)
    loaded = load_records(out_dir)
    recorded = loaded.records
    if not recorded:  # not a Table I of zero trials (as `tegrasp plot table1` refuses it)
        corrupt = (f" ({len(loaded.corrupt)} corrupt, first {next(iter(loaded.corrupt))}: "
                   f"{next(iter(loaded.corrupt.values()))})" if loaded.corrupt else "")
        raise ValueError(f"write_reports: argument 'out_dir': {shorten(str(out_dir))} holds no "
                         f"trial record under trials/{corrupt}; give the results folder of a "
                         "sweep (run_sweep, `tegrasp sweep --out FOLDER`)")
    records = [record for trial_id, record in recorded.items()
               if own is None or trial_id in own]
    if own is not None and not records:  # not reports of zero trials over the folder's own
        raise ValueError(f"write_reports: argument 'trial_ids' names no trial recorded in "
                         f"{shorten(str(out_dir))} (got {shorten(repr(sorted(own)))}; it has "
                         f"{len(recorded)} records); give their ids, or None for all")
    problem = foreign_report_problem(out_dir, report_starts(), "sweep")
    if problem:
        raise UserPathError(problem)
    with results_parsed_once():  # every table and figure reads each record's result
        paths = (write_table1(records, out_dir) + write_statistics(records, out_dir)
                 + write_summary(records, out_dir) + write_offset_table(records, out_dir))
        if any(record["status"] == "ok" for record in records):
            paths.append(write_success_maps(records, out_dir,
                                            figure_path(".", FIGURE_STEMS[0], figure_format).name))
            paths.append(Path(plot_table1(records, figure_path(out_dir, FIGURE_STEMS[1],
                                                               figure_format))))
        if latency_samples(records):
            paths.append(Path(plot_latency_distributions(
                records, figure_path(out_dir, FIGURE_STEMS[2], figure_format))))
    return paths
