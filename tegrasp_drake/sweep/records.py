"""Durable per-trial records: one checksummed JSON file per trial.

`<out>/trials/<controller>.<object>.<marker>.a<k>.json` (the trial id, '/' as '.') holds:

    format          "tegrasp-sweep-record"
    format_version  1
    trial_id        the trial's id
    status          "ok" (the trial function returned) or "error" (it raised)
    trial           TrialSpec.to_dict(): the scene, seeds and perturbation
    result          the trial function's result dict, or null for an error
    error           null, or {"type", "message", "traceback"} for an error
    checksum        "sha256:" + hex digest of the canonical JSON of all other fields

Canonical JSON: sorted keys, no spaces, ASCII, no NaN/Infinity. Written to a temporary file,
fsync'ed, renamed into place, the folder fsync'ed: a crash leaves no record or a whole one.
A record that fails to parse or to checksum, whose trial is not one a sweep makes
(spec.trial_problem: TrialSpec's fields, their ranges and relations), or whose result is not a
TrialResult's JSON form (TrialResult.from_dict: its fields' ranges and the relations between
them), is corrupt, and its trial runs again."""

import contextlib
import contextvars
import hashlib
import json
import os
import re
from typing import Annotated
from dataclasses import dataclass
from pathlib import Path

from tegrasp_drake.rig.files import (JSON_OBJECT_START, JsonFileError, UserPathError,
                                     folder_entries, read_error_remedy, read_json_file,
                                     remove_stale_staging_files_in, replace_problem,
                                     write_atomically)
from tegrasp_drake.rig.api_boundary import INPUT_FOLDER, PathLike, public_api
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_entry
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.scenario.object_placement import result_offset_problem
from tegrasp_drake.sweep.spec import TrialSpec, offset_key, trial_problem

RECORD_FORMAT = "tegrasp-sweep-record"
# Version 2 adds "events", what the trial matched against (make_record); a version-1 record
# (without it) is read as it is, its events unknown.
RECORD_FORMAT_VERSION = 2
TRIALS_FOLDER = "trials"
# How earlier versions named a record's temporary file (tempfile's `.NAME.XXXXXXXX.tmp`): no
# writer's process id, so a killed writer's cannot be told from a live one's.
_EARLIER_TEMPORARY = re.compile(r"\..+\.json\.[a-z0-9_]{8}\.tmp", re.DOTALL)
# A record is one trial's result, a few kB (its transitions and scores); more is not one.
MAX_RECORD_BYTES = 1_000_000
_RECORD_FIELDS_V1 = {"format", "format_version", "trial_id", "status", "trial", "result",
                     "error", "checksum"}
_RECORD_FIELDS = {1: _RECORD_FIELDS_V1, 2: _RECORD_FIELDS_V1 | {"events"}}


class RecordError(ValueError):
    """A record cannot be built or written (for example a result that is not JSON)."""


@dataclass(frozen=True)
class LoadedRecords:
    """The records of a results folder: valid ones by trial id, corrupt ones by path (files
    named as a trial's record, record_name_trial_id), and `others`, the .json files under
    trials/ whose names are no trial's record (a user's file): not the sweep's, left alone."""
    records: dict[str, dict]
    corrupt: dict[Path, str]
    others: tuple[Path, ...] = ()

    def corrupt_problem(self, out_dir) -> str | None:
        """Why a table or figure may not be made from this folder's records, or None: a
        corrupt record is a trial the table would silently lose (Table I of 242 trials
        presented as the sweep's 243), so every reader of a sweep folder refuses it alike."""
        if not self.corrupt:
            return None
        path, reason = next(iter(self.corrupt.items()))
        return (f"{len(self.corrupt)} corrupt trial record(s) in {out_dir} (first: {path}: "
                f"{reason}); a table or figure without them would be wrong: `tegrasp sweep "
                f"--out {out_dir}` with the sweep's options runs them again")

    def table_problem(self, out_dir) -> str | None:
        """Why a table or figure may not be made from this folder's records, or None: a
        corrupt record (corrupt_problem), or records that are not one study's
        (mixed_records_problem)."""
        return (self.corrupt_problem(out_dir)
                or mixed_records_problem(self.records.values(), out_dir))


