"""Everything a results folder's records yield: Table I, statistics, success maps."""

from pathlib import Path

from tegrasp_drake.experiments.sweep.records import load_records
from tegrasp_drake.experiments.sweep.table import write_statistics, write_table1


def write_reports(out_dir, trial_ids=None) -> list[Path]:
    """Writes table1.md/.csv, statistics.md/.json and success_maps.png into `out_dir`.

    Reads only the records, so it reproduces the reports of any results folder; with
    `trial_ids` (a sweep's own trials), only theirs: records another spec left in the
    folder are not counted.
    Corrupt records are skipped (the next sweep run re-runs their trials); the success
    map is left out when no trial has finished.
    """
    # Imported here: the figure module reads the sweep's spec and table (this package).
    from tegrasp_drake.experiments.figures.sweep import write_success_maps
    records = [record for trial_id, record in load_records(out_dir).records.items()
               if trial_ids is None or trial_id in set(trial_ids)]
    paths = write_table1(records, out_dir) + write_statistics(records, out_dir)
    if any(record["status"] == "ok" for record in records):
        paths.append(write_success_maps(records, out_dir))
    return paths
