"""Runs a sweep's trials in parallel and records each one durably as it finishes.

`run_sweep` skips every trial with a valid "ok" record, so a killed sweep resumes with
nothing lost or run twice; a missing, corrupt or error record (a trial function that
raised, recorded with its traceback) runs again. Backends: a local process pool
(forkserver, never fork: pydrake has started threads) or a Dask cluster (`scheduler`, the
`dask` extra); the workers only compute, the parent writes every record. A worker that
dies leaves its trial unrecorded, for the next run."""

import dataclasses
import functools
import json
import logging
import multiprocessing
import os
import pickle
import signal
import struct
import tempfile
import threading
import time
import traceback
import typing
import uuid
from typing import Annotated
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import ExitStack, closing, contextmanager, nullcontext, suppress
from dataclasses import dataclass
from pathlib import Path
from collections.abc import Callable

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.sweep.records import (
    TRIALS_FOLDER,
    RecordError,
    canonical_json,
    earlier_temporary_files,
    events_words,
    load_records,
    mixed_study_problem,
    make_record,
    record_name_trial_id,
    remove_stale_staging_files,
    result_problem,
    result_trial_problem,
    unwritable_records,
    write_record,
)
from tegrasp_drake.sweep.spec import (CONFIRMED_TRIALS, SweepSpec, TrialSpec, check_sweep_size,
                                      expand_trials)
from tegrasp_drake.rig.api_boundary import OUTPUT_FOLDER, PathLike, public_api
from tegrasp_drake.rig.files import (FolderHeldError, UserPathError, folder_problem, held_folder,
                                     non_folder_on_path, unprobed_folder_checks)
from tegrasp_drake.rig.number_text import count_text
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.scenario.trial_log_file import LogNotWritten

logger = logging.getLogger(__name__)

DASK_CONNECT_TIMEOUT_S = 30.0
# The wall time a scheduler has to answer, the handshake included: distributed's connect
# timeout and as long again for the handshake's replies (a scheduler on a loaded host
# answers in well under a second).
DASK_ANSWER_BOUND_S = 2 * DASK_CONNECT_TIMEOUT_S


class SweepError(RuntimeError):
    """A sweep cannot start or could not finish; the message says what to do."""


class RecordPlaceError(SweepError):
    """The output folder cannot take a trial's record (a folder where the record belongs,
    `trials` not a folder): a folder that cannot be used, said before any trial runs."""


class SchedulerLostError(SweepError):
    """The Dask scheduler went away while trials ran; the finished ones are recorded."""


@dataclass(frozen=True)
class SweepSummary:
    """What one `run_sweep` call did."""
    out_dir: Path
    total: int                      # trials in the spec
    skipped: int                    # already finished before this call
    ran: int                        # trials this call ran and recorded
    errors: tuple[str, ...]         # trial ids whose trial function raised in this call
    unfinished: tuple[str, ...]     # trial ids left without a record (a worker died)
    corrupt: tuple[str, ...]        # corrupt record files found (their trials re-run)
    backend: str                    # "processes:N" or "dask:ADDRESS"
    wall_time_s: float
    trial_ids: tuple[str, ...] = ()  # the trials of this spec (what the reports count)
    other_records: int = 0          # records in the folder of trials not in this spec
    unwritten_log: str | None = None  # "PATH: reason" of a --logs copy not written (the
    #                                   sweep stopped there; its trial's result is recorded)


def check_result(result, trial: dict) -> str | None:
    """Why a trial function's return value cannot be `trial`'s result, or None when it can
    (the checks below name the field; result_problem and result_trial_problem are the
    record's own checks, the last word)."""
    if not isinstance(result, dict):
        return f"the trial function returned {type(result).__name__}, not a dict"
    for name in ("hold_success", "unload_success"):
        if not isinstance(result.get(name), bool):
            return f"result field {name!r} must be true or false, got {result.get(name)!r}"
    expected_types = {"transitions": list, "corrective_actions": (list, dict),
                      "detection_latency_s": dict, "false_triggers": int}
    for name, types in expected_types.items():
        if name in result and not isinstance(result[name], types):
            return f"result field {name!r} has type {type(result[name]).__name__}"
    from tegrasp_drake.control.grasp_modes import Mode, Transition
    for k, entry in enumerate(result.get("transitions", [])):
        try:
            Transition.from_dict(entry)
        except (KeyError, ValueError, TypeError, AttributeError) as e:
            return (f"result field 'transitions'[{k}] is not a transition (t, from, to, "
                    f"trigger, reason; as Transition.as_dict writes it): {e!r}")
    if "final_mode" in result:
        try:
            Mode.from_label(result["final_mode"])
        except ValueError as e:
            return f"result field 'final_mode': {e}"
    # What load_records will ask of the record: a result it would refuse is an error now,
    # not a record that is corrupt at every resume and runs again each time.
    problem = result_problem(result)
    if problem is not None:
        return f"the result is {problem}"
    return result_trial_problem(result, trial)