def mixed_records_problem(records, out_dir=None) -> str | None:
    """Why `records` (valid records) may not be counted together, or None: they are records
    of different sweeps (mixed_study_problem) or one row of Table I mixes memorized events
    (mixed_events_problem). The one check every reader of a results folder makes."""
    records = list(records)
    return mixed_study_problem(records, out_dir) or mixed_events_problem(records, out_dir)


def events_words(events: dict | None) -> str:
    """A record's events in words: their hash's first 12 hex digits and the folder."""
    if events is None:
        return "none"
    folder = events["folder"] or "your events folder, then the package's"
    return f"sha256 {events['sha256'][:12]}... from {folder}"


def mixed_events_problem(records, out_dir=None) -> str | None:
    """Why `records` (valid records) may not be counted together, or None: two records of one
    controller on one object (a row of Table I) that matched against different memorized
    events (their "events" sha256 differ). Each object has its own events and each controller
    reads its own folder's, so records differ there only between rows; a record that names
    no events (a controller that reads none, or a format-1 record) is not compared."""
    first = {}  # (controller, object) -> the first record naming its events
    for record in records:
        events = record.get("events")
        if events is None:
            continue
        key = (record["trial"]["controller"], record["trial"]["object_name"])
        other = first.setdefault(key, record)
        if other["events"]["sha256"] != events["sha256"]:
            where = f"{out_dir}: " if out_dir is not None else ""
            names = [f"{TRIALS_FOLDER}/{record_file_name(r['trial_id'])}"
                     for r in (other, record)]
            return (f"{where}records {names[0]} and {names[1]} ({key[0]} on '{key[1]}') "
                    f"matched against different memorized events ({events_words(other['events'])}; "
                    f"{events_words(events)}), and a table counting both would mix them: keep "
                    "the records of one events set in a folder (run the sweep again into "
                    "another --out with one --events)")
    return None


# The fields of a record's trial that one sweep gives every trial alike (its spec's base_seed,
# randomisation.sensor_noise and scenario_overrides); absent scenario_overrides are none.
_SWEEP_FIELDS = (("base_seed", None), ("sensor_noise", None), ("scenario_overrides", []))


def _study_trial(trial: dict) -> dict:
    """A record's trial as this version names its fields: a user object's old field names
    (spec.user_object) and scenario_overrides keys since moved (moved_keys), as a resumed
    sweep reads them, so that records of one sweep written by two versions agree."""
    from tegrasp_drake.scenario.moved_keys import migrate_stored_trial
    if trial.get("object_definition"):
        trial = TrialSpec.from_dict(trial).to_dict()
    return migrate_stored_trial(trial)


def _sweep_identities(trial: dict):
    """(what, key, value, subject) of each thing of a trial that every record of its sweep
    with the same `what` and `key` gives the same `value`: the sweep's own fields
    (_SWEEP_FIELDS); a marker's offset and an offset's marker (the grid: marker_names); an
    object's definition; a scene's draw (pair_id: seed and perturbation, drawn under the
    sweep's randomisation), which every controller meets alike. `subject` names it."""
    offset = [trial["marker_dx_m"], trial["marker_dy_m"]]
    for name, absent in _SWEEP_FIELDS:
        yield name, None, trial.get(name, absent), f"field 'trial.{name}' is"
    yield ("marker", trial["marker"], offset_key(offset),
           f"marker {trial['marker']} (fields 'trial.marker_dx_m', 'trial.marker_dy_m') lies at")
    yield ("offset", offset_key(offset), trial["marker"],
           f"the marker offset {shown(offset)} m (field 'trial.marker') is")
    yield ("object", trial["object_name"], trial["object_definition"],
           f"object '{trial['object_name']}' (field 'trial.object_definition') is")
    yield ("scene", trial["pair_id"], [trial["seed"], trial["perturbation"]],
           f"scene {trial['pair_id']} (fields 'trial.seed', 'trial.perturbation', drawn "
           "under the sweep's randomisation) is")


def _identity_value(what: str, value, trial: dict) -> str:
    """A trial's `value` of the identity `what` (_sweep_identities), in words."""
    if what == "marker":
        return f"{shown([trial['marker_dx_m'], trial['marker_dy_m']])} m"
    if what == "offset":
        return f"marker {value}"
    if what == "object":
        return "the built-in one" if value is None else shorten(repr(value))
    if what == "scene":
        return f"seed {value[0]}, perturbation {shorten(canonical_json(value[1]), 120)}"
    return shorten(repr(value))


