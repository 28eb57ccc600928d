"""A text report this tool writes (a command's Table I, statistics or transfer matrix in its
--out; an analysis script's report): known by how it starts (its exact title line, a CSV's
header row, a JSON report's opening through its first key), so that an existing file under
a report's name is replaced only when it is a report of that kind the tool wrote earlier,
never the user's own notes saved under that name. Asked before the work
(foreign_report_problem) and again when the report is written (write_report), as
figure_files does for figures."""

import pathlib

from tegrasp_drake.rig.echo import shown
from tegrasp_drake.rig.files import UserPathError, existing_output_head, write_atomically

_HEAD_BYTES = 4096  # more than any report's start


def report_replace_problem(path, start: str, kind: str = "report",
                           writer: str = "this script") -> str | None:
    """Why a `kind` of report starting with `start` (its title line and newline, or more)
    may not replace the file at `path`, in words that follow it, or None: nothing is there,
    or a file starting with `start` (one `writer` wrote); the user's notes, or another
    report, are never replaced. Only the head is read."""
    head, problem = existing_output_head(
        path, max(_HEAD_BYTES, len(start.encode("utf-8"))),
        "a file belongs; move it away, or give another file name")
    if problem:
        return problem
    if head is None or head.startswith(start.encode("utf-8")):
        return None
    first = head.split(b"\n", 1)[0].rstrip(b"\r").decode("utf-8", errors="replace")
    return (f"exists and is not a {kind} {writer} writes (its first line is "
            f"{shown(first) if first else 'empty'}); give another file name, or remove it "
            "yourself")


def foreign_report_problem(folder, reports: dict[str, str], command: str) -> str | None:
    """Why `tegrasp <command>` may not write its reports `reports` (file name -> how it
    starts) into --out `folder`, or None: a file there under a report's name is not that
    report (report_replace_problem). Asked before the command runs anything, in the words
    of a run's refusal of a foreign trial.npz or result.json (run_folder)."""
    folder = pathlib.Path(folder)
    for name, start in reports.items():
        problem = report_replace_problem(folder / name, start, writer=f"`tegrasp {command}`")
        if problem:
            why = problem.split(";")[0]
            return (f"--out {folder}: {name} {why}, and a {command} run replaces its {name}; "
                    "move it out of the folder, or give another --out")
    return None


def write_report(path, text: str, start: str) -> pathlib.Path:
    """Writes the report `text`, which starts with `start`, to `path` atomically
    (write_atomically); UserPathError naming it, the file there untouched, when that file is
    not an earlier such report (report_replace_problem: one that came during the work)."""
    if not text.startswith(start):
        raise ValueError(f"the report for {path} does not start with {start!r}")
    problem = report_replace_problem(path, start, writer="this tool")
    if problem:
        raise UserPathError(f"cannot write {path}: it {problem}")
    return write_atomically(path, text, start=start.encode("utf-8"))
