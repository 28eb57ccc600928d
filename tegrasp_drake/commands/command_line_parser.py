"""The command line's argument parser: one for `tegrasp` and each of its subcommands, so that
each refuses a command line that does not parse alike, in one line (docs/user-guide.md, "Exit
codes")."""

import argparse

from tegrasp_drake.rig.usage_parser import UsageParser


class CommandLineParser(UsageParser):
    """The `tegrasp` command's parser (and, by add_subparsers, each subcommand's): a command
    line that does not parse ends in one line, `tegrasp: error: <what> (see tegrasp sweep
    --help)` (rig/usage_parser.py), led as every error of the command is
    (error_boundary.ERROR_LEAD)."""

    def error_lead(self) -> str:
        from tegrasp_drake.commands.error_boundary import ERROR_LEAD
        return ERROR_LEAD

    def parse_args(self, args=None, namespace=None):
        """argparse's parse_args, an argument no parser knows refused by the subcommand's
        parser (`tegrasp: error: unrecognized arguments: ... (see tegrasp record-events
        --help)`), not the top's."""
        parsed, extras = self.parse_known_args(args, namespace)
        if extras:
            subparsers = [a for a in self._actions
                          if isinstance(a, argparse._SubParsersAction)]
            command = (subparsers[0].choices.get(getattr(parsed, subparsers[0].dest, None))
                       if subparsers else None)
            (command or self).error(f"unrecognized arguments: {' '.join(extras)}")
        return parsed

    def parse_known_args(self, args=None, namespace=None):
        """A command with an optional positional (`plot signals -v LOG`) takes it after its
        options too: argparse alone fills an optional positional with its default when an
        option comes first, and then refuses the positional as an unrecognized argument."""
        optional_positional = any(not action.option_strings and action.nargs in ("?", "*")
                                  for action in self._actions)
        if not optional_positional or getattr(self, "_intermixing", False):
            return super().parse_known_args(args, namespace)
        self._intermixing = True  # parse_known_intermixed_args calls parse_known_args
        try:
            return self.parse_known_intermixed_args(args, namespace)
        finally:
            self._intermixing = False