def run_trial_safely(trial_function, trial: dict) -> tuple[str, dict, str | None]:
    """Runs one trial in a worker: ("ok", result, unwritten log) or ("error", error dict,
    unwritten log), never raises; the unwritten log is "PATH: reason" when the trial finished
    but its log copy could not be written (LogNotWritten), else None. The result goes
    through canonical JSON here (numpy to plain numbers, unstorable results fail)."""
    unwritten_log = None
    try:
        try:
            value = trial_function(trial)
        except LogNotWritten as unwritten:  # the result stands; only the copy is lost
            value, unwritten_log = unwritten.result, f"{unwritten.path}: {unwritten.reason}"
        result = json.loads(canonical_json(value))
    except Exception as error:  # Any failure of the trial is recorded, not raised.
        return "error", {"type": type(error).__name__, "message": str(error),
                         "traceback": traceback.format_exc()}, unwritten_log
    problem = check_result(result, trial)
    if problem is not None:
        return ("error", {"type": "InvalidResult", "message": problem, "traceback": ""},
                unwritten_log)
    return "ok", result, unwritten_log


# Local worker processes (run_sweep's workers, `tegrasp sweep --workers`); more than the
# cores only when asked for (--oversubscribe) and never more than the memory holds (pool_size).
WORKER_COUNT = Range(low=1)


def default_workers() -> int:
    return len(os.sched_getaffinity(0))


def cores_problem(workers: int, oversubscribe: bool) -> str | None:
    """Why `workers` local worker processes are refused, in words that follow "--workers N:":
    more than the cores this process may run on (default_workers), unless `oversubscribe`
    (--oversubscribe) asks for them; None otherwise. `tegrasp sweep` and the analysis
    scripts ask it alike."""
    cores = default_workers()
    if workers <= cores or oversubscribe:
        return None
    return (f"this machine gives this process {cores} core(s); give at most {cores}, or add "
            f"--oversubscribe to start {workers} workers anyway")


# Resident memory of one worker process running a trial [bytes]: sweep workers hold 250-300 MB
# RSS, and one open-loop `tegrasp trial` process peaks at 333 MB (GNU time's maximum RSS).
WORKER_MEMORY_BYTES = 330e6


