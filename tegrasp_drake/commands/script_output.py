"""The analysis scripts' (analysis/*.py) reports, written whole (a report that cannot be
written ends the script with one line naming it), and their one error boundary, run_script."""

import argparse
import os
import pathlib
import signal
import sys

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.commands.error_boundary import EXIT_ERROR, EXIT_USAGE, internal_error
from tegrasp_drake.figures.figure_files import (FigureFormatError, check_figure_path,
                                                figure_replace_problem)
from tegrasp_drake.rig.files import (MARKDOWN_START, MARKDOWN_TABLE_START, UserPathError,
                                     error_line, folder_problem, output_file_problem,
                                     write_atomically)
from tegrasp_drake.rig.report_files import report_replace_problem
from tegrasp_drake.rig.usage_parser import UsageParser
from tegrasp_drake.rig.echo import shown


def write_report(path, text: str, *, script: str, start: bytes = MARKDOWN_START
                 ) -> pathlib.Path:
    """Writes `text` to `path` whole (rig.files.write_atomically: an earlier report stays as it
    was when it cannot) and returns `path`; SystemExit with one line, `<script>: cannot write
    <path>: <why>; <what to do>`, when it cannot. `start` is how a report of `path`'s kind
    starts (MARKDOWN_START; MARKDOWN_TABLE_START for a bare table). An existing file is
    replaced only when its first line is `text`'s (report_replace_problem): the user's notes
    or another script's report at `path` are never lost."""
    kind = "table" if start == MARKDOWN_TABLE_START else "report"
    problem = report_replace_problem(path, text.split("\n", 1)[0] + "\n", kind)
    if problem:
        raise SystemExit(f"{script}: error: {path} {problem}")
    try:
        return write_atomically(path, text, start=start)
    except UserPathError as error:
        raise SystemExit(f"{script}: {error}") from None


# An analysis script's exit codes are the `tegrasp` command line's (docs/user-guide.md,
# "Exit codes"): EXIT_USAGE for a command line that does not parse, EXIT_ERROR for input
# refused (a path, a file's content, a figure name) or nothing to do on it,
# EXIT_INTERNAL_ERROR for an exception no check foresaw.