def mixed_study_problem(records, out_dir=None) -> str | None:
    """Why `records` (valid records) are not the records of one sweep, or None: two of them
    disagree on what the sweep gives its trials alike (_sweep_identities): the base seed,
    sensor noise or scenario overrides; where a marker lies, or which marker an offset is
    (records of two grids, whose marker names mean other offsets); an object's definition;
    or a scene's seed and perturbation. A table or map counts records by marker and pair,
    so records of two sweeps copied into one folder would be counted as one study's."""
    first = {}  # (what, key) -> (canonical value, the first record giving it, its words)
    for record in records:
        trial = _study_trial(record["trial"])
        for what, key, value, subject in _sweep_identities(trial):
            text = canonical_json(value)
            seen = first.setdefault((what, key),
                                    (text, record, subject, _identity_value(what, value, trial)))
            if seen[0] == text:
                continue
            where = f"{out_dir}: " if out_dir is not None else ""
            names = [f"{TRIALS_FOLDER}/{record_file_name(r['trial_id'])}"
                     for r in (seen[1], record)]
            return (f"{where}records {names[0]} and {names[1]} are not of one sweep: "
                    f"{seen[2]} {seen[3]} in one, {_identity_value(what, value, trial)} in the "
                    "other; a table or map counting both would mix two studies: keep each "
                    "sweep's records in a folder of their own (its `tegrasp sweep --out`)")
    return None


def record_file_name(trial_id: str) -> str:
    return trial_id.replace("/", ".") + ".json"


# A record's file name: its trial id CONTROLLER/OBJECT/MARKER/aK with '/' as '.' (none of
# the four parts holds a '.': controller and object names are letters, digits, '_' and '-').
_RECORD_NAME = re.compile(r"([A-Za-z0-9_-]+)\.([A-Za-z0-9_-]+)\.(m[0-9]+)\.(a[0-9]+)\.json",
                          re.ASCII)


def record_name_trial_id(name: str) -> str | None:
    """The trial id a record of this file name would hold, or None: a name of no trial's
    record, which no sweep writes (a user's file in trials/)."""
    match = _RECORD_NAME.fullmatch(name)
    return "/".join(match.groups()) if match else None


def record_path(out_dir, trial_id: str) -> Path:
    return Path(out_dir) / TRIALS_FOLDER / record_file_name(trial_id)


def unwritable_records(out_dir, trial_ids) -> list[tuple[Path, str]]:
    """(path, why) of each of these trials' records that write_record could not put in place (a
    folder where it belongs): asked before the trials run, whose results would otherwise be lost."""
    problems = []
    for trial_id in trial_ids:
        path = record_path(out_dir, trial_id)
        problem = replace_problem(path)
        if problem:
            problems.append((path, problem))
    return problems


def canonical_json(value) -> str:
    """The one JSON text of `value` that checksums are taken over (numpy through `tolist`);
    RecordError for values JSON cannot hold, NaN and infinities included."""
    try:
        return json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=True,
                          allow_nan=False, default=_numpy_to_python)
    except (TypeError, ValueError) as error:
        raise RecordError(f"not representable as JSON: {error}") from None


def _numpy_to_python(value):
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"object of type {type(value).__name__} is not JSON serializable")


def _checksum(record_without_checksum: dict) -> str:
    digest = hashlib.sha256(canonical_json(record_without_checksum).encode("ascii"))
    return "sha256:" + digest.hexdigest()


def make_record(trial: dict, *, result: dict | None = None,
                error: dict | None = None, events: dict | None = None) -> dict:
    """A checksummed record of a trial that returned `result` or raised `error`; `events`:
    the memorized events it matched against ({"folder", "sha256"} of
    trial_function.events_identity), None when it read none or its trial function does
    not say."""
    if (result is None) == (error is None):
        raise ValueError("a record holds exactly one of result and error")
    record = {
        "format": RECORD_FORMAT,
        "format_version": RECORD_FORMAT_VERSION,
        "trial_id": trial["trial_id"],
        "status": "ok" if error is None else "error",
        "trial": trial,
        "result": result,
        "error": error,
        "events": events,
    }
    # Round trip through canonical JSON so the record holds exactly what a reader sees.
    record = json.loads(canonical_json(record))
    record["checksum"] = _checksum(record)
    return record


