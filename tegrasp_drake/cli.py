"""The `tegrasp` command line: one sub-command per module, each with a `register(subparsers)` that
adds its parser and sets `func=run` (args -> exit code). `main` is the one error boundary: an
unforeseen exception ends the run with one line on stderr (traceback to a file; `-v` prints it);
SIGTERM, SIGHUP and the other catchable terminating signals end a run as Ctrl-C does
(rig/files.TERMINATION_SIGNALS); a closed pipe or a full disk on stdout or stderr is told by
commands/output_streams.py. Exit codes: docs/user-guide.md, "Exit codes"."""

import argparse
import errno
import importlib
import signal
import sys

from tegrasp_drake import __version__
from tegrasp_drake.commands import error_boundary, output_streams
from tegrasp_drake.commands.command_line_parser import CommandLineParser
from tegrasp_drake.commands.verbosity import add_verbosity_arguments, configure_logging

# Each entry is a module with a register(subparsers) function. Modules are imported only
# when the command line is built, so a missing optional extra breaks only its own command.
COMMAND_MODULES = (
    "tegrasp_drake.commands.demo",
    "tegrasp_drake.commands.trial",
    "tegrasp_drake.commands.sweep",
    "tegrasp_drake.commands.transfer",
    "tegrasp_drake.commands.sensitivity",
    "tegrasp_drake.commands.record_events",
    "tegrasp_drake.commands.plot",
    "tegrasp_drake.commands.emulate",
    "tegrasp_drake.commands.hardware",
    "tegrasp_drake.commands.replay",
)


# The arguments that name a file or folder, by their `dest` (or (command, dest) where one
# command's differs), with what each takes: an empty one ('' from an unset shell variable)
# is refused saying so, never taken as "not given" or as the current folder.
PATH_ARGUMENTS = {
    "scenario": "a scenario YAML file", "events": "an events folder", "out": "an output folder",
    "html": "an HTML file to write", "spec": "a spec YAML file",
    "logs": "a folder for the trial logs", "trial": "a trial log file (.npz)",
    "write_config": "a file to write the hardware config to",
    "config": "a hardware config YAML file", "log": "an LCM log file",
    "source": "a trial log file or a results folder", ("plot", "out"): "a figure file"}


def refuse_empty_values(parser: argparse.ArgumentParser, args) -> None:
    """Exits with a usage error naming the first argument of `args` given as '' (alone or in a
    repeated option's list): an unset shell variable, never "not given" or the current folder."""
    subparsers = next(a for a in parser._actions
                      if isinstance(a, argparse._SubParsersAction))
    command = subparsers.choices[args.command]
    for action in command._actions:
        value = getattr(args, action.dest, None)
        if action.default == "" or not (value == "" or (isinstance(value, list)
                                                         and "" in value)):
            continue
        name = (action.option_strings[0] if action.option_strings
                else action.metavar or action.dest)
        what = (PATH_ARGUMENTS.get((args.command, action.dest), PATH_ARGUMENTS[action.dest])
                if action.dest in PATH_ARGUMENTS else
                f"a value, or leave {name} out" if action.option_strings else "a value")
        command.error(f"{name} '' is empty; give {what}")


def build_parser() -> argparse.ArgumentParser:
    parser = CommandLineParser(
        prog="tegrasp",
        description="Tactile-event grasping with memorized triggers, on Drake.")
    parser.add_argument("--version", action="version", version=f"tegrasp {__version__}",
                        help="print the package's version and exit")
    subparsers = parser.add_subparsers(dest="command", required=True)
    for module_name in COMMAND_MODULES:
        importlib.import_module(module_name).register(subparsers)
    for subparser in subparsers.choices.values():
        add_verbosity_arguments(subparser)
    return parser


# Exit codes (docs/user-guide.md, "Exit codes"); a command returns the first three itself.
EXIT_SUCCESS = 0
EXIT_ERROR = error_boundary.EXIT_ERROR  # bad input refused, an output or a device unusable
EXIT_GRASP_FAILED = 2  # hardware: a fault or a Failed state machine (also argparse's usage)
EXIT_INTERNAL_ERROR = error_boundary.EXIT_INTERNAL_ERROR  # an exception no command foresaw
EXIT_CLOSED_PIPE = 128 + signal.SIGPIPE  # the shell's status of a command SIGPIPE ended


