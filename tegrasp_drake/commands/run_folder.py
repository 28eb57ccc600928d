"""Where a run's files go, and which earlier run they may replace (docs/user-guide.md, "`tegrasp
trial` and `tegrasp demo`"). Files are staged in a hidden folder and replace the earlier run's
together at the end (commit_run), so a failed or interrupted run leaves the earlier one whole."""

import contextlib
import json
import logging
import os
import pathlib
import re
import shutil
import tempfile

from tegrasp_drake.events.event_file import INDEX_FILE
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS, starts_as_figure
from tegrasp_drake.figures.trial_figures import TRIAL_FIGURE_KEYS, TRIAL_FIGURE_STEMS
from tegrasp_drake.rig.files import (os_error_text, FOLDER_HELD, JSON_OBJECT_START, FolderHeldError,
                                     absent_folders, claim_folder, file_problem,
                                     folder_problem, held_folder, interruptions_deferred,
                                     load_json, made_folders_removed_if_empty,
                                     own_staging_suffix, read_bounded,
                                     remove_stale_staging_files_of, write_atomically)
from tegrasp_drake.rig.echo import shown

logger = logging.getLogger(__name__)

RESULT_FILE = "result.json"
RUN_FILES = (RESULT_FILE, "trial.npz")  # a folder with any of these holds a run
REPLAY_KEY = "replay_html"  # result.json's entry for the replay --html wrote



# What each command that writes a run folder leaves at its top level, the entries that say
# whose run a folder holds; asked in this order, since a sensitivity study's folder holds a
# transfer's entries too (its points.json beside them). An events folder (record-events')
# is one too: a run written into it would mix with the memorized events a sweep reads. Its
# index.json is asked before the folders a transfer's or a sweep's run holds, whose names an
# object's folder of events may have (an object called `trials`); an object's name holds no
# '.', so no object's folder is taken for a file asked here.
RUN_OWNERS = (("sensitivity", ("points.json",)), ("record-events", (INDEX_FILE,)),
              ("transfer", ("cells", "events")), ("sweep", ("trials",)), ("trial", RUN_FILES))


def run_owners(folder) -> list[tuple[str, str]]:
    """Each (command whose run `folder` holds, the entry that says so), in RUN_OWNERS' order,
    a command once: a folder may hold several runs' entries (a trial's result.json beside a
    sweep's trials). In an events folder (its index.json) a folder entry is an object's
    events, not a run's (an object called `trials`); its files are still asked."""
    folder = pathlib.Path(folder)
    events_folder = os.path.lexists(folder / INDEX_FILE)
    owners = []
    for command, entries in RUN_OWNERS:
        for entry in entries:
            path = folder / entry
            if os.path.lexists(path) and not (events_folder and command != "record-events"
                                              and path.is_dir()):
                owners.append((command, entry))
                break
    return owners


def run_owner(folder) -> tuple[str, str] | None:
    """The first of run_owners(folder), or None."""
    owners = run_owners(folder)
    return owners[0] if owners else None


def other_run_problem(folder, command: str, *, named: str | None = None) -> str | None:
    """Why `tegrasp <command>` may not write its run into `folder`, or None: it holds another
    command's run (any of run_owners, not only the first), whose files a run of this one
    would mix with (and a resume of that run would then read); each command's run keeps a
    folder of its own. `named`: the option or setting that chose the folder, when it is not
    --out (record-events' --events, a command's default folder)."""
    owner = next((owner for owner in run_owners(folder) if owner[0] != command and (
        command, owner[0]) != ("sensitivity", "transfer")), None)
    if owner is None:  # a sensitivity study is a transfer with its points.json beside it
        return None
    if named is not None:
        return (f"{named} holds {held_run(owner)}; give {command} a folder of its own (not "
                "a run's folder)")
    return f"--out {folder} holds {held_run(owner)}; give another --out for this {command} run"


def held_run(owner: tuple[str, str]) -> str:
    """What a folder of run_owner `owner` holds, in words."""
    command, entry = owner
    if command == "record-events":
        return f"memorized events ({entry})"
    return f"a `tegrasp {command}` run ({entry})"


