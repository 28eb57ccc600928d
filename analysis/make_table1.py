"""Regenerate Table I (table1.md, table1.csv), the trial statistics, the results
table (summary.md) and the success per placement offset (success_by_offset.md, .csv) from a
results folder written by `tegrasp sweep`.

    python analysis/make_table1.py RESULTS_DIR
"""

import sys

from tegrasp_drake.commands.script_output import (load_sweep_records, refuse_unusable_folders,
                                                  run_script, script_parser)
from tegrasp_drake.sweep import write_offset_table, write_statistics, write_summary, write_table1


def main(argv=None) -> int:
    parser = script_parser("make_table1", __doc__)
    parser.add_argument("results", help="the --out folder of a sweep")
    args = parser.parse_args(argv)
    loaded = load_sweep_records("make_table1", args.results)  # an input first, then
    refuse_unusable_folders("make_table1", args.results)  # where it writes the tables
    if not loaded.records:
        raise SystemExit(f"make_table1: error: no trial records under {args.results}; give "
                         "the --out folder of `tegrasp sweep`")
    records = list(loaded.records.values())
    for path in (write_table1(records, args.results) + write_statistics(records, args.results)
                 + write_summary(records, args.results)
                 + write_offset_table(records, args.results)):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "make_table1"))
