"""`tegrasp transfer SPEC.yaml`: events memorized in one world, trials run in another
(transfer/matrix.py, transfer/report.py): writes DIR/events, DIR/cells, DIR/transfer.md and
the heat map; the same command resumes. Exit codes as `tegrasp sweep`'s."""

import argparse
import contextlib

from tegrasp_drake.commands.progress import progress_wanted
from tegrasp_drake.commands.sweep import (DEFAULT_TRIAL_FUNCTION, add_runner_arguments,
                                          check_report_files, check_runner_arguments,
                                          output_folder_held, refusals_said, resolve_trial_function,
                                          scheduler_connection)
from tegrasp_drake.sweep.runner import summary_text

DEFAULT_OUT = "results/transfer"

EPILOG = """\
examples:
  tegrasp transfer analysis/transfer_matrix.yaml --out results/transfer
  tegrasp transfer my_transfer.yaml --workers 2 --out out/transfer
  tegrasp transfer analysis/transfer_matrix.yaml --scheduler tcp://10.0.0.5:8786

A spec names the worlds (a scenario preset such as memorizing_world or faithful_world, plus
--set overrides), the cells [memorizing world, running world] and the sweep every cell runs
(docs/transfer.md). Re-running the command into the same --out resumes it."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("spec", metavar="SPEC.yaml", help="the transfer spec")
    add_runner_arguments(parser, default_out=DEFAULT_OUT)
    parser.add_argument("--trial-function", default=DEFAULT_TRIAL_FUNCTION,
                        help=argparse.SUPPRESS)  # Testing hook, see the module docstring.


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "transfer", help="events memorized in one world, trials run in another (a matrix "
        "of sweeps)", description=__doc__.split("\n\n")[0], epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_arguments(parser)
    parser.set_defaults(func=run)


def run(args) -> int:
    with contextlib.ExitStack() as held:  # --out, from the first read to the last report
        return _run(args, held)


def _run(args, held: contextlib.ExitStack) -> int:
    from tegrasp_drake.transfer.matrix import LoadTransferSpec, run_transfer
    from tegrasp_drake.transfer.report import (FIGURE_STEM, TABLE_FILE, TABLE_START,
                                               write_transfer_reports)
    with refusals_said() as refused:
        check_runner_arguments(args, "transfer")
        check_report_files(args, "transfer", {TABLE_FILE: TABLE_START}, (FIGURE_STEM,))
        with scheduler_connection(args, "transfer") as scheduler:
            spec = LoadTransferSpec(args.spec, confirmed_trials=args.confirm_trials)
            trial_function = resolve_trial_function(args.trial_function)
            held.enter_context(output_folder_held(args, "transfer"))
            summaries = run_transfer(spec, trial_function, args.out, workers=args.workers,
                                     scheduler=scheduler,
                                     progress=not args.no_progress and progress_wanted(args),
                                     confirmed_trials=args.confirm_trials)
    if refused.exit_code is not None:
        return refused.exit_code
    for name, summary in summaries.items():
        print(f"{name}: {summary_text(summary)}")
    for path in write_transfer_reports(spec, args.out, figure_format=args.format):
        print(f"wrote {path}")
    return 1 if any(s.errors or s.unfinished for s in summaries.values()) else 0

