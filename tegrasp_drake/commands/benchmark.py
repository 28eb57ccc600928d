"""`tegrasp benchmark`: real-time factor of a full trial and the cost of the sensor systems
(experiments/benchmarks/trial.py)."""

import argparse
import json

import numpy as np

from tegrasp_drake.commands.scenario_args import add_scenario_arguments, scenario_from_arguments


EPILOG = """\
examples:
  tegrasp benchmark                    # 3 ideal-grasp trials of the default scenario
  tegrasp benchmark --trials 5 --set tactile.sample_rate_hz=1000 --json

It times its runs, so it shows no progress bar (the runs are the measurement)."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "benchmark", help="print the real-time factor of an ideal-grasp trial and the cost of "
        "one tactile-pad evaluation (medians)", epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_scenario_arguments(parser)
    parser.add_argument("--trials", type=int, default=3, help="full trials to time")
    parser.add_argument("--json", action="store_true")
    parser.set_defaults(func=run)


def run(args) -> int:
    scenario = scenario_from_arguments(args)
    from tegrasp_drake.experiments.benchmarks.trial import run_trial_benchmark
    result = run_trial_benchmark(scenario, args.trials)
    if args.json:
        print(json.dumps(result))
    else:
        for key, value in result.items():
            print(f"{key}: {np.round(value, 3) if isinstance(value, float) else value}")
    return 0
