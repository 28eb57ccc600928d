"""Detection quality per trigger and controller, and paired McNemar comparisons, from one or
more sweep results folders (sweep/detection_report.py).

    python analysis/detection_quality.py OUT.md RESULTS [RESULTS ...]
        [--reference open_loop] [--title TEXT]

The folders' records are merged (the same base seed and grid give the same pair ids, so a
folder of one controller pairs with another folder's controllers).
"""

import pathlib
import sys

from tegrasp_drake.commands.script_output import (SWEEP_RESULTS_ADVICE, load_sweep_records,
                                                  run_script, script_parser, write_report)
from tegrasp_drake.sweep.detection_report import report_markdown
from tegrasp_drake.sweep.spec import CONTROLLER_NAMES


def main(argv=None) -> int:
    parser = script_parser("detection_quality", __doc__)
    parser.add_output("out", type=pathlib.Path, help="the Markdown report to write (an "
                      "existing file only if it is one, of this --title)",
                      title=lambda args: f"# {args.title}")
    parser.add_input("results", type=pathlib.Path, nargs="+", what="results folder",
                     advice=SWEEP_RESULTS_ADVICE,
                     help="`tegrasp sweep` results folders (their records, trials/*.json)")
    parser.add_argument("--reference", choices=CONTROLLER_NAMES,
                        help="the controller the others are paired against (default: open_loop "
                             "when the results hold it; else no paired table)")
    parser.add_argument("--title", default="Detection quality and paired comparison",
                        help="the report's heading")
    args = parser.parse_args(argv)
    records = {}
    for folder in args.results:
        loaded = load_sweep_records("detection_quality", folder)
        if not loaded.records:
            raise SystemExit(f"detection_quality: {folder} holds no trial records; "
                             f"{SWEEP_RESULTS_ADVICE}")
        records.update(loaded.records)
    controllers = [c for c in CONTROLLER_NAMES
                   if any(r["trial"]["controller"] == c for r in records.values())]
    if args.reference is None:
        args.reference = "open_loop" if "open_loop" in controllers else None
    elif args.reference not in controllers:
        raise SystemExit(f"detection_quality: --reference {args.reference}: the results hold no "
                         f"trial of that controller (they hold {', '.join(controllers)}); give "
                         f"one of those, or add a folder swept with it")
    text = report_markdown(records, controllers, args.reference, args.title)
    write_report(args.out, text, script="detection_quality")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "detection_quality"))