def available_memory_bytes() -> float | None:
    """Memory the system can give new processes without swapping [bytes] (Linux's
    MemAvailable; None where it cannot be read)."""
    try:
        with open("/proc/meminfo", encoding="ascii") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def pool_size(workers: int | None, pending: int) -> int:
    """Worker processes for `pending` trials: never more than the trials, nor (for the
    default) more than the available memory holds; SweepError for an explicit `workers`
    whose processes the memory cannot hold."""
    n = min(workers or default_workers(), max(pending, 1))
    available = available_memory_bytes()
    if available is None:
        return n
    fits = max(1, int(available // WORKER_MEMORY_BYTES))
    if n <= fits:
        return n
    if workers is None:
        return fits
    raise SweepError(f"--workers {workers}: {n} worker processes need about "
                     f"{n * WORKER_MEMORY_BYTES / 1e9:.1f} GB (each holds about "
                     f"{WORKER_MEMORY_BYTES / 1e6:.0f} MB) and {available / 1e9:.1f} GB are "
                     f"available; give at most {fits}")


@typing.runtime_checkable
class DaskClient(typing.Protocol):
    """What a sweep uses of a connected `distributed.Client` (connect_scheduler's)."""
    scheduler: typing.Any  # its connection; `.address` the scheduler's

    def submit(self, *args, **kwargs): ...

    def cancel(self, futures): ...


@public_api
def run_sweep(spec: SweepSpec, trial_function: Callable,
              out_dir: Annotated[PathLike, OUTPUT_FOLDER], *,
              workers: Annotated[int | None, WORKER_COUNT] = None,
              scheduler: str | DaskClient | None = None,
              progress: bool = True,
              confirmed_trials: Annotated[int | None, CONFIRMED_TRIALS] = None
              ) -> SweepSummary:
    """Runs the trials of `spec` that have no finished record in `out_dir`.

    `trial_function(trial_dict) -> result_dict`: a picklable module-level callable. `workers`
    defaults to all local cores; `scheduler` runs on that Dask cluster: its address
    ("tcp://host:port", connected to for this sweep) or a client connect_scheduler made (a
    command's one connection, left open for its next sweep).
    ConfigError or SweepError before any trial runs for an invalid spec, a sweep over the
    trial bound that `confirmed_trials` (the count given with --confirm-trials) does not
    cover (checked before its trials are listed) or a folder holding another sweep's records;
    UserPathError (hold_output_folder) when another run is writing there."""
    start = time.perf_counter()
    check_sweep_size(spec, "run_sweep", confirmed_trials)
    trials = [trial.to_dict() for trial in expand_trials(spec)]
    progress_bar = progress_bar_factory(progress)
    try:
        pickle.dumps(trial_function)
    except Exception as error:
        raise SweepError(f"the trial function cannot be sent to worker processes "
                         f"(it must be a module-level function): {error}") from None

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    with hold_output_folder(out_dir):
        remove_stale_staging_files(out_dir, [trial["trial_id"] for trial in trials])
        _tell_earlier_temporary_files(out_dir)
        loaded = load_records(out_dir)
        _tell_files_not_the_sweeps(loaded.others)
        _keep_corrupt_records_aside(loaded.corrupt, {trial["trial_id"] for trial in trials})
        events = _check_records_fit(trials, trial_function, loaded.records, out_dir)
        pending = [trial for trial in trials
                   if loaded.records.get(trial["trial_id"], {}).get("status") != "ok"]
        _check_records_writable(out_dir, pending)
        logger.info(f"sweep: {count_text(len(trials), 'trial')}, "
                    f"{count_text(len(loaded.records), 'record')} read from "
                    f"{out_dir}, {len(pending)} to run")
        if scheduler is None:
            n = pool_size(workers, len(pending))
            backend = f"processes:{n}"
            outcomes = _run_on_process_pool(trial_function, pending, n)
        else:
            backend = f"dask:{_scheduler_address(scheduler)}"
            outcomes = _run_on_dask(trial_function, pending, scheduler)
        logger.info(f"sweep: running {count_text(len(pending), 'trial')} on {backend}")
        ran, errors, unfinished, unwritten_log = _record_outcomes(
            outcomes, pending, out_dir, progress_bar, events)
        logger.info(f"sweep: wrote {ran} trial records in {out_dir} ({len(errors)} errors, "
                    f"{len(unfinished)} unfinished)")
    trial_ids = tuple(trial["trial_id"] for trial in trials)
    return SweepSummary(out_dir=out_dir, total=len(trials),
                        skipped=len(trials) - len(pending), ran=ran, errors=tuple(errors),
                        unfinished=tuple(unfinished),
                        corrupt=tuple(str(path) for path in loaded.corrupt),
                        backend=backend, wall_time_s=time.perf_counter() - start,
                        trial_ids=trial_ids,
                        other_records=len(set(loaded.records) - set(trial_ids)),
                        unwritten_log=unwritten_log)


@contextmanager
def hold_output_folder(out_dir: Path):
    """Holds the output folder for the block (rig.files.held_folder, the lock every run into
    a folder takes, a trial's and a hardware run's too), so a second run into it is refused
    at once; nested holds of one folder in this process (a sensitivity study holding its
    folder across the transfer it runs) share the outer one. UserPathError when another
    holds it: an error outside the run (exit 1), not a refused spec. `out_dir` must exist."""
    with ExitStack() as stack:
        try:
            stack.enter_context(held_folder(out_dir, shared=True))
        except FolderHeldError:
            raise UserPathError(f"{out_dir}: another run (a trial, sweep, transfer or "
                                "sensitivity study) is writing there now; wait for it to end "
                                "or choose another output folder") from None
        yield


def _tell_earlier_temporary_files(out_dir) -> None:
    """Warns of the record temporary files an earlier version left (earlier_temporary_files),
    which stay: a run of that version may still be writing them."""
    left = earlier_temporary_files(out_dir)
    if left:
        logger.warning(f"sweep: {out_dir / TRIALS_FOLDER} holds {len(left)} temporary "
                       f"file(s) of an earlier version ({shorten(left[0].name)}"
                       + (", ..." if len(left) > 1 else "") + "), left by a run killed while "
                       "writing a record; this version neither writes nor reads them: delete "
                       "them once no earlier version's run writes into this folder")


def check_sweep_folder(spec: SweepSpec, trial_function: Callable, out_dir
                       ) -> tuple[int, dict[Path, str], bool]:
    """What run_sweep refuses in `out_dir` before it runs a trial (records made with other
    settings, or matched against other memorized events, for this spec's trial ids), checked
    without writing anything: `tegrasp sweep --dry-run` asks it, so a plan it prints is one
    the real run does not refuse. ConfigError or SweepError, as run_sweep's. Returns what the
    run would do there: the count of trials it would run (those without a finished record, as
    run_sweep counts them), the corrupt records it would set aside ({path: why}), and whether
    another run is writing into the folder now (it holds it: hold_output_folder), whose
    records, each written whole, are read as they stand (a dry run writes nothing)."""
    trials = [trial.to_dict() for trial in expand_trials(spec)]
    if not Path(out_dir).is_dir():
        return len(trials), {}, False  # a new folder: nothing recorded to disagree with
    with ExitStack() as stack:
        try:
            stack.enter_context(held_folder(Path(out_dir), shared=True))
            in_use = False
        except FolderHeldError:
            in_use = True
        loaded = load_records(out_dir)
        _check_records_fit(trials, trial_function, loaded.records, out_dir)
    pending = [trial for trial in trials
               if loaded.records.get(trial["trial_id"], {}).get("status") != "ok"]
    with unprobed_folder_checks():  # nothing made, not even a probe of trials/
        _check_records_writable(out_dir, pending, set_aside=loaded.corrupt)
    return len(pending), dict(loaded.corrupt), in_use


def _check_records_writable(out_dir, pending, set_aside=()) -> None:
    """SweepError naming the trials folder when this user cannot write in it (folder_problem),
    or the first record of the `pending` trials that could not be written
    (unwritable_records: a folder in its place, `trials` not a folder), before any trial runs:
    run_sweep's check, and check_sweep_folder's for a dry run. `set_aside`: the corrupt records
    a run moves away first (not there once it writes)."""
    folder = Path(out_dir) / TRIALS_FOLDER
    problem = (pending or set_aside) and not non_folder_on_path(folder) and folder_problem(folder)
    if problem:  # (a file as trials/ is said per record below)
        raise RecordPlaceError(f"the trial records cannot be written: {problem}; give a "
                               "folder you can write; nothing was run")
    set_aside = {Path(path) for path in set_aside if _set_aside(Path(path))}
    unwritable = [(path, problem) for path, problem in
                  unwritable_records(out_dir, [trial["trial_id"] for trial in pending])
                  if Path(path) not in set_aside]
    if unwritable:
        path, problem = unwritable[0]
        more = f" (and {len(unwritable) - 1} more)" if len(unwritable) > 1 else ""
        raise RecordPlaceError(f"the record {path} {problem}{more}; nothing was run")


def _check_records_fit(trials, trial_function, records, out_dir) -> dict[str, dict | None]:
    """The trials' memorized-event identities (trial_events_identities), after refusing
    `records` made for the same ids with other settings or other events."""
    _check_same_sweep(trials, records, out_dir)
    _check_one_study(trials, records, out_dir)
    events = trial_events_identities(trial_function, trials)
    _check_same_events(events, records, out_dir)
    return events


def _check_one_study(trials, records, out_dir) -> None:
    """SweepError when the folder's records and this sweep's trials are not of one study
    (mixed_study_problem: another grid, base seed, noise, overrides, object definition or scene
    draw, under other trial ids): the folder's readers would refuse it once run."""
    problem = mixed_study_problem(records.values(), out_dir)
    if problem is None:
        planned = [{"trial_id": trial["trial_id"], "trial": trial} for trial in trials]
        problem = mixed_study_problem([*records.values(), *planned], out_dir)
        if problem is not None:
            problem += " (the second is this sweep's, not yet run)"
    if problem is not None:
        raise SweepError(f"{problem}; nothing was run")


def _check_same_sweep(trials, records, out_dir):
    """Refuses a folder whose records were made with other settings for the same ids."""
    from tegrasp_drake.scenario.moved_keys import migrate_stored_trial
    for trial in trials:
        record = records.get(trial["trial_id"])
        recorded = None if record is None else record["trial"]
        if recorded is not None and recorded.get("object_definition"):
            # A user object recorded with its old field names (spec.user_object).
            recorded = TrialSpec.from_dict(recorded).to_dict()
        if recorded is not None:  # scenario_overrides recorded with keys since moved
            recorded = migrate_stored_trial(recorded)
        if recorded is not None and canonical_json(recorded) != canonical_json(trial):
            raise SweepError(
                f"{out_dir} holds a record of trial {trial['trial_id']} made with other "
                "settings (seed, grid offsets, randomisation or scenario overrides differ); "
                "resume with the same spec, or choose another output folder")


def trial_events_identities(trial_function, trials) -> dict[str, dict | None]:
    """{trial id: the memorized events it matches against} when the trial function says which
    (an `events_identities(trials, events_dir)` attribute, as run_trial_from_spec's; the
    events_dir bound to it, bound_arguments, is the folder it reads); else every one None."""
    function, keywords = trial_function, {}
    if isinstance(trial_function, functools.partial):
        function, keywords = trial_function.func, trial_function.keywords
    identities = getattr(function, "events_identities", None)
    if identities is None:
        return {trial["trial_id"]: None for trial in trials}
    return identities(trials, keywords.get("events_dir"))


def _check_same_events(events: dict, records: dict, out_dir) -> None:
    """Refuses a folder whose finished records matched against other memorized events than
    `events` ({trial id: identity}) says this sweep's trials will: their content hashes
    differ (a copy of the same events in another folder is the same). A record written before
    records named their events (format 1) cannot be checked: one warning says how many."""
    unknown = 0
    for trial_id, identity in events.items():
        record = records.get(trial_id)
        if record is None or record["status"] != "ok" or identity is None:
            continue  # an error record runs again, with this sweep's events
        recorded = record.get("events")
        if recorded is None:
            unknown += 1
        elif recorded["sha256"] != identity["sha256"]:
            raise SweepError(
                f"{out_dir} holds a record of trial {trial_id} made with other memorized "
                f"events ({events_words(recorded)}) than this sweep's "
                f"({events_words(identity)}); resume with the same events (--events), or "
                "choose another output folder")
    if unknown:
        logger.warning(f"{out_dir}: {unknown} finished record(s) do not name the memorized "
                       "events they matched against (written before records did); they are "
                       "kept, unchecked against this sweep's events")


def _record_outcomes(outcomes, pending, out_dir, progress_bar, events):
    """Writes each finished trial's record as it arrives, naming its memorized `events`
    ({trial id: identity}); returns (ran, errors, unfinished, unwritten log).

    A trial whose log copy could not be written ("PATH: reason") is recorded with its result
    and ends the sweep there: the other trials are left unfinished for the next run rather
    than spend their CPU on logs the full or unwritable --logs folder would lose too."""
    by_id = {trial["trial_id"]: trial for trial in pending}
    finished, errors, unwritten_log = set(), [], None
    # closing(): an interrupt shuts the backend down here, not at garbage collection.
    with closing(outcomes), progress_bar(len(pending)) as bar:
        for trial_id, outcome in outcomes:
            if outcome is None:
                continue  # The worker died: no record, the next run retries it.
            status, payload, unwritten_log = outcome
            trial = by_id[trial_id]
            try:
                record = (make_record(trial, result=payload, events=events[trial_id])
                          if status == "ok"
                          else make_record(trial, error=payload, events=events[trial_id]))
            except RecordError as error:
                record = make_record(trial, error={"type": "RecordError",
                                                   "message": str(error), "traceback": ""},
                                     events=events[trial_id])
            write_record(out_dir, record)
            finished.add(trial_id)
            if record["status"] == "error":
                errors.append(trial_id)
            bar.update(1)
            if unwritten_log is not None:
                break  # closing(outcomes) ends the workers; their trials stay unfinished
    unfinished = [trial["trial_id"] for trial in pending if trial["trial_id"] not in finished]
    return len(finished), sorted(errors), unfinished, unwritten_log


class _NoProgressBar:
    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        return False

    def update(self, n):
        pass


def progress_bar_factory(enabled, *, description: str = "sweep", unit: str = "trial"):
    """A function total -> progress bar (tqdm, with rate and ETA) of `description`, counting
    `unit`s (a sweep's trials, a study's recordings), checked up front."""
    if not enabled:
        return lambda total: _NoProgressBar()
    try:
        from tqdm import tqdm
    except ImportError:
        raise SweepError("the progress bar needs tqdm, a dependency of tegrasp-drake: "
                         "install it, or run without a progress bar") from None
    return lambda total: tqdm(total=total, desc=description, unit=unit, dynamic_ncols=True)


def worker_context(trial_function) -> multiprocessing.context.BaseContext:
    """The start method of a sweep's worker processes: a fork server, which imports the main
    module, this one (and with it pydrake) and `trial_function`'s module once and forks each
    worker from that state, where the platform has one; else spawn, which imports them in
    every worker. A fresh worker then starts in about 0.1 s instead of the 3-5 s an import of
    pydrake takes, the time a short sweep (or a resumed one with few trials left) spent
    mostly in starting workers. The server forks before any simulation has run: it has no
    thread of Drake's (LCM, Meshcat) for a forked child to lose. The list takes effect when
    the server starts, at the first sweep of this process; later sweeps share that server
    and import any other trial function's module in the worker."""
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    module = getattr(trial_function, "__module__", None)
    preload = ["__main__", __name__] + ([module] if module and module != "__main__" else [])
    context.set_forkserver_preload(preload)
    return context


def _run_on_process_pool(trial_function, pending, workers):
    """Yields (trial_id, outcome) as trials finish (None if the worker died). When the caller
    stops early (Ctrl-C, SIGTERM, closing this generator) the workers end at once and their
    trials are abandoned without a record, for the resumed sweep."""
    if not pending:
        return
    with _hangup_held_from_helpers():
        executor = ProcessPoolExecutor(max_workers=workers,
                                       mp_context=worker_context(trial_function),
                                       initializer=end_with_parent, initargs=(os.getpid(),))
    finished = False
    try:
        with _hangup_held_from_helpers():
            futures = {executor.submit(run_trial_safely, trial_function, trial):
                       trial["trial_id"] for trial in pending}
        for future in as_completed(futures):
            try:
                outcome = future.result()
            except Exception:  # BrokenProcessPool: a worker died; no trial result.
                outcome = None
            yield futures[future], outcome
        finished = True
    finally:
        if not finished:
            _end_workers(executor)
        executor.shutdown(wait=True, cancel_futures=True)


@contextmanager
def _hangup_held_from_helpers():
    """SIGHUP blocked in this thread while the pool's helper processes start (the workers,
    multiprocessing's fork server and resource tracker), which keep the blocked mask. A
    terminal that closes sends SIGHUP to its whole process group: the tracker, which ignores
    only SIGINT and SIGTERM, died of it and was relaunched during the pool's clean-up with
    none of the semaphores it is then told to release, printing a traceback for each. This
    process takes a SIGHUP that came meanwhile when the block ends (a run ends on it as on
    Ctrl-C, rig/files); the helpers end with it (_end_workers, end_with_parent)."""
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGHUP})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _end_workers(executor: ProcessPoolExecutor) -> None:
    """Ends a pool's workers now (SIGKILL: only the main process writes records)."""
    for process in list((getattr(executor, "_processes", None) or {}).values()):
        with suppress(OSError, ValueError):
            process.kill()


