"""How much a command tells: `-v` logs the run's steps (Python `logging` at INFO), `-vv`
adds DEBUG; `-q/--quiet` keeps to warnings and errors and shows no progress bar. Results
go to stdout; logs and progress bars (commands/progress.py) go to stderr."""

import logging

PACKAGE_LOGGER = "tegrasp_drake"
LOG_FORMAT = "%(levelname)s %(name)s: %(message)s"


def add_verbosity_arguments(parser) -> None:
    group = parser.add_mutually_exclusive_group()
    group.add_argument("-v", "--verbose", action="count", default=0,
                       help="log the run's steps on stderr (-vv: debug details too)")
    group.add_argument("-q", "--quiet", action="store_true",
                       help="no progress bar; only warnings and errors on stderr")


def log_level(verbose: int, quiet: bool) -> int:
    """The package logger's level for -v/-vv/--quiet (default: warnings)."""
    if quiet or verbose <= 0:
        return logging.WARNING
    return logging.INFO if verbose == 1 else logging.DEBUG


def configure_logging(args) -> None:
    """Sends log records to stderr (a root handler, if there is none yet) and sets the
    package's level; other libraries stay at warnings (pydrake keeps its own level)."""
    logging.basicConfig(format=LOG_FORMAT, level=logging.WARNING)
    logging.getLogger(PACKAGE_LOGGER).setLevel(
        log_level(getattr(args, "verbose", 0), getattr(args, "quiet", False)))