def logs_folder_problem(logs, out) -> str | None:
    """Why a sweep's --logs `logs` may not hold its trials' logs beside --out `out`, or None:
    it holds a run or memorized events (run_owner), or is --out or inside one of --out's
    run entries (its trials), whose files a log would mix with."""
    owner = run_owner(logs)
    if owner is not None:
        return (f"--logs {logs} holds {held_run(owner)}; give the trials' logs a folder of "
                "their own")
    logs_path, out_path = pathlib.Path(logs).resolve(), pathlib.Path(out).resolve()
    if logs_path == out_path:
        return (f"--logs {logs} is the sweep's --out; give the trials' logs a folder of "
                "their own")
    for _, entries in RUN_OWNERS:
        for entry in entries:
            if logs_path.is_relative_to(out_path / entry):
                return (f"--logs {logs} is inside --out {out}'s {entry}; give the trials' logs "
                        "a folder of their own")
    return None


class RunFolderError(Exception):
    """A run would replace an earlier run's files; the message says what to do."""


def holds_run(folder) -> bool:
    folder = pathlib.Path(folder)
    return any((folder / name).exists() for name in RUN_FILES)


def claim_numbered_folder(default) -> pathlib.Path:
    """The first of `default`, default-2, default-3, ... that this call creates (one mkdir
    each: a folder another run has just claimed, or that already exists, is passed over)."""
    default = pathlib.Path(default)
    candidate, number = default, 1
    while not claim_folder(candidate):
        number += 1
        candidate = default.with_name(f"{default.name}-{number}")
    return candidate


def check_run_folder(folder) -> None:
    """RunFolderError unless `folder` is, or can be made as, a folder this user can write."""
    if not str(folder).strip():
        raise RunFolderError(f"--out {shown(str(folder))} is empty; give a folder you can write")
    problem = folder_problem(folder)
    if problem:
        raise RunFolderError(f"--out {folder}: {problem}; give a folder you can write")


def choose_run_folder(out, *, default, replace_default: bool, overwrite: bool) -> pathlib.Path:
    """The folder for a new run (module docstring), created; out: the `--out` given, or None.
    RunFolderError when `out` holds a run without `overwrite`, or cannot be written."""
    check_run_folder(out if out is not None else default)
    folder = pathlib.Path(out if out is not None else default)
    # the default folder a run replaces (demo's out/demo) is checked as an --out given is
    problem = (out is not None or replace_default) and other_run_problem(
        folder, "trial", named=None if out is not None else f"the default --out {folder}")
    if problem:
        raise RunFolderError(problem)
    for name in sorted(run_file_names()) if out is not None else ():
        problem = os.path.lexists(folder / name) and file_problem(folder / name)
        if not problem and os.path.islink(folder / name):  # a run writes no link: the user's
            problem = "is a symbolic link (a run writes its files itself, never a link)"
        if problem and problem != "does not exist":  # a dangling symlink is replaced
            raise RunFolderError(
                f"--out {folder}: {name} {problem.split(';')[0]}, where the run writes its "
                f"{name}; remove it yourself, or give another --out")
    problem = (out is not None or replace_default) and (
        foreign_run_file_problem(folder) or foreign_figure_problem(folder))
    if problem:
        raise RunFolderError(problem)
    if out is not None and holds_run(folder) and not overwrite:
        present = ", ".join(name for name in RUN_FILES if (folder / name).exists())
        raise RunFolderError(f"{folder} already holds a run ({present}); give another "
                             "--out, or --overwrite to replace it")
    try:
        if out is None and not replace_default:
            return claim_numbered_folder(default)
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise RunFolderError(f"--out {folder}: cannot make the folder: "
                             f"{os_error_text(e)}") from None
    return folder


def _made_by(make, folder) -> tuple[pathlib.Path, list[pathlib.Path]]:
    """Runs make() -> the run folder, and returns it with the folders it created (the run
    folder, if it was not there, then its parents that were not), deepest first."""
    absent_parents = absent_folders(folder.parent)
    existed = folder.exists()
    made_folder = make()  # `folder`, or a numbered one it claimed beside `folder`
    new = [] if made_folder == folder and existed else [made_folder]
    return made_folder, [path for path in new + absent_parents if path.is_dir()]