PARENT_CHECK_PERIOD_S = 0.5


def end_with_parent(parent_pid: int) -> None:
    """A pool worker's initializer: the worker exits (os._exit) once the main process
    `parent_pid` is gone, however it died; on Linux PR_SET_PDEATHSIG also kills it when the
    fork server exits."""
    import ctypes
    import threading
    try:
        libc = ctypes.CDLL("libc.so.6", use_errno=True)
        libc.prctl(1, 9)  # PR_SET_PDEATHSIG, SIGKILL
    except (OSError, AttributeError):
        pass

    def watch():
        while True:
            time.sleep(PARENT_CHECK_PERIOD_S)
            try:
                os.kill(parent_pid, 0)
            except ProcessLookupError:
                os._exit(1)
            except PermissionError:
                pass  # alive, someone else's (cannot happen for our parent)
    threading.Thread(target=watch, name="end with the sweep", daemon=True).start()


def _dask_distributed():
    """The `distributed` module; SweepError naming the extra to install when it is missing."""
    try:
        import distributed
    except ImportError:
        raise SweepError("--scheduler needs the optional Dask extra: "
                         "pip install 'tegrasp-drake[dask]'") from None
    return distributed


def scheduler_address(text: str) -> str:
    """`text`, a Dask scheduler's address, as a URL: HOST:PORT (no PROTOCOL://) is
    tcp://HOST:PORT, as distributed reads it; any other text as given."""
    return text if "://" in text or not text.strip() else f"tcp://{text}"


