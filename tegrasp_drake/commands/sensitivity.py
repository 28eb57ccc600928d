"""`tegrasp sensitivity SPEC.yaml`: the guessed parameters (docs/model.md, "What was
guessed") each moved to either end of its range, or sampled together as a Latin hypercube;
each point the spec's sweep (sensitivity/study.py, sensitivity/report.py). Writes
DIR/points.json, DIR/events, DIR/cells, DIR/sensitivity.md and the tornado chart; the same
command resumes. Exit codes as `tegrasp sweep`'s."""

import argparse
import contextlib

from tegrasp_drake.commands.progress import progress_wanted
from tegrasp_drake.commands.sweep import (DEFAULT_TRIAL_FUNCTION, add_runner_arguments,
                                          OptionError, check_report_files, check_runner_arguments,
                                          output_folder_held, refusals_said, resolve_trial_function,
                                          scheduler_connection)
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.sweep.runner import summary_text

DEFAULT_OUT = "results/sensitivity"

EPILOG = """\
examples:
  tegrasp sensitivity analysis/sensitivity.yaml --out results/sensitivity
  tegrasp sensitivity analysis/sensitivity.yaml --latin-hypercube 32 --out results/lhs
  tegrasp sensitivity my_sensitivity.yaml --scheduler tcp://10.0.0.5:8786 --out out/sens

A spec names the parameters (keys of the uncertain parameters' table; all when left out),
where each point's events are memorized (events: each_point or default_point) and the sweep
of each point (docs/sweeps.md). Re-running the command into the same --out resumes it."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("spec", metavar="SPEC.yaml", help="the sensitivity spec")
    parser.add_argument("--latin-hypercube", type=integer_option, metavar="N",
                        help="N points sampled over all the spec's parameters together "
                             "(and the defaults), instead of each parameter's two ends")
    add_runner_arguments(parser, default_out=DEFAULT_OUT)
    parser.add_argument("--trial-function", default=DEFAULT_TRIAL_FUNCTION,
                        help=argparse.SUPPRESS)  # Testing hook, as `tegrasp sweep`'s.


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "sensitivity", help="the guessed parameters at the ends of their ranges (a sweep at "
        "each point; tornado chart)", description=__doc__.split("\n\n")[0], epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_arguments(parser)
    parser.set_defaults(func=run)


def run(args) -> int:
    with contextlib.ExitStack() as held:  # --out, from the first read to the last report
        return _run(args, held)


def _run(args, held: contextlib.ExitStack) -> int:
    from tegrasp_drake.sensitivity.report import (FIGURE_STEM, REPORT_FILE, REPORT_START,
                                                  write_sensitivity_report)
    from tegrasp_drake.sensitivity.study import (LoadSensitivitySpec, latin_hypercube,
                                                 one_at_a_time, run_sensitivity)
    with refusals_said() as refused:
        check_runner_arguments(args, "sensitivity")
        check_report_files(args, "sensitivity", {REPORT_FILE: REPORT_START}, (FIGURE_STEM,))
        with scheduler_connection(args, "sensitivity") as scheduler:
            spec = LoadSensitivitySpec(args.spec)
            if args.latin_hypercube is None:
                points = one_at_a_time(spec)
            else:
                try:
                    points = latin_hypercube(spec, args.latin_hypercube)
                except ConfigError as error:  # its count
                    raise OptionError(str(error)) from None
            trial_function = resolve_trial_function(args.trial_function)
            held.enter_context(output_folder_held(args, "sensitivity"))
            summaries = run_sensitivity(spec, points, trial_function, args.out,
                                        workers=args.workers, scheduler=scheduler,
                                        progress=not args.no_progress and progress_wanted(args),
                                        confirmed_trials=args.confirm_trials)
    if refused.exit_code is not None:
        return refused.exit_code
    for name, summary in summaries.items():
        print(f"{name}: {summary_text(summary)}")
    for path in write_sensitivity_report(spec, points, args.out, figure_format=args.format):
        print(f"wrote {path}")
    return 1 if any(s.errors or s.unfinished for s in summaries.values()) else 0
