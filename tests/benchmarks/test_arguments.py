"""The scenario benchmarks' shared command line (benchmarks/arguments.py)."""

import pytest

from benchmarks.arguments import benchmark_parser, parse_benchmark_arguments
from tegrasp_drake.commands.scenario_args import scenario_from_arguments


def test_repeats_json_and_scenario_options_parse_into_a_scenario():
    parser = benchmark_parser("A benchmark.\nMore.", "runs of each variant")
    args = parse_benchmark_arguments(parser, ["--repeats", "2", "--json",
                                              "--set", "random_seed=600"])
    assert (args.repeats, args.json) == (2, True)
    assert scenario_from_arguments(args).random_seed == 600
    assert parser.description == "A benchmark."


def test_fewer_than_one_repeat_is_a_one_line_usage_error(capsys):
    parser = benchmark_parser("A benchmark.", "runs of each variant")
    with pytest.raises(SystemExit) as exit_:
        parse_benchmark_arguments(parser, ["--repeats", "0"])
    assert exit_.value.code == 2
    assert capsys.readouterr().err.strip().splitlines()[-1].endswith(
        "--repeats 0: give at least 1 run per variant")