class _ScriptParser(UsageParser):
    """The package's parser (UsageParser: a text value holding a control character refused)
    for a script, ending a command line that does not parse with one line, `<script>: error:
    <what>; <script>.py --help shows the usage`, and EXIT_USAGE (argparse's own error prints
    the usage first, several lines)."""

    def __init__(self, script: str, **keywords):
        super().__init__(prog=f"{script}.py", **keywords)
        self._script = script
        self._outputs = []  # (destination, kind) of each add_output argument
        self._inputs = []  # (destination, what, advice, folder) of each add_input argument
        self._ranges = []  # (destination, option, allowed) of each add_number argument
        self._workers_default = None  # add_workers's default, once it is added

    def add_output(self, *names, figure: bool = False, folder: bool = False,
                   title=None, rows: tuple[str, ...] = (),
                   reads: tuple[str, str] | None = None, **keywords):
        """add_argument for a file the script writes (a report; a figure when `figure`), or
        a folder it writes in (`folder`: its reports, its cache): parse_args refuses one it
        cannot write (refuse_unusable_output, refuse_unusable_folders) before any work. A
        report's `title` is the first line the script writes (or a function of the parsed
        arguments giving it): an existing file is replaced only when it starts so; a JSON
        list of `rows` (the keys of each), only when it is one (rows_replace_problem). A figure
        the user names adds --overwrite, without which an existing figure is kept, as
        `tegrasp plot`. One it also reads first (`reads`: what its errors call it, and the
        advice) is checked as an input first (add_input), and needs no title: the script
        edits it in its own places (update_results_page: between its markers)."""
        if figure and folder:
            raise ValueError("add_output: an output is a figure or a folder, not both")
        if title is None and not (figure or folder or reads or rows):
            raise ValueError("add_output: a report needs the title line the script writes")
        action = self.add_argument(*names, **keywords)
        if reads:
            self._inputs.append((action.dest, *reads, folder))
        if figure and "--overwrite" not in self._option_string_actions:
            self.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
        self._outputs.append((action.dest, "figure" if figure else "folder" if folder
                              else "rows" if rows else "report", rows or title))
        return action

    def add_input(self, *names, what: str, advice: str, folder: bool = True, **keywords):
        """add_argument for a folder (a file unless `folder`) the script reads, which its
        errors call `what` ("results folder"): parse_args refuses one that is missing or of
        the other kind (refuse_unusable_input, with `advice`) before any output is checked,
        so that an input that cannot be read is never blamed on writing."""
        action = self.add_argument(*names, **keywords)
        self._inputs.append((action.dest, what, advice, folder))
        return action

    def add_number(self, *names, allowed, **keywords):
        """add_argument for a number of range `allowed` (ranges.Range; each one, for a
        list): parse_args refuses one outside it as the package's commands do (bad input,
        EXIT_ERROR, ranges.option_problem), before any work."""
        action = self.add_argument(*names, **keywords)
        self._ranges.append((action.dest, action.option_strings[-1] if action.option_strings
                             else action.dest, allowed))
        return action

    def add_workers(self, default: int = 2):
        """--workers N, the processes a script simulates in, and --oversubscribe: at least 1
        and at most the cores unless --oversubscribe, as `tegrasp sweep --workers`
        (sweep.runner.WORKER_COUNT, cores_problem); by default `default`, at most the cores."""
        from tegrasp_drake.rig.integer_text import integer_option
        from tegrasp_drake.sweep.runner import WORKER_COUNT
        self._workers_default = default
        self.add_argument("--oversubscribe", action="store_true",
                          help="allow --workers above the number of cores")
        return self.add_number("--workers", type=integer_option, metavar="N",
                               allowed=WORKER_COUNT, help="processes to simulate in (default: "
                               f"{default}, at most the cores; at most the cores unless "
                               "--oversubscribe)")

    def parse_args(self, args=None, namespace=None):
        from tegrasp_drake.rig.ranges import option_problem
        parsed = super().parse_args(args, namespace)
        for destination, option, allowed in self._ranges:
            values = getattr(parsed, destination)
            for value in values if isinstance(values, list) else [values]:
                problem = None if value is None else option_problem(option, value, allowed)
                if problem:
                    raise SystemExit(f"{self._script}: error: {problem}")
            setattr(parsed, destination, _plain_numbers(values))  # the typed text no further
        if self._workers_default is not None:
            parsed.workers = self._workers_within_cores(parsed.workers, parsed.oversubscribe)
        for destination, what, advice, folder in self._inputs:
            paths = getattr(parsed, destination)
            for path in paths if isinstance(paths, list) else [paths]:
                if path is not None:
                    refuse_unusable_input(self._script, path, what, advice, folder=folder)
        for destination, kind, title in self._outputs:
            path = getattr(parsed, destination)
            if path is None:
                continue
            if kind == "folder":
                refuse_unusable_folders(self._script, path)
            elif kind == "rows":
                refuse_unusable_output(self._script, path, rows=title)
            elif kind == "figure":
                refuse_unusable_output(self._script, path, figure=True,
                                       overwrite=parsed.overwrite)
            else:
                refuse_unusable_output(self._script, path, edited=title is None,
                                       title=title(parsed) if callable(title) else title)
        return parsed

    def _workers_within_cores(self, workers: int | None, oversubscribe: bool) -> int:
        """--workers as given, refused above the cores (cores_problem); or its default, at
        most the cores."""
        from tegrasp_drake.sweep.runner import cores_problem, default_workers
        if workers is None:
            return min(self._workers_default, default_workers())
        problem = cores_problem(workers, oversubscribe)
        if problem:
            raise SystemExit(f"{self._script}: error: --workers {workers}: {problem}")
        return workers

    def refuse(self, message):
        raise SystemExit(f"{self._script}: error: {message}")

    def _get_values(self, action, arg_strings):
        """argparse's values, an output given as '' (an unset shell variable) refused as a
        command line that does not parse, naming it, as `tegrasp`'s are (its type would
        make '' the current folder, '.')."""
        outputs = {destination: kind for destination, kind, _ in self._outputs}
        if action.dest in outputs and "" in arg_strings:
            name = action.option_strings[0] if action.option_strings else action.dest
            what = {"figure": "a figure file (.png, .pdf or .svg)",
                    "folder": "a folder to write in"}.get(outputs[action.dest], "a file to write")
            self.error(f"{name} '' is empty; give {what}")
        return super()._get_values(action, arg_strings)

    def error(self, message):
        self.exit(EXIT_USAGE, f"{self._script}: error: {error_line(message)}; "
                              f"{self.prog} --help shows the usage\n")