# [s] the most a scheduler's host name may take to resolve: a resolver that says nothing
# for this long will not (glibc's default: 5 s a try, 2 tries).
DASK_RESOLVE_BOUND_S = 10.0


def _tcp_reach_problem(address: str) -> str | None:
    """Why nothing can be reached at `address`, a tcp://HOST:PORT URL, in words, or None
    (another protocol, or something there accepts a connection): a HOST that does not
    resolve within DASK_RESOLVE_BOUND_S, a port where nothing listens (refused at once), no
    answer within DASK_CONNECT_TIMEOUT_S. distributed retries each of these until its own
    timeout; this says it at once, or after one try. Each step runs on a daemon thread,
    abandoned when its bound passes (the resolver's call cannot be interrupted)."""
    import socket
    import urllib.parse
    if not address.startswith("tcp://"):
        return None
    try:
        parts = urllib.parse.urlsplit(address)
        host, port = parts.hostname, parts.port
    except ValueError:
        return None  # the address's form is the command line's to check
    if host is None or port is None:
        return None

    def bounded(call, bound: float):
        done = {}

        def run():
            try:
                done["value"] = call()
            except OSError as error:
                done["error"] = error
        thread = threading.Thread(target=run, name="tegrasp-dask-reach", daemon=True)
        thread.start()
        thread.join(bound)
        return done if not thread.is_alive() else None

    found = bounded(lambda: socket.getaddrinfo(host, port, type=socket.SOCK_STREAM),
                    DASK_RESOLVE_BOUND_S)
    if found is None:
        return f"the host name {host} did not resolve within {DASK_RESOLVE_BOUND_S:.0f} s"
    if "error" in found:
        reason = found["error"].strerror or found["error"]
        return f"the host name {host} does not resolve ({reason})"

    def connect():
        with socket.create_connection((host, port), timeout=DASK_CONNECT_TIMEOUT_S):
            return True
    connected = bounded(connect, DASK_CONNECT_TIMEOUT_S + 1.0)
    if connected is None or isinstance(connected.get("error"), socket.timeout):
        return f"nothing answered on port {port} within {DASK_CONNECT_TIMEOUT_S:.0f} s"
    error = connected.get("error")
    if isinstance(error, ConnectionRefusedError):
        return f"nothing listens on port {port} (connection refused)"
    if error is not None:
        return f"{os_error_text(error)}"
    return None