def main(argv=None) -> int:
    """The command line's exit code; a closed stdout or stderr (`tegrasp ... | head`) ends
    the command quietly with EXIT_CLOSED_PIPE, as SIGPIPE ends a C program; one that cannot
    be written (a full disk, an I/O error) ends it with one line and EXIT_ERROR. `argv`
    None: the process's own command line, run in its environment (process_environment.py)."""
    if argv is None:
        from tegrasp_drake.commands.process_environment import (
            check_matplotlib_backend, private_matplotlib_config, run_in_utf8_mode)
        run_in_utf8_mode()
        private_matplotlib_config()
        check_matplotlib_backend()
    try:
        try:
            code = _main(argv, process_ends=argv is None)
        except SystemExit as exit_:  # argparse's --help or usage error, a command's refusal
            unwritable = output_streams.unwritable_output()
            if unwritable and exit_.code in (0, None):
                return _cannot_write(*unwritable)
            raise
        # what is still buffered goes out now, while a closed pipe or a full disk can be told;
        # a command's own failure keeps its exit code (a refusal said on a closed stderr: 2)
        unwritable = output_streams.unwritable_output()
        if unwritable:
            told = _cannot_write(*unwritable)
            return code or told
        return code
    except BrokenPipeError:  # Python's flush at exit then finds no closed pipe to report
        output_streams.detach_standard_streams()
        return EXIT_CLOSED_PIPE


def _cannot_write(name: str, error: OSError) -> int:
    """One line for an output stream the system refused to write (output_streams.py)."""
    output_streams.tell_cannot_write(name, error)
    return EXIT_ERROR


def _main(argv, process_ends: bool = False) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    with output_streams.guarded_output():
        return _run_command(argv, process_ends)


def _run_command(argv, process_ends: bool = False) -> int:
    """The command's exit code. `process_ends`: the process exits after it (termination
    signals after the first are then ignored until it has: rig/files.termination_interrupts).
    A signal while the command modules are imported (pydrake among them) is acted on once
    they are, a second or two later: pydrake's C++ initialisation catches a KeyboardInterrupt
    raised inside it and prints its own stack instead of passing the interrupt on."""
    from tegrasp_drake.rig.files import (UserPathError, error_line, interrupt_received,
                                         interruptions_deferred, termination_interrupts)
    with termination_interrupts(process_ends):
        try:
            with interruptions_deferred():
                parser = build_parser()
            args = parser.parse_args(argv)
            refuse_empty_values(parser, args)
            configure_logging(args)
            return int(args.func(args) or 0)
        except KeyboardInterrupt as interrupt:
            name = str(interrupt) if str(interrupt).startswith("SIG") else "SIGINT"
            return _interrupted(name)
        except SystemExit as exit_:
            if isinstance(exit_.code, str):  # ERROR_LEAD + what, one bounded line
                raise SystemExit(error_line(exit_.code)) from None
            raise
        except GeneratorExit:
            raise
        except UserPathError as error:  # a file or folder the user named, said in one line
            if interrupt_received():
                return _interrupted(interrupt_received())
            print(f"{error_boundary.ERROR_LEAD}{error_line(str(error))}", file=sys.stderr,
                  flush=True)
            return EXIT_ERROR
        except BrokenPipeError:
            if output_streams.output_closed():  # the reader of our output left: main ends quietly
                raise
            return error_boundary.internal_error(sys.exc_info()[1], argv)
        except output_streams.OutputStreamError as error:  # a print to a full disk
            return _cannot_write(error.stream_name, error)
        except BaseException as error:  # noqa: BLE001: the error boundary
            if interrupt_received():  # a Ctrl-C that Drake wrapped in another exception
                return _interrupted(interrupt_received())
            if isinstance(error, OSError) and error.errno == errno.ENAMETOOLONG:
                # a path the user gave, wherever a command first used it
                print(f"{error_boundary.ERROR_LEAD}{error_boundary.path_too_long_line(error)}",
                      file=sys.stderr, flush=True)
                return EXIT_ERROR
            return error_boundary.internal_error(error, argv)


def _interrupted(name: str) -> int:
    """128 + N for the signal `name`, after the one line that says it stopped the run."""
    print(f"tegrasp: interrupted ({name}); the run's unfinished files were removed",
          file=sys.stderr, flush=True)
    # CPython marks a KeyboardInterrupt that leaves code exec() ran from a string (scipy
    # imports numpy so) as never caught, and then ends a `python -m` process by SIGINT in
    # place of its exit code (-2 for a SIGTERM's 143). Each exec of a string clears the mark.
    exec("")  # noqa: S102: a constant, empty program
    return 128 + signal.Signals[name].value


if __name__ == "__main__":
    sys.exit(main())