def _plain_numbers(values):
    """An option's number (or list of them) without the text a TypedNumber holds for its
    messages (rig.number_text.number_option): a plain float for the script's work."""
    from tegrasp_drake.rig.number_text import TypedNumber
    if isinstance(values, list):
        return [_plain_numbers(value) for value in values]
    return float(values) if isinstance(values, TypedNumber) else values


def script_parser(script: str, doc: str) -> argparse.ArgumentParser:
    """The argument parser of analysis/`script`.py, described by the first paragraph of its
    docstring `doc`: every script's command line is read through it, so each refuses one
    that does not parse alike (_ScriptParser). A value that parses but cannot be used (a
    figure name of no format, a path) is refused after parsing, with EXIT_ERROR."""
    return _ScriptParser(script, description=doc.strip().split("\n\n")[0])


def run_script(main, script: str, argv=None) -> int:
    """`main(argv)`'s exit code (argv None: the process's arguments), behind the scripts'
    one error boundary (_run_guarded), its standard output and error guarded as the `tegrasp`
    command line's (output_streams): one that cannot be written (a full disk, an I/O error;
    --help's text too, which argparse would lose) ends it with one line naming the stream and
    EXIT_ERROR; a reader that has gone (`| head`) ends it quietly with 128 + SIGPIPE."""
    from tegrasp_drake.commands import output_streams
    try:
        try:
            with output_streams.guarded_output():
                code = _run_guarded(main, script, argv)
        except SystemExit as exit_:  # --help, a usage error, a refusal
            unwritable = output_streams.unwritable_output()
            if unwritable and exit_.code in (0, None):
                output_streams.tell_cannot_write(*unwritable, program=script)
                return EXIT_ERROR
            raise
        unwritable = output_streams.unwritable_output()
        if unwritable:  # a script's own failure keeps its exit code (as cli.main's)
            output_streams.tell_cannot_write(*unwritable, program=script)
            return code or EXIT_ERROR
        return code
    except BrokenPipeError:
        output_streams.detach_standard_streams()
        return 128 + signal.SIGPIPE