def write_record(out_dir, record: dict) -> Path:
    """Writes `record` durably and atomically; returns its path."""
    path = record_path(out_dir, record["trial_id"])
    path.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(record, sort_keys=True, indent=1, ensure_ascii=True, allow_nan=False)
    # Through rig/files.py: the umask's mode, as a trial's outputs, not mkstemp's 0600.
    write_atomically(path, (text + "\n").encode("ascii"), start=JSON_OBJECT_START)
    _fsync_folder(path.parent)
    return path


def _fsync_folder(folder: Path) -> None:
    descriptor = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(descriptor)
    finally:
        os.close(descriptor)


# The result fields a trial's run copies from its trial (where the result has them): a
# record whose result names another trial's is not this trial's record.
_RESULT_OF_TRIAL = (("seed", "seed"), ("controller", "controller"), ("object", "object_name"))


def _offset_problem(result: dict, trial: dict) -> str | None:
    """Why the result's offset_m (where it has one) is not where its trial put the object,
    the marker moved by the jitter (x normal to the palm, y along the stroke), or None."""
    if "offset_m" not in result:
        return None
    jitter = trial["perturbation"]
    expected = [trial["marker_dx_m"] + jitter["dx_m"], trial["marker_dy_m"] + jitter["dy_m"]]
    problem = result_offset_problem(result["offset_m"], expected)
    return (f"its result's offset_m {problem}, its trial's marker + jitter (where the trial "
            "puts the object)") if problem else None


def _sim_time_problem(result: dict) -> str | None:
    """Why the result's sim_time_s (where it has one) is longer than any sweep trial runs:
    a sweep loads its scenarios without allow_long, so a run stops by longest_trial_s of those."""
    from tegrasp_drake.scenario.grasp_diagram import longest_trial_s  # Drake: on use
    sim_time = result.get("sim_time_s")
    longest = longest_trial_s(allow_long=False)
    if sim_time is not None and sim_time > longest:
        return (f"its result's sim_time_s {shorten(repr(sim_time))} s is longer than a sweep "
                f"trial runs, at most {longest:g} s (the longest grasp script a scenario "
                "allows plus the time for corrections)")
    return None


# An events identity's digest: SHA-256, 64 lowercase hex digits (hashlib's hexdigest).
_SHA256_HEX = re.compile(r"[0-9a-f]{64}")


def events_problem(events, controller=None) -> str | None:
    """Why `events` is not what a record says of the memorized events a trial matched
    against (trial_function.events_identity: null, or {"folder": the folder asked for, absolute
    (older records name it relative), or null; "sha256": the SHA-256 of their content}), or
    None; the trial's `controller` (its name; another value is not checked here) must read
    memorized events for them to be named (ControllerEntry.reads_memorized_events)."""
    if events is None:
        return None
    if not (isinstance(events, dict) and set(events) == {"folder", "sha256"}):
        return "events is neither null nor {\"folder\", \"sha256\"}"
    if (isinstance(controller, str) and controller in CONTROLLER_NAMES
            and not controller_entry(controller).reads_memorized_events):
        return (f"events names memorized events, but its trial's {controller} controller reads "
                "none (a sweep records null for it): the record was edited or is another "
                "controller's; set events to null or correct the trial's controller")
    if not (isinstance(events["sha256"], str) and _SHA256_HEX.fullmatch(events["sha256"])):
        return (f"events.sha256 must be a SHA-256 (64 lowercase hex digits), got "
                f"{shorten(repr(events['sha256']))}")
    folder = events["folder"]
    if folder is not None and not (isinstance(folder, str) and folder):
        return (f"events.folder must be null or a folder's path (the events folder the sweep "
                f"was given; older records name it relative), got {shorten(repr(folder))}")
    return None


def _fields_problem(record: dict, fields: set) -> str | None:
    """Which of a record's `fields` it is missing and which keys it has that no record has
    (names cut as echoed values are), or None when it has exactly `fields`."""
    missing = sorted(fields - set(record))
    extra = sorted(map(str, set(record) - fields))
    said = []
    if missing:
        said.append(f"it is missing the field(s) {shorten(', '.join(missing))}")
    if extra:
        said.append(f"it has field(s) {shorten(', '.join(map(repr, extra)))} that no record "
                    "has")
    return "; ".join(said) or None