def connect_scheduler(scheduler: str,
                      announce: Callable[[], None] | None = None) -> DaskClient:
    """A Client of the Dask scheduler at `scheduler` (its protocol read in any case; HOST:PORT
    without one is tcp://: scheduler_address);
    SweepError when the extra is missing,
    the address cannot be reached (_tcp_reach_problem: an unknown host or a refused port said
    at once), or what answers there is not a Dask scheduler (any error of the handshake),
    all within DASK_ANSWER_BOUND_S of wall time. `announce` is called once
    the extra is known to be installed, just before connecting (a command says there what it
    connects to: an address where nothing listens takes the whole bound). A command connects once,
    before its first trial or event recording, and hands the client to each sweep it runs
    (run_sweep's `scheduler`); the caller closes it.

    distributed's own `timeout` bounds the TCP connect, not every read of the handshake: a
    peer that accepts and stays silent held the Client forever. The Client is made on a
    daemon thread, abandoned (with its socket) when the bound passes."""
    distributed = _dask_distributed()
    if announce is not None:
        announce()
    made, started = {}, time.monotonic()
    protocol, separator, rest = scheduler_address(scheduler).partition("://")
    address = protocol.lower() + separator + rest  # distributed knows "tcp", not "TCP"
    problem = _tcp_reach_problem(address)
    if problem:
        raise SweepError(f"cannot reach the Dask scheduler at {scheduler}: {problem}; start "
                         "`dask scheduler` there, or give the address it prints")

    def make_client():
        try:
            made["client"] = distributed.Client(address, timeout=f"{DASK_CONNECT_TIMEOUT_S}s")
        except Exception as error:  # the peer's answer decides what is raised: any of them
            made["error"] = error
    connecting = threading.Thread(target=make_client, name="tegrasp-dask-connect",
                                  daemon=True)
    connecting.start()
    connecting.join(max(DASK_ANSWER_BOUND_S - (time.monotonic() - started), 1.0))
    if connecting.is_alive():
        raise SweepError(f"the Dask scheduler at {scheduler} did not answer as one within "
                         f"{DASK_ANSWER_BOUND_S:.0f} s: give the address `dask scheduler` "
                         "prints")
    error = made.get("error")
    if isinstance(error, OSError):
        raise SweepError(f"cannot reach the Dask scheduler at {scheduler}: {error}")
    if error is not None:
        raise SweepError(f"what answers at {scheduler} is not a Dask scheduler "
                         f"({_handshake_problem(error)}): give the address `dask scheduler` "
                         "prints")
    return made["client"]


def _handshake_problem(error: Exception) -> str:
    """What went wrong in a Dask handshake, in words that follow "is not a Dask scheduler":
    bytes that do not decode as Dask's frames (a length of 2^62 bytes that numpy cannot
    allocate, a shape or a value out of range) are no Dask reply, whatever distributed's
    decoder raised for them; any other error is named with its type."""
    if isinstance(error, (MemoryError, OverflowError, ValueError, struct.error)):
        return "its reply is not Dask's protocol"
    return f"{type(error).__name__}: {shorten(str(error))}"


# The loggers distributed configures (dask's `logging` config) and tornado's under them.
_DASK_LOGGERS = ("distributed", "tornado")


