"""Regenerate the per-position success maps (success_maps.png) from a results folder
written by `tegrasp sweep`.

    python analysis/make_success_maps.py RESULTS_DIR [--file FIGURE.png [--overwrite]]

The figure goes to RESULTS_DIR/success_maps.png (the sweep's own, replaced), or to --file
(.png, .pdf or .svg), a path from the current folder like every other path on a command
line, which replaces an existing figure only with --overwrite, as `tegrasp plot`.
"""

import pathlib
import sys

from tegrasp_drake.commands.script_output import (SWEEP_RESULTS_ADVICE, load_sweep_records,
                                                  refuse_unusable_output,
                                                  run_script, script_parser)
from tegrasp_drake.figures.sweep import write_success_maps


def main(argv=None) -> int:
    parser = script_parser("make_success_maps", __doc__)
    parser.add_input("results", what="results folder", advice=SWEEP_RESULTS_ADVICE,
                     help="the --out folder of a sweep")
    parser.add_output("--file", type=pathlib.Path, default=None, figure=True,
                      help="the figure to write (.png, .pdf or .svg; default "
                           "RESULTS/success_maps.png)")
    args = parser.parse_args(argv)  # the input first, then --file (add_output)
    out = args.file or pathlib.Path(args.results) / "success_maps.png"
    if args.file is None:  # the sweep folder's own figure, which each run replaces
        refuse_unusable_output("make_success_maps", out, figure=True, overwrite=True)
    loaded = load_sweep_records("make_success_maps", args.results)
    if not any(record["status"] == "ok" for record in loaded.records.values()):
        raise SystemExit(f"make_success_maps: error: no finished trial records under "
                         f"{args.results}; give the --out folder of `tegrasp sweep`")
    print(f"wrote {write_success_maps(loaded.records.values(), out.parent, out.name)}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "make_success_maps"))