def check_record(record, expected_file_name: str | None = None) -> str | None:
    """Why `record` is not a valid record, or None when it is."""
    if not isinstance(record, dict):
        return "not a JSON object"
    version = record.get("format_version")
    if version is None:  # absent (or null): no record of any version
        return "it has no format_version, so no sweep wrote it"
    if type(version) is not int or version not in _RECORD_FIELDS:
        return (f"format_version {version!r} is not one of "
                f"{', '.join(map(str, _RECORD_FIELDS))}")
    fields = _RECORD_FIELDS[version]
    problem = _fields_problem(record, fields)
    if problem is not None:
        return problem
    if record["format"] != RECORD_FORMAT:
        return f"format {record['format']!r} is not {RECORD_FORMAT!r}"
    trial = record.get("trial")
    problem = events_problem(record.get("events"),
                             trial.get("controller") if isinstance(trial, dict) else None)
    if problem is not None:
        return problem
    content = {key: value for key, value in record.items() if key != "checksum"}
    try:
        checksum = _checksum(content)
    except RecordError as error:
        return str(error)
    if record["checksum"] != checksum:
        return "checksum does not match the content"
    if record["status"] not in ("ok", "error"):
        return f"status {record['status']!r} is neither 'ok' nor 'error'"
    ok = record["status"] == "ok"
    if ok != (record["result"] is not None) or ok == (record["error"] is not None):
        return ("it must hold a result and no error (status 'ok') or an error and no result "
                "(status 'error'), as a run writes it")
    trial = record["trial"]
    if not isinstance(trial, dict) or trial.get("trial_id") != record["trial_id"]:
        return "its trial's trial_id is not the record's trial_id"
    problem = trial_problem(trial)
    if problem is not None:
        return f"its 'trial' is not one a sweep makes: {problem}"
    if ok:
        problem = result_problem(record["result"])
        if problem is not None:
            return f"its 'result' is {problem}"
        problem = result_trial_problem(record["result"], trial)
        if problem is not None:
            return problem
    if expected_file_name is not None and (
            not isinstance(record["trial_id"], str)
            or record_file_name(record["trial_id"]) != expected_file_name):
        return f"trial_id {record['trial_id']!r} does not belong in {expected_file_name}"
    return None


def result_trial_problem(result: dict, trial: dict) -> str | None:
    """Why `result` (a valid result, result_problem) cannot be the result of `trial` (a sweep
    trial's dict): its seed, controller, object or offset are another trial's, or it ran
    longer than a sweep trial runs; None when it can."""
    for field, trial_field in _RESULT_OF_TRIAL:
        value = result.get(field, trial.get(trial_field))
        if value != trial.get(trial_field):
            return (f"its result's {field} {shorten(repr(value))} is not its trial's "
                    f"{trial_field} {shorten(repr(trial.get(trial_field)))}")
    return _offset_problem(result, trial) or _sim_time_problem(result)