@contextlib.contextmanager
def new_run_folder(out, *, default, replace_default: bool, overwrite: bool):
    """choose_run_folder for the block. When the block raises or is interrupted (a failed
    simulation, Ctrl-C, SIGTERM), the folders made for it, the run folder and any parents it
    needed, are removed again if they are still empty (made_folders_removed_if_empty): a run
    that wrote nothing leaves nothing."""
    folder = pathlib.Path(out if out is not None else default)
    folder, made = _made_by(lambda: choose_run_folder(
        out, default=default, replace_default=replace_default, overwrite=overwrite), folder)
    with made_folders_removed_if_empty(made):
        yield folder


STAGING_PREFIX = ".staging-"  # a run's files until it commits them (staged_run)


# What tempfile.mkdtemp names a staging folder: the prefix and 8 of its random characters.
_STAGING_FOLDER_NAME = re.compile(re.escape(STAGING_PREFIX) + r"[a-z0-9_]{8}")


def is_left_staging_folder(path) -> bool:
    """Whether `path` is a staging folder a run left (staged_run): named as mkdtemp names
    one, a folder (not a link), holding nothing but files under a run's own names and their
    hidden temporary files. A folder of the user's that happens to start with the prefix
    holds something else, or is named otherwise, and is left alone."""
    path = pathlib.Path(path)
    if (not _STAGING_FOLDER_NAME.fullmatch(path.name) or path.is_symlink()
            or not path.is_dir()):
        return False
    names = run_file_names()
    try:
        entries = list(path.iterdir())
    except OSError:
        return False
    return all(entry.is_file() and not entry.is_symlink()
               and (entry.name in names
                    or (entry.name.startswith(".") and any(name in entry.name for name in names)))
               for entry in entries)


@contextlib.contextmanager
def staged_run(folder):
    """A hidden staging folder inside the run folder (removed when the block ends), the run
    folder locked (flock) for the block, so a second run into it is refused at once. Staging
    folders already there that a run left (is_left_staging_folder) are removed first: with the
    lock held no live run writes there, so they are what a run killed past its handlers
    (SIGKILL, a power cut) left."""
    with claimed_run_folder(folder):
        for stale in pathlib.Path(folder).glob(f"{STAGING_PREFIX}*"):
            if is_left_staging_folder(stale):
                shutil.rmtree(stale, ignore_errors=True)
        stage = None
        try:
            with interruptions_deferred():  # a signal between mkdir and `stage` leaves it
                try:
                    stage = pathlib.Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=folder))
                except OSError as e:
                    raise RunFolderError(f"--out {folder}: cannot write there: "
                                         f"{os_error_text(e)}") from None
            yield stage
        finally:
            if stage is not None:
                shutil.rmtree(stage, ignore_errors=True)


def staging_file_beside(path, start: bytes) -> pathlib.Path:
    """Where this process writes `path` until it commits it (`.NAME.PID.staging` beside it);
    the staging files of `path` that runs killed past their handlers (SIGKILL, a power cut)
    left, holding what starts with `start` (its format's magic), are removed first
    (remove_stale_staging_files). Other files in the folder are left alone, whatever
    their names."""
    path = pathlib.Path(path)
    remove_stale_staging_files(path, start)
    return path.with_name(f".{path.name}{own_staging_suffix()}")


def remove_stale_staging_files(target, start: bytes) -> list[pathlib.Path]:
    """Removes the staging files of `target` whose process has ended and whose content starts
    as `target`'s does (stale_staging_files_of), and returns them; a live process's are left
    alone. The folder is locked meanwhile (claimed_run_folder), as staged_run locks it to
    remove stale staging folders; when another run holds the lock (a trial writing there),
    nothing is removed now, and the next run does it."""
    target = pathlib.Path(target)
    try:
        with claimed_run_folder(target.parent):
            return remove_stale_staging_files_of(target, start)
    except (RunFolderError, OSError):
        return []


@contextlib.contextmanager
def claimed_run_folder(folder):
    """Holds `folder` for the block (rig.files.held_folder, the lock every run into a folder
    takes); RunFolderError if another run holds it or it cannot be opened."""
    with contextlib.ExitStack() as stack:
        try:
            stack.enter_context(held_folder(folder))
        except FolderHeldError:
            raise RunFolderError(f"--out {folder}: {FOLDER_HELD}; wait for it to end, or "
                                 "give another --out") from None
        except OSError as e:
            raise RunFolderError(f"--out {folder}: cannot open it: {os_error_text(e)}") from None
        yield


