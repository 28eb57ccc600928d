"""The argument parser of every command line in the package (`tegrasp`, its subcommands and
the `python -m` docs commands): a command line that does not parse is refused in one line
(docs/user-guide.md, "Exit codes"), never argparse's usage block."""

import argparse

EXIT_USAGE = 2  # a command line that does not parse (argparse's own code)


class UsageParser(argparse.ArgumentParser):
    """argparse's parser, ending a command line that does not parse with one line on stderr,
    `PROG: error: <what> (see PROG --help)`, the user's text quoted safely
    (files.error_line), and EXIT_USAGE."""

    def error(self, message):
        from tegrasp_drake.rig.files import error_line
        self.exit(EXIT_USAGE, f"{self.prog}: error: {error_line(message)} "
                              f"(see {self.prog} --help)\n")
