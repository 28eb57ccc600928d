"""The command line the scenario benchmarks share: the scenario options (`--scenario`,
`--scenario-name`, `--set`), `--repeats` (runs of each variant, alternating) and `--json`."""

import argparse

from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.commands.scenario_args import add_scenario_arguments


def benchmark_parser(doc: str, repeats_help: str,
                     default_repeats: int = 3) -> argparse.ArgumentParser:
    """A parser described by the first line of `doc`, with the shared options; a benchmark
    adds its own before `parse_benchmark_arguments`."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    add_scenario_arguments(parser)
    parser.add_argument("--repeats", type=integer_option, default=default_repeats,
                        help=repeats_help)
    parser.add_argument("--json", action="store_true",
                        help="print the figures as one JSON object")
    return parser


def parse_benchmark_arguments(parser: argparse.ArgumentParser, argv=None) -> argparse.Namespace:
    """The parsed arguments; a one-line usage error for fewer than one repeat."""
    args = parser.parse_args(argv)
    if args.repeats < 1:
        parser.error(f"--repeats {args.repeats}: give at least 1 run per variant")
    return args
