"""The `tegrasp` command line: one sub-command per module, each with a `register` function.

A command module defines `register(subparsers)`, which adds its parser and sets
`func=run` (a function taking the parsed arguments and returning an exit code). Every
sub-command also takes -v/-vv/--quiet (commands/verbosity.py).
"""

import argparse
import importlib
import sys

from tegrasp_drake.commands.verbosity import add_verbosity_arguments, configure_logging

# Each entry is a module with a register(subparsers) function. Modules are imported only
# when the command line is built, so a missing optional extra breaks only its own command.
COMMAND_MODULES = (
    "tegrasp_drake.commands.demo",
    "tegrasp_drake.commands.trial",
    "tegrasp_drake.commands.sweep",
    "tegrasp_drake.commands.transfer",
    "tegrasp_drake.commands.record_events",
    "tegrasp_drake.commands.plot",
    "tegrasp_drake.commands.emulate",
    "tegrasp_drake.commands.hardware",
    "tegrasp_drake.commands.replay",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="tegrasp",
        description="Tactile-event grasping with memorized triggers, on Drake.")
    subparsers = parser.add_subparsers(dest="command", required=True)
    for module_name in COMMAND_MODULES:
        importlib.import_module(module_name).register(subparsers)
    for subparser in subparsers.choices.values():
        add_verbosity_arguments(subparser)
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    configure_logging(args)
    return int(args.func(args) or 0)


if __name__ == "__main__":
    sys.exit(main())
