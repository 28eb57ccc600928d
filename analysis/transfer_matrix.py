"""Rebuilds the transfer matrix's table (transfer.md) and heat map (transfer_matrix.png)
from the committed records of its cells' sweeps.

    python analysis/transfer_matrix.py SPEC.yaml RESULTS [--format png|pdf|svg]

SPEC.yaml is the transfer spec the results were run with (analysis/transfer_matrix.yaml),
RESULTS the folder `tegrasp transfer` wrote (its cells/ folder holds the records).
"""

import sys

from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS
from tegrasp_drake.transfer.matrix import LoadTransferSpec
from tegrasp_drake.transfer.report import write_transfer_reports


def main(argv=None) -> int:
    parser = script_parser("transfer_matrix", __doc__)
    parser.add_argument("spec", help="the transfer spec (YAML)")
    # the reports are written into it: checked as an output before the records are read
    parser.add_output("results", folder=True, help="the folder `tegrasp transfer` wrote",
                      reads=("results folder", "give the --out folder of `tegrasp transfer`"))
    parser.add_argument("--format", choices=FIGURE_FORMATS, default="png")
    args = parser.parse_args(argv)
    spec = LoadTransferSpec(args.spec)  # a ConfigError: run_script's one line, EXIT_ERROR
    written = write_transfer_reports(spec, args.results, figure_format=args.format)
    if not written:
        raise SystemExit(f"transfer_matrix: error: no finished trial in {args.results}/cells")
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "transfer_matrix"))