def result_problem(result) -> str | None:
    """Why `result` is not a TrialResult's JSON form (from_dict: its fields' ranges and the
    relations between them), or None when it is: a record is checked whole when it is read,
    so that a result no trial could have produced runs again instead of reaching a report."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    if not isinstance(result, dict):
        return f"not a trial result's JSON form (a mapping), got {shorten(repr(result))}"
    try:
        TrialResult.from_dict(result)
    except ValueError as error:
        return str(error)
    return None


def read_record(path) -> tuple[dict | None, str | None]:
    """(record, None) for a valid record file, (None, reason) for a damaged one; UserPathError
    naming it for one this user cannot read (no permission, an I/O error): not a damaged
    record, so never set aside or run again (it may be another user's good record)."""
    try:
        record = read_json_file(path, limit=MAX_RECORD_BYTES, encoding="ascii",
                                kind="a trial record",
                                check=lambda data: check_record(data, Path(path).name))
    except JsonFileError as error:
        if error.unreadable is not None:
            raise UserPathError(f"trial record {path}: {error.problem}; "
                                f"{read_error_remedy(error.unreadable)}; it was neither set "
                                "aside nor run again", error.unreadable) from None
        return None, error.problem
    return record, None


@public_api
def load_records(out_dir: Annotated[PathLike, INPUT_FOLDER]) -> LoadedRecords:
    """Reads every record under `<out_dir>/trials` (temporary files ignored; no trials folder:
    no records); UserPathError for a path that is not a folder, or a trials folder this user
    cannot read (not one without records). A folder without records reads as empty, not as
    an error, on purpose: it is how a sweep starts (run_sweep reads its --out to resume, and a
    new one holds none) and how a transfer's or sensitivity study's report reads a cell not
    run yet. What needs records refuses an empty result itself, in its own words:
    write_reports (ValueError), `tegrasp plot` and the analysis scripts."""
    folder = Path(out_dir) / TRIALS_FOLDER
    records, corrupt, others = {}, {}, []
    for path in folder_entries(folder) or []:  # UserPathError: a trials/ that cannot be read
        if path.suffix == ".json":
            if record_name_trial_id(path.name) is None:
                others.append(path)  # no sweep writes this name: not a record, not read
                continue
            record, reason = read_record(path)
            if record is None:
                corrupt[path] = reason
            else:
                records[record["trial_id"]] = record
    return LoadedRecords(records=records, corrupt=corrupt, others=tuple(others))


def remove_stale_staging_files(out_dir, trial_ids) -> list[Path]:
    """Removes the staging files that writers of these trials' records killed past their
    handlers (SIGKILL, a power cut) left in `<out_dir>/trials`, and returns them: only a
    record's own (named for it), only an ended writer's, only while it holds JSON
    (remove_stale_staging_files_in). Another process's, or a file of another name or
    content, stays."""
    return remove_stale_staging_files_in(Path(out_dir) / TRIALS_FOLDER,
                                         [record_file_name(i) for i in trial_ids],
                                         JSON_OBJECT_START)


def earlier_temporary_files(out_dir) -> list[Path]:
    """The record temporary files (`.NAME.json.XXXXXXXX.tmp`) in `<out_dir>/trials` that an
    earlier version wrote: not removed, since nothing in them tells a killed writer's from a
    live one's (an earlier version's run into a folder two hosts share); the user is told."""
    folder = Path(out_dir) / TRIALS_FOLDER
    try:
        return [path for path in sorted(folder.iterdir())
                if _EARLIER_TEMPORARY.fullmatch(path.name)]
    except OSError:
        return []


# record_result's results by record (id -> (record, result)) within results_parsed_once.
_PARSED_RESULTS = contextvars.ContextVar("tegrasp_parsed_results", default=None)


@contextlib.contextmanager
def results_parsed_once():
    """Within the block, record_result parses each record's result once and gives the same
    TrialResult again: the reports of a results folder (its tables, statistics and figures)
    each read every record's result, about 2 ms of checks apiece. The records must not change
    within the block (a report writer only reads them)."""
    token = _PARSED_RESULTS.set({})
    try:
        yield
    finally:
        _PARSED_RESULTS.reset(token)


@public_api
def record_result(record: dict):
    """The TrialResult of a record's "result" (its JSON form), None for a record without
    one (an error); ValueError naming the record's file and the field for one that is not."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    if not isinstance(record, dict) or "result" not in record:
        if not isinstance(record, dict):
            given = f"a {type(record).__name__}"
        elif record:
            given = "the keys " + shorten(", ".join(map(str, record)))
        else:
            given = "an empty dict"
        raise ValueError(f"record_result: argument 'record' is not a sweep record (it has no "
                         f"'result'; got {given}); give a record of load_records(FOLDER)")
    result = record["result"]
    if result is None:
        return None
    if not (isinstance(result, dict) and "hold_success" in result):
        raise ValueError(f"record_result: the record's 'result' is not a trial's result (a "
                         f"TrialResult's JSON form, with hold_success), got "
                         f"{shorten(repr(result))}")
    parsed = _PARSED_RESULTS.get()
    if parsed is not None and parsed.get(id(record), (None,))[0] is record:
        return parsed[id(record)][1]
    try:
        trial_result = TrialResult.from_dict(result)
    except ValueError as e:  # a record edited by hand: its file, then the field
        trial_id = record.get("trial_id")
        if not isinstance(trial_id, str):
            raise
        raise ValueError(f"record {TRIALS_FOLDER}/{record_file_name(trial_id)}: its 'result' "
                         f"is {e}") from None
    if parsed is not None:  # the record is held with it: its id is not reused meanwhile
        parsed[id(record)] = (record, trial_result)
    return trial_result