def hold_dask_logs() -> Callable[[], None]:
    """Silences distributed's and tornado's loggers (their tracebacks while a client
    reconnects to a scheduler that went away, and while it closes); returns the function
    that gives them their levels back. A command holds them from connecting to closing its
    client unless asked for debug output (-vv): what it needs to say, it says in one line
    (SchedulerLostError, a trial unfinished)."""
    names = [name for name in logging.root.manager.loggerDict
             if name.split(".")[0] in _DASK_LOGGERS] + list(_DASK_LOGGERS)
    levels = {name: logging.getLogger(name).level for name in names}
    for name in names:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)

    def restore():
        for name, level in levels.items():
            logging.getLogger(name).setLevel(level)
    return restore


def _scheduler_address(scheduler: str | DaskClient) -> str:
    return (scheduler_address(scheduler) if isinstance(scheduler, str)
            else scheduler.scheduler.address)


def _run_on_dask(trial_function, pending, scheduler: str | DaskClient):
    """Yields (trial_id, outcome) from a Dask cluster; outcome None if workers died.
    `scheduler`: a connected client (left open), or an address connected to here (and
    closed at the end)."""
    if not pending:
        return
    address = _scheduler_address(scheduler)
    with (connect_scheduler(scheduler) if isinstance(scheduler, str)
          else nullcontext(scheduler)) as client:
        # A key of its own for each submission: a transfer's cells share trial ids, and a key
        # the previous cell's futures were just cancelled under could cancel the next's.
        futures = {client.submit(run_trial_safely, trial_function, trial, pure=False,
                                 key=f"tegrasp-trial-{trial['trial_id']}-{uuid.uuid4().hex}"):
                   trial["trial_id"] for trial in pending}
        finished = 0
        try:
            for future in _as_completed_saying_when_no_workers(client, list(futures),
                                                               address):
                try:
                    outcome = future.result()
                except Exception:  # KilledWorker and kin: no trial result.
                    if client.status != "running":  # its futures were cancelled with it
                        raise SchedulerLostError(
                            f"lost the Dask scheduler at {address} after "
                            f"{finished} of {len(futures)} trials: the finished ones are "
                            "recorded; start the scheduler and its workers again and run the "
                            "same command to run the rest") from None
                    outcome = None
                finished += outcome is not None
                yield futures[future], outcome
        finally:
            with suppress(Exception):  # a client whose scheduler is gone cannot cancel
                client.cancel(list(futures))


# How long a scheduler may have no worker while trials wait before a sweep says so [s]. A
# `dask worker` registers within about a second of starting (importing distributed, then a
# connect and a registration message), a LocalCluster's or a batch system's several within a
# few; ten seconds lets those in without a word and is still short beside a trial (tens of
# seconds) for a user waiting for output.
NO_WORKERS_NOTICE_S = 10.0
# How often the submitting thread looks for finished trials, and asks the scheduler how many
# workers it has (one small message), while none has finished [s]. distributed's own
# as_completed iterator looks every 0.1 s; a trial takes tens of seconds.
DASK_LOOK_PERIOD_S = 0.2
WORKER_COUNT_PERIOD_S = 1.0


def _as_completed_saying_when_no_workers(client, futures: list, address: str):
    """Yields `futures` one at a time as they finish (distributed's as_completed, looked at
    without blocking). Between looks, this thread (the only one that uses the client) asks
    the scheduler every WORKER_COUNT_PERIOD_S how many workers it has; after
    NO_WORKERS_NOTICE_S with none it warns once, in one line, and keeps waiting: workers may
    still come, and Ctrl-C stops the sweep with its finished trials kept. Workers that join
    and leave again start the count afresh."""
    completed = _dask_distributed().as_completed(futures, loop=client.loop)
    none_since = asked_at = None
    said = False
    while not completed.is_empty():
        ready = completed.next_batch(block=False)
        yield from ready
        if ready:
            continue
        now = time.monotonic()
        if asked_at is None or now - asked_at >= WORKER_COUNT_PERIOD_S:
            asked_at = now
            workers = _worker_count(client)
            if workers:
                none_since, said = None, False
            elif workers == 0:
                none_since = now if none_since is None else none_since
        if not said and none_since is not None and now - none_since >= NO_WORKERS_NOTICE_S:
            said = True
            logger.warning(
                f"sweep: the Dask scheduler at {address} has had no worker for "
                f"{now - none_since:.0f} s (none has connected, or the last one left); "
                f"{count_text(completed.count(), 'trial')} waiting: start one with `dask "
                f"worker {address}`, or stop with Ctrl-C (finished trials are kept; the same "
                "command runs the rest)")
        time.sleep(DASK_LOOK_PERIOD_S)


def _worker_count(client) -> int | None:
    """How many workers the client's scheduler has; None when it cannot say (gone or
    reconnecting: the futures' cancellation then says so, SchedulerLostError)."""
    if client.status != "running":
        return None
    try:
        return int(client.scheduler_info(n_workers=0)["n_workers"])
    except Exception:  # any failure of the one message: ask again next time
        return None


def _tell_files_not_the_sweeps(others) -> None:
    """Warns, one line each, of the files under trials/ whose names are no trial's record
    (records.record_name_trial_id): a user's files, which the sweep neither reads, renames
    nor counts."""
    for path in others:
        logger.warning(f"sweep: {path}: its name is no trial's record (records are named "
                       "CONTROLLER.OBJECT.MARKER.aK.json), so it is not the sweep's; left "
                       "alone as it is")


