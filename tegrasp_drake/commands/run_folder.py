"""Where a run's files go, and which earlier run they may replace.

A run folder holds one run: its log (trial.npz), its figures and `result.json` (the object
that `--json` prints), written last. A new run never replaces an earlier one unasked:
- a folder named with `--out` that already holds a run (result.json or trial.npz) is
  refused with one line, unless `--overwrite` is given;
- without `--out`, `tegrasp trial` writes out/trial, or the first of out/trial-2,
  out/trial-3, ... that holds no run, so that every trial is kept;
- `tegrasp demo` writes out/demo and replaces the last demo there: it is the README's
  demonstration, run again as it stands (give `--out DIR` to keep one).
A hardware run's result goes beside its LCM log: run.lcmlog -> run.result.json.
"""

import json
import os
import pathlib

RESULT_FILE = "result.json"
RUN_FILES = (RESULT_FILE, "trial.npz")  # a folder with any of these holds a run


class RunFolderError(Exception):
    """A run would replace an earlier run's files; the message says what to do."""


def holds_run(folder) -> bool:
    folder = pathlib.Path(folder)
    return any((folder / name).exists() for name in RUN_FILES)


def first_free_folder(default) -> pathlib.Path:
    """`default`, or the first of default-2, default-3, ... that holds no run."""
    default = pathlib.Path(default)
    candidate, number = default, 1
    while holds_run(candidate):
        number += 1
        candidate = default.with_name(f"{default.name}-{number}")
    return candidate


def choose_run_folder(out, *, default, replace_default: bool, overwrite: bool) -> pathlib.Path:
    """The folder for a new run (module docstring); out: the `--out` given, or None.

    Raises RunFolderError when `out` holds a run and `overwrite` is false. The folder is
    created, and an earlier result.json in it removed, so that a run that fails before
    its end leaves no result that is not its own."""
    if out is None:
        folder = pathlib.Path(default) if replace_default else first_free_folder(default)
    else:
        folder = pathlib.Path(out)
        if holds_run(folder) and not overwrite:
            present = ", ".join(name for name in RUN_FILES if (folder / name).exists())
            raise RunFolderError(f"{folder} already holds a run ({present}); give another "
                                 "--out, or --overwrite to replace it")
    folder.mkdir(parents=True, exist_ok=True)
    (folder / RESULT_FILE).unlink(missing_ok=True)
    return folder


def write_result(path, result: dict) -> pathlib.Path:
    """Writes `result` as JSON (keys sorted, as `--json` prints it) to `path`, atomically."""
    path = pathlib.Path(path)
    temporary = path.with_name(f".{path.name}.tmp")
    temporary.write_text(json.dumps(result, sort_keys=True, indent=1) + "\n", encoding="utf-8")
    os.replace(temporary, path)
    return path


def result_path_beside_log(log_path) -> pathlib.Path:
    """Where a hardware run's result goes: run.lcmlog -> run.result.json."""
    log_path = pathlib.Path(log_path)
    return log_path.with_name(f"{log_path.stem}.result.json")
