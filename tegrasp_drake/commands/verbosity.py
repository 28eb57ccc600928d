"""How much a command tells: `-v` logs the run's steps (Python `logging` at INFO), `-vv`
adds DEBUG; `-q/--quiet` keeps to warnings and errors and shows no progress bar. Results
go to stdout; logs and progress bars (commands/progress.py) go to stderr."""

import logging
import sys

PACKAGE_LOGGER = "tegrasp_drake"
DRAKE_LOGGER = "drake"  # where pydrake sends Drake's log
LOG_FORMAT = "%(levelname)s %(name)s: %(message)s"


class CommandLogFormatter(logging.Formatter):
    """LOG_FORMAT, except that the package's warnings read as its other warnings do, one
    line `tegrasp: warning: ...` (files.error_line: a name holding a control character is
    shown escaped): what the user is told, not a log record."""

    def __init__(self):
        super().__init__(LOG_FORMAT)

    def format(self, record):
        ours = record.name == PACKAGE_LOGGER or record.name.startswith(PACKAGE_LOGGER + ".")
        if ours and record.levelno == logging.WARNING and not record.exc_info:
            from tegrasp_drake.rig.files import error_line  # a file's name, escaped and cut
            return f"tegrasp: warning: {error_line(record.getMessage())}"
        return super().format(record)


class StderrLogHandler(logging.StreamHandler):
    """Log records on the current stderr (the guarded one while a command runs,
    commands/output_streams.py). A record that stderr refuses (a full disk, an I/O error, a
    closed pipe) is dropped: stderr is itself the broken stream, the one place a line about
    it could go. The failure is remembered, and the error boundary ends the command with the
    full-disk line and EXIT_ERROR (or quietly, for a closed pipe) when it returns; Python's
    own handleError would write a traceback to that same stream ("--- Logging error ---")."""

    def __init__(self):
        logging.Handler.__init__(self)  # no stream of its own: `stream` is stderr's

    @property
    def stream(self):
        return sys.stderr

    def handleError(self, record):
        error = sys.exc_info()[1]
        if not isinstance(error, OSError):  # not the stream's doing: a record that cannot
            super().handleError(record)     # be formatted, which Python reports
            return
        from tegrasp_drake.commands.output_streams import (STANDARD_ERROR, OutputStreamError,
                                                           note_failed_write)
        if not isinstance(error, (OutputStreamError, BrokenPipeError)):  # stderr not guarded
            note_failed_write(OutputStreamError(STANDARD_ERROR, error))


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
    """Sends log records to stderr (a StderrLogHandler on the root logger, if it has no
    handler yet) and sets the package's level; other libraries stay at warnings, Drake's
    (pydrake hands its log to the Python logger "drake", at INFO) too unless -v: its INFO
    lines (Meshcat's port) are not warnings."""
    root = logging.getLogger()
    if not root.handlers:
        handler = StderrLogHandler()
        handler.setFormatter(CommandLogFormatter())
        root.addHandler(handler)
        root.setLevel(logging.WARNING)
    level = log_level(getattr(args, "verbose", 0), getattr(args, "quiet", False))
    logging.getLogger(PACKAGE_LOGGER).setLevel(level)
    logging.getLogger(DRAKE_LOGGER).setLevel(max(level, logging.INFO))