def _keep_corrupt_records_aside(corrupt: dict, trial_ids=None) -> None:
    """Renames each corrupt record (a file named as a trial's record) to NAME.corrupt-<pid>
    beside it (its trial then runs again into NAME), saying so in one line each before
    anything runs: nothing silent, nothing lost. One of a trial not in `trial_ids` (this
    sweep's; another spec's in a shared folder) is set aside too, said to be run again by a
    sweep of its spec. A FIFO or a link (to a device) in a record's place is renamed as a file
    is (the entry, not what it points to); a folder there is left for the write check, which
    refuses the sweep before it runs anything."""
    for path, reason in corrupt.items():
        if not _set_aside(path):
            continue
        kept = path.with_name(f"{path.name}.corrupt-{os.getpid()}")
        os.replace(path, kept)
        trial_id = record_name_trial_id(path.name)
        if trial_ids is None or trial_id in trial_ids:
            logger.warning(f"sweep: {path}: {reason}; kept as {kept.name}, its trial is "
                           "re-run")
        else:
            logger.warning(f"sweep: {path}: {reason}; kept as {kept.name}; its trial, "
                           f"{trial_id}, is not in this sweep: a sweep of the spec that has it "
                           "runs it again")


def _set_aside(path: Path) -> bool:
    """Whether _keep_corrupt_records_aside moves the corrupt record `path` away: all but a
    folder, which no record can replace."""
    return not (path.is_dir() and not path.is_symlink())


def summary_text(summary: SweepSummary) -> str:
    lines = [f"sweep: {count_text(summary.total, 'trial')}, {summary.skipped} already "
             f"finished, {summary.ran} run now on {summary.backend} in {summary.wall_time_s:.1f} s"]
    if summary.other_records:
        lines.append(f"  {summary.other_records} record(s) of trials not in this spec are in "
                     f"{summary.out_dir} (another spec's); the reports count only this "
                     "spec's trials")
    if summary.corrupt:
        lines.append(f"  {len(summary.corrupt)} corrupt record(s) kept as NAME.corrupt-<pid> "
                     "and re-run: "
                     + ", ".join(summary.corrupt))
    if summary.errors:
        lines.append(f"  {len(summary.errors)} trial(s) raised (error records; re-run on "
                     "the next run): " + _trial_ids_text(summary.errors))
    if summary.unfinished:
        why = ("the sweep stopped where a trial's log could not be written (the error line)"
               if summary.unwritten_log is not None else "a worker died")
        lines.append(f"  {len(summary.unfinished)} trial(s) unfinished because {why}, not "
                     f"recorded: {_trial_ids_text(summary.unfinished)}; run the same command "
                     "again (the same --out) to run them")
    return "\n".join(lines)


def _trial_ids_text(trial_ids, shown: int = 10) -> str:
    """The first `shown` trial ids, comma-separated, "..." after them if there are more."""
    return ", ".join(trial_ids[:shown]) + (" ..." if len(trial_ids) > shown else "")


# Result fields that measure the machine, not the trial.
TIMING_FIELDS = ("wall_time_s", "cpu_time_s", "real_time_factor")


@dataclass(frozen=True)
class BenchmarkRun:
    workers: int
    trials: int
    errors: int
    wall_time_s: float
    unwritten_log: str | None = None  # as SweepSummary's: this run stopped there


BENCHMARK_WORKER_COUNTS = (1, 2)


def benchmark_spec(spec: SweepSpec) -> SweepSpec:
    """The sweep a benchmark of `spec` times: its memorized controller's trials."""
    return dataclasses.replace(spec, controllers=("memorized",))


def run_benchmark(spec: SweepSpec, trial_function, *, worker_counts=BENCHMARK_WORKER_COUNTS,
                  progress: bool = True) -> tuple[list[BenchmarkRun], bool]:
    """Runs the memorized sweep of `spec` once per worker count, each into a fresh temporary
    folder, timed whole (pool start-up included); returns the runs and whether every result
    was the same in all (TIMING_FIELDS aside): the worker count must not change a result.
    A run that could not write a trial's log copy (SweepSummary.unwritten_log) is the last."""
    spec = benchmark_spec(spec)
    runs, results = [], []
    for workers in worker_counts:
        with tempfile.TemporaryDirectory(prefix="tegrasp-benchmark-") as folder:
            summary = run_sweep(spec, trial_function, folder, workers=workers,
                                progress=progress)
            records = load_records(folder).records
        runs.append(BenchmarkRun(workers=workers, trials=summary.ran,
                                 errors=len(summary.errors), wall_time_s=summary.wall_time_s,
                                 unwritten_log=summary.unwritten_log))
        results.append({trial_id: canonical_json(
            {k: v for k, v in (record["result"] or record["error"]).items()
             if k not in TIMING_FIELDS + ("traceback",)})
            for trial_id, record in records.items()})
        if summary.unwritten_log is not None:
            break
    return runs, all(r == results[0] for r in results)


def benchmark_text(runs: list[BenchmarkRun], identical: bool) -> str:
    base = runs[0].wall_time_s
    lines = ["benchmark: memorized sweep, workers / trials / wall time / trials per s / "
             "speed-up"]
    for run in runs:
        lines.append(f"  {run.workers:>2} worker(s): {run.trials} trials, "
                     f"{run.wall_time_s:.2f} s, {run.trials / run.wall_time_s:.2f} trials/s, "
                     f"speed-up {base / run.wall_time_s:.2f}x"
                     + (f" ({run.errors} errors)" if run.errors else ""))
    lines.append("  results identical across worker counts: " + ("yes" if identical else "NO"))
    return "\n".join(lines)
