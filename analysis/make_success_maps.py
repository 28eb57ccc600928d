"""Regenerate the per-position success maps (success_maps.png) from a results folder
written by `tegrasp sweep`.

    python analysis/make_success_maps.py RESULTS_DIR [--file NAME.png]
"""

import sys

from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake.figures.sweep import write_success_maps
from tegrasp_drake.sweep import load_records


def main(argv=None) -> int:
    parser = script_parser("make_success_maps", __doc__)
    parser.add_argument("results", help="the --out folder of a sweep")
    parser.add_argument("--file", default="success_maps.png",
                        help="file name inside the results folder")
    args = parser.parse_args(argv)
    loaded = load_records(args.results)
    for path, reason in loaded.corrupt.items():
        print(f"skipped corrupt record {path}: {reason}", file=sys.stderr)
    if not any(record["status"] == "ok" for record in loaded.records.values()):
        print(f"no finished trial records under {args.results}", file=sys.stderr)
        return 1
    print(f"wrote {write_success_maps(loaded.records.values(), args.results, args.file)}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "make_success_maps"))
