"""The one line an exception no code foresaw ends a program with (the `tegrasp` command line,
cli.py, and the analysis scripts, script_output.run_script): its type and first line, the
file its traceback was written to, exit code EXIT_INTERNAL_ERROR."""

import datetime
import os
import sys
import tempfile
import traceback

from tegrasp_drake.rig import usage_parser

EXIT_ERROR = 1  # bad input refused, a file not writable, a device that did not come up
EXIT_USAGE = usage_parser.EXIT_USAGE  # a command line that does not parse
EXIT_INTERNAL_ERROR = 70  # an exception no command foresaw (sysexits.h EX_SOFTWARE)

# How every error line of `tegrasp` and its subcommands starts, whoever refuses (argparse's
# usage errors, a command's checks, the boundary): one documented form (docs/user-guide.md,
# "Exit codes"). A usage error names its subcommand in its pointer, `(see tegrasp sweep --help)`.
ERROR_LEAD = "tegrasp: error: "


def path_too_long_line(error: OSError) -> str:
    """The one line for a path the file system refused as too long (ENAMETOOLONG): only a
    path the user gave, or one made from it, can be; names it (cut to about 80 characters)."""
    from tegrasp_drake.rig.echo import shorten
    path = error.filename if error.filename is not None else error.filename2
    what = "a path" if path is None else f"the path '{shorten(os.fsdecode(path))}'"
    return (f"{what} is too long for the file system (each name at most "
            f"{_path_limit('PC_NAME_MAX', 255)} bytes, the whole at most "
            f"{_path_limit('PC_PATH_MAX', 4096)}): give a shorter one")


def _path_limit(name: str, usual: int) -> int:
    """The root file system's limit `name` (os.pathconf), else `usual`: Linux's NAME_MAX 255
    and PATH_MAX 4096 (limits.h)."""
    try:
        return os.pathconf("/", name)
    except (OSError, ValueError):
        return usual


def internal_error(error: BaseException, argv, program: str = "tegrasp") -> int:
    """One line on stderr for an exception no command foresaw, `program` first; its traceback
    in a file (printed too when `argv` asks for -v)."""
    text = "".join(traceback.format_exception(error))
    where = write_traceback(text, argv, program)
    verbose = any(a in ("-v", "-vv", "--verbose") for a in argv)
    if verbose:
        print(text, file=sys.stderr, end="")
    from tegrasp_drake.rig.files import one_line
    summary = one_line(str(error).strip().splitlines()[0]) if str(error).strip() else ""
    print(f"{program}: internal error: {type(error).__name__}"
          + (f": {summary[:300]}" if summary else "")
          + (f"; traceback in {where}" if where else "; the traceback could not be written")
          + ("" if verbose else " (-v shows it)")
          + "; please report it", file=sys.stderr, flush=True)
    return EXIT_INTERNAL_ERROR


def write_traceback(text: str, argv, program: str = "tegrasp") -> str | None:
    """Writes the command line and `text` to a new file in the temporary folder; its path."""
    stamp = datetime.datetime.now().strftime("%Y%m%d-%H%M%S")
    try:
        descriptor, path = tempfile.mkstemp(prefix=f"{program}-{stamp}-", suffix=".traceback")
        with os.fdopen(descriptor, "w", encoding="utf-8", errors="replace") as stream:
            stream.write(" ".join([program, *argv]) + "\n\n" + text)
    except OSError:
        return None
    return path