def own_file_problem(path, folder) -> str | None:
    """Why an output path given beside a run (--html) may not be written: it is one of the
    files the run writes into `folder`. None if not."""
    path, folder = pathlib.Path(path), pathlib.Path(folder)
    if path.resolve() == folder.resolve() or path.resolve() in folder.resolve().parents:
        return f"is the run's folder {folder} (or holds it); give a file name, e.g. replay.html"
    if path.resolve().parent != folder.resolve():
        return None
    stem = path.name.split(".", 1)[0]
    if path.name in RUN_FILES or stem in TRIAL_FIGURE_STEMS or path.name.startswith(STAGING_PREFIX):
        return (f"is one of the run's own files in {folder} ({path.name}); give another "
                "name, e.g. replay.html")
    return None


def commit_run(stage, folder, result: dict) -> dict:
    """Moves the staged files into `folder` and writes result.json last, Ctrl-C held back;
    returns `result` with the staged paths replaced by the final ones. What it replaced and
    removed of the earlier run is logged at INFO (`-v`)."""
    stage, folder = pathlib.Path(stage), pathlib.Path(folder)
    result = {key: (str(folder / pathlib.Path(value).name)
                    if isinstance(value, str) and pathlib.Path(value).parent == stage
                    else value) for key, value in result.items()}
    result["result"] = str(folder / RESULT_FILE)
    new_names = {staged.name for staged in stage.iterdir()} | {RESULT_FILE}
    earlier_files = earlier_run_files(folder)
    leftovers = [path for path in earlier_files if path.name not in new_names]
    with interruptions_deferred():
        for staged in sorted(stage.iterdir()):
            os.replace(staged, folder / staged.name)
        write_result(folder / RESULT_FILE, result)
        for path in leftovers:  # the earlier run's files this run did not replace
            with contextlib.suppress(OSError):
                path.unlink()
    replaced = sorted(new_names & {path.name for path in earlier_files})
    if replaced:
        logger.info(f"{folder}: replaced the earlier run's {', '.join(replaced)}")
    if leftovers:
        logger.info(f"{folder}: removed the earlier run's "
                    f"{', '.join(path.name for path in leftovers)} (not written by this run)")
    return result


def run_file_names() -> set[str]:
    """The names a run gives its own files in its folder: result.json, trial.npz and each
    figure's STEM.FORMAT (a folder moved or copied still holds them under these names)."""
    return set(RUN_FILES) | {f"{stem}.{figure_format}" for stem in TRIAL_FIGURE_STEMS
                             for figure_format in FIGURE_FORMATS}


def earlier_run_files(folder) -> list[pathlib.Path]:
    """The files of the run `folder` holds, under a run's own names (run_file_names): what
    a new run replaces. Known by name, since the absolute paths result.json recorded name
    where the run was written, which a moved or copied folder no longer is; a file under a
    figure's name only when the run wrote it (is_earlier_figure). Nothing else is touched:
    not the replay an earlier `--html` wrote (a file the user named, and may have edited or
    replaced since), nor any file result.json names."""
    folder = pathlib.Path(folder)
    recorded = recorded_figure_names(folder)
    return [folder / name for name in sorted(run_file_names())
            if (folder / name).is_file() and not (folder / name).is_symlink()
            and (name in RUN_FILES or is_earlier_figure(folder / name, recorded))]


# The most a run's result.json holds: its transitions and scores are a few kB.
MAX_RESULT_BYTES = 16_000_000


def recorded_figure_names(folder) -> set[str]:
    """The names of the figures the run in `folder` recorded in its result.json (the last part
    of each figure field's path: the folder may have been moved or copied since); none when
    the folder holds no result.json that reads as a run's (a JSON object)."""
    try:
        result = load_json(read_bounded(pathlib.Path(folder) / RESULT_FILE,
                                        MAX_RESULT_BYTES).decode("utf-8"))
    except (OSError, ValueError, RecursionError):  # missing, not a file, not JSON, too large
        return set()
    if not isinstance(result, dict):
        return set()
    paths = (result.get(key) for key in TRIAL_FIGURE_KEYS.values())
    return {pathlib.PurePath(path).name for path in paths if isinstance(path, str)}