def _run_guarded(main, script: str, argv=None) -> int:
    """`main(argv)`'s exit code behind the scripts' one error boundary: a SystemExit with a
    message ends it with that line, led by the
    script's name (_with_prefix); an error in a file or folder the user named (UserPathError,
    TrialLogError, MemorizedEventError, ConfigError, RecordError, FigureFormatError, another
    OSError, UnicodeDecodeError) ends it with one line, `<script>: error: <path>: <what is wrong>`,
    and EXIT_ERROR; any other exception with error_boundary's internal-error line, its traceback in a file."""
    from tegrasp_drake.commands.output_streams import OutputStreamError, tell_cannot_write
    from tegrasp_drake.events.event_file import MemorizedEventError
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.trial_log_file import TrialLogError
    from tegrasp_drake.sweep.records import RecordError
    arguments = sys.argv[1:] if argv is None else list(argv)
    try:
        return int(main(argv) or 0)
    except SystemExit as exit_:
        if isinstance(exit_.code, str):  # "script: ...", one bounded line
            raise SystemExit(error_line(_with_prefix(script, exit_.code))) from None
        raise
    except KeyboardInterrupt:
        print(f"{script}: interrupted (SIGINT)", file=sys.stderr, flush=True)
        return 128 + signal.SIGINT
    except (UserPathError, TrialLogError, MemorizedEventError, ConfigError, RecordError,
            FigureFormatError) as error:
        return _refused(script, str(error))
    except OutputStreamError as error:  # a print to a full disk: the stream, not a path
        tell_cannot_write(error.stream_name, error, program=script)
        return EXIT_ERROR
    except BrokenPipeError:
        raise
    except OSError as error:  # the system's words, after the path it could not use
        path = error.filename or getattr(error, "path", None)
        words = ("does not exist; check the path" if isinstance(error, FileNotFoundError)
                 else error.strerror or str(error))
        return _refused(script, f"{path}: {words}" if path else words)
    except UnicodeDecodeError as error:
        return _refused(script, f"a file is not UTF-8 text (byte {error.start}: "
                                f"{shown(error.object[error.start:error.start + 1])}); give a "
                                "UTF-8 text file")
    except Exception as error:  # noqa: BLE001: the error boundary
        return internal_error(error, arguments, script)


def _with_prefix(script: str, message: str) -> str:
    """`message`, a line ending the script, led by `<script>: error: ` (after the script's
    name when it names it), so that every line a script ends with says which script it was
    and that it is an error, as every `tegrasp` error line does."""
    lead = f"{script}: error: "
    if message.startswith(lead):
        return message
    return lead + message.removeprefix(f"{script}: ")


def _refused(script: str, message: str) -> int:
    print(f"{script}: error: {error_line(message)}", file=sys.stderr, flush=True)
    return EXIT_ERROR


# What a script tells the user to give for a folder it reads.
SWEEP_RESULTS_ADVICE = "give the --out folder of `tegrasp sweep`"
SWEEP_LOGS_ADVICE = "give the --logs folder of the sweep that wrote the records"
EVENTS_ADVICE = "give a folder of memorized events (`tegrasp record-events --out`)"
CORRECTIVE_LOGS_ADVICE = "give the folder analysis/record_corrective_events.py wrote"
ENSEMBLE_LOGS_ADVICE = "give the folder analysis/record_ensemble_events.py wrote"


def input_problem(path, *, folder: bool = True) -> str | None:
    """Why `path`, a folder (a file unless `folder`) a script reads, cannot be read as one,
    in words that follow it ("does not exist", "is a file, not a folder", "cannot be read
    (permission denied)"), or None; nothing is opened."""
    from tegrasp_drake.rig.api_boundary import INPUT_FOLDER
    from tegrasp_drake.rig.files import file_problem
    problem = INPUT_FOLDER.problem(path) if folder else file_problem(path)
    if problem is None and not os.access(path, os.R_OK | (os.X_OK if folder else 0)):
        problem = "cannot be read (permission denied)"
    return problem.split(";")[0] if problem else None


def refuse_unusable_input(script: str, path, what: str, advice: str, *,
                          folder: bool = True) -> None:
    """SystemExit with one line, `<script>: error: <what> '<path>' <why>; <advice>`, unless
    `path` can be read as a folder (a file unless `folder`): input_problem. `what` names the
    script's own argument ("results folder", "--events folder"), never a function's."""
    problem = input_problem(path, folder=folder)
    if problem:
        raise SystemExit(f"{script}: error: {what} {shown(os.fspath(path))} {problem}; "
                         f"{advice}")


