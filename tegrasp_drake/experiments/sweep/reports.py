"""Everything a results folder's records yield: Table I, statistics, the README's results
table, success maps."""

from pathlib import Path

from tegrasp_drake.experiments.sweep.records import load_records
from tegrasp_drake.experiments.sweep.summary import write_summary
from tegrasp_drake.experiments.sweep.table import write_statistics, write_table1


def write_reports(out_dir) -> list[Path]:
    """Writes table1.md/.csv, statistics.md/.json, summary.md and success_maps.png into
    `out_dir`.

    Reads only the records, so it reproduces the reports of any results folder.
    Corrupt records are skipped (the next sweep run re-runs their trials); the success
    map is left out when no trial has finished.
    """
    # Imported here: the figure module reads the sweep's spec and table (this package).
    from tegrasp_drake.experiments.figures.sweep import write_success_maps
    records = list(load_records(out_dir).records.values())
    paths = write_table1(records, out_dir) + write_statistics(records, out_dir)
    paths += write_summary(records, out_dir)
    if any(record["status"] == "ok" for record in records):
        paths.append(write_success_maps(records, out_dir))
    return paths