def is_earlier_figure(path, recorded: set[str]) -> bool:
    """Whether the file at `path`, under a figure's name, is a figure a run of this tool
    wrote there: its folder's result.json records it (`recorded`, recorded_figure_names) and it
    starts as a figure of its format does (starts_as_figure). Anything else there, the
    user's notes or own picture, is never replaced or removed by a run."""
    path = pathlib.Path(path)
    return path.name in recorded and starts_as_figure(path)


def foreign_figure_problem(folder) -> str | None:
    """Why a run may not be written into `folder`, or None: a regular file there under a
    figure's name (any format: a run replaces its own format's and removes the others') that
    no run of this tool wrote (is_earlier_figure). Asked before the run simulates."""
    folder = pathlib.Path(folder)
    recorded = recorded_figure_names(folder)
    for name in sorted(run_file_names() - set(RUN_FILES)):
        path = folder / name
        if not path.is_file() or path.is_symlink() or is_earlier_figure(path, recorded):
            continue
        why = ("is not a figure this tool wrote" if not starts_as_figure(path) else
               f"is not a figure of the run there (its {RESULT_FILE} does not list it)")
        return (f"--out {folder}: {name} {why}, and a run writes or removes its {name}; move "
                "it out of the folder, or give another --out")
    return None


def foreign_run_file_problem(folder) -> str | None:
    """Why a run may not be written into `folder`, or None: its trial.npz or result.json (a
    regular file under a run's own name, which a run replaces) is not an earlier run's:
    trial.npz must be a trial log as TrialLog.save wrote it (written_trial_log: its checksum
    that of what it holds, or, written by an earlier version of the package, none), result.json
    a trial's result (TrialResult's JSON form) naming trial.npz as its log and, beside a log, that log's own result. Asked
    before the run simulates, as foreign_figure_problem is for the figures."""
    from tegrasp_drake.scenario.trial_log_file import TrialLogError, written_trial_log
    from tegrasp_drake.scenario.trial_result import TrialResult
    folder = pathlib.Path(folder)
    log_name = RUN_FILES[1]

    def refusal(name: str, why: str) -> str:
        return (f"--out {folder}: {name} {why}, and a run replaces its {name}; move it out of "
                "the folder, or give another --out")

    def own(path: pathlib.Path) -> bool:  # links and non-files: choose_run_folder's
        return path.is_file() and not path.is_symlink()
    logged_result = None
    if own(folder / log_name):
        try:
            logged_result = written_trial_log(folder / log_name, any_version=True)[0].get("result")
        except TrialLogError as error:
            reason = str(error).removeprefix("trial log ").removeprefix(
                f"'{folder / log_name}'").lstrip(": ")
            reason = reason.split("; run the trial again")[0].split("; give the trial.npz")[0]
            return refusal(log_name, f"is not a trial log a run wrote ({reason})")
    if not own(folder / RESULT_FILE):
        return None
    try:
        data = load_json(read_bounded(folder / RESULT_FILE, MAX_RESULT_BYTES).decode("utf-8"))
        TrialResult.from_dict(data)
    except (OSError, ValueError, TypeError, RecursionError) as error:
        reason = error.strerror if isinstance(error, OSError) else str(error)
        reason = reason.removeprefix("not a trial result's JSON form: ").split("; give")[0]
        return refusal(RESULT_FILE, f"is not a trial's result ({reason})")
    logged = data.get("log")
    if not isinstance(logged, str) or pathlib.PurePath(logged).name != log_name:
        named = shown(logged) if isinstance(logged, str) else logged
        return refusal(RESULT_FILE, f"is a result whose log is {named}, not a run's {log_name}")
    if isinstance(logged_result, dict):
        differs = next((key for key, value in logged_result.items()
                        if data.get(key, "absent") != value), None)
        if differs is not None:
            return refusal(RESULT_FILE, f"is not the result of the {log_name} beside it (their "
                                        f"'{differs}' differ)")
    return None


def write_result(path, result: dict) -> pathlib.Path:
    """Writes `result` as JSON (keys sorted, as `--json` prints it) to `path`, atomically."""
    return write_atomically(path, json.dumps(result, sort_keys=True, indent=1) + "\n",
                            start=JSON_OBJECT_START)


def result_path_beside_log(log_path) -> pathlib.Path:
    """Where a hardware run's result goes: run.lcmlog -> run.result.json."""
    log_path = pathlib.Path(log_path)
    return log_path.with_name(f"{log_path.stem}.result.json")