def load_sweep_records(script: str, results, what: str = "results folder",
                       advice: str = SWEEP_RESULTS_ADVICE):
    """The records (sweep.LoadedRecords) of the sweep folder `results`, which the script's
    argument `what` names; SystemExit with one line if it is no folder to read
    (refuse_unusable_input), any record is corrupt or records mix memorized events
    (LoadedRecords.table_problem, as `tegrasp plot` refuses them)."""
    from tegrasp_drake.sweep.records import load_records
    refuse_unusable_input(script, results, what, advice)
    loaded = load_records(results)
    problem = loaded.table_problem(results)
    if problem:
        raise SystemExit(f"{script}: error: {problem}")
    return loaded


def refuse_unusable_folders(script: str, *folders) -> None:
    """SystemExit with one line naming the first of `folders` (a script's outputs) that
    cannot be, or be made as, a folder this user writes in (rig.files.folder_problem);
    asked before the work starts, so that a long run does not end on its output."""
    for folder in folders:
        problem = folder_problem(folder)
        if problem:
            raise SystemExit(f"{script}: cannot write into {folder}: {problem}; give a "
                             "folder you can write in")


def refuse_unusable_output(script: str, path, *, figure: bool = False, overwrite: bool = False,
                           title: str | None = None, edited: bool = False,
                           rows: tuple[str, ...] = ()) -> None:
    """SystemExit with one line unless `path` can be written (rig.files.output_file_problem)
    as a script's report, whose first line is `title` (an existing file only if it starts
    so: report_replace_problem; a bare table's title is its header row), or as a figure the
    user named when `figure` (a suffix naming a figure format, figure_files.check_figure_path;
    an existing file only if it is a figure of that format, and only with `overwrite`:
    figure_replace_problem, as `tegrasp plot --overwrite`), or as a file the script reads
    and edits in its own places (`edited`, no title), or as a JSON list of `rows` (the keys
    of each: rows_replace_problem); asked before the work starts."""
    if figure:
        try:
            check_figure_path(path)
        except FigureFormatError as error:
            raise SystemExit(f"{script}: error: {error}") from None
    elif title is None and not (edited or rows):
        raise ValueError("refuse_unusable_output: a report needs the title line it starts with")
    problem = output_file_problem(path)
    if problem:
        raise SystemExit(f"{script}: cannot write {path}: {problem}")
    problem = (figure_replace_problem(path, overwrite=overwrite) if figure else None if edited
               else rows_replace_problem(path, rows) if rows
               else report_replace_problem(path, title + "\n",
                                           "table" if title.startswith("| ") else "report"))
    if problem:
        raise SystemExit(f"{script}: error: {path} {problem}")


def rows_replace_problem(path, keys: tuple[str, ...]) -> str | None:
    """Why a script's JSON list of rows, each with `keys`, may not replace the file at `path`,
    in words that follow it, or None: only a JSON list of such rows is one it wrote (the
    user's result or notes are not). Read up to _ROWS_BYTES."""
    import json
    from tegrasp_drake.rig.files import read_bounded
    try:
        raw = read_bounded(path, _ROWS_BYTES)
    except (FileNotFoundError, NotADirectoryError, IsADirectoryError):
        return None  # nothing there, or a folder (output_file_problem says so)
    except OSError as error:  # InputTooLargeError too: no list of rows is that long
        return (f"cannot be read to check what it is ({os_error_text(error)}); give another "
                "file name")
    try:
        data = json.loads(raw)
    except ValueError:
        data = None
    if isinstance(data, list) and all(isinstance(row, dict) and set(keys) <= set(row)
                                      for row in data):
        return None
    first = raw.split(b"\n", 1)[0].rstrip(b"\r").decode("utf-8", errors="replace")
    return (f"exists and is not a JSON list of rows this script writes (its first line is "
            f"{shown(first) if first else 'empty'}); give another file name, or remove it "
            "yourself")


_ROWS_BYTES = 16 * 1024 * 1024


# --overwrite of a script writing a figure the user names, in `tegrasp plot`'s words.
OVERWRITE_HELP = ("replace an existing figure at the path given (a file that is not a figure "
                  "of its format is never replaced)")
