"""TrialLog: everything a later step needs from one trial, in one .npz file.

Arrays (times in s, simulation clock):
  t_sa (N,), taxels (N, 24) [N] measured (left 12 then right 12), true_taxels (N, 24) [N]
  t_ra (M,), channels (M, 4) [SA_L, SA_R N; RA_L, RA_R m/s^2], pad_acceleration (M, 6)
  t_slow (K,), arm_q (K, 6) [rad], arm_q_desired (K, 6), gripper_command (K, 3),
  gripper_status (K, 8), phase (K,) [the Mode value, an index into `mode_names`; an ideal
  grasp's: an index into `phases`], object_state (K, 13)
Metadata (JSON in `meta`): format version, scenario YAML, phase names, phase start times,
physical event times, controller name, package versions, and the checksum of all of it
(trial_log_checksum): a log edited after it was written is refused."""

import dataclasses
import hashlib
import json
import math
import os
import pathlib
import zipfile
import zlib

from collections.abc import Callable

import numpy as np

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.files import (DuplicateKeyError, JsonValueError, file_problem, load_json,
                                     is_read_failure, read_error_remedy,
                                     one_line, temporary_sibling)
from tegrasp_drake.scenario.logged_channels import logged_channels_problem
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS, TAXELS_PER_PAD
from tegrasp_drake.rig.station_interface import PAD_ACCELERATION_AXES
from tegrasp_drake.rig.number_text import distinct_number_texts, number_text
from tegrasp_drake.rig.ranges import is_integer
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.npz_headers import (MAX_TRIAL_LOG_BYTES, NPZ_START, DamagedNpzError,
                                           DeclaredArraysError, NotAnNpzError, NpzHeaderError,
                                           checked_npz_arrays)
from tegrasp_drake.rig.api_boundary import PathLike, public_api, public_dataclass
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES

FORMAT_VERSION = 1
ARRAY_FIELDS = ("t_sa", "taxels", "true_taxels", "t_ra", "channels", "pad_acceleration",
                "t_slow", "arm_q", "arm_q_desired", "gripper_command", "gripper_status",
                "phase", "object_state")


class TrialLogError(ValueError):
    """A trial log file is missing, truncated or of another format; the message names it."""

    def __init__(self, message: str):
        super().__init__(one_line(message))


@public_dataclass
@dataclasses.dataclass
class TrialLog:
    t_sa: np.ndarray
    taxels: np.ndarray
    true_taxels: np.ndarray
    t_ra: np.ndarray
    channels: np.ndarray
    pad_acceleration: np.ndarray
    t_slow: np.ndarray
    arm_q: np.ndarray
    arm_q_desired: np.ndarray
    gripper_command: np.ndarray
    gripper_status: np.ndarray
    phase: np.ndarray
    object_state: np.ndarray
    meta: dict

    def save(self, path) -> pathlib.Path:
        """Writes the log to `path` (.npz), atomically. TrialLogError naming `path`, and
        nothing written, for a log load_trial_log would refuse (arrays of other shapes,
        channels that are not Eq. 1-2 of the taxels and accelerations, metadata that
        disagrees with them): what the one reader refuses is never written."""
        path = pathlib.Path(path)
        meta = {key: value for key, value in self.meta.items() if key != CHECKSUM_FIELD}
        meta["format_version"] = FORMAT_VERSION
        arrays = {name: np.asanyarray(getattr(self, name)) for name in ARRAY_FIELDS}
        problem = trial_log_problem(meta, arrays)
        if problem:
            raise TrialLogError(f"TrialLog.save: '{path}' not written: {problem}")
        # The checksum of the metadata as a reader parses it back (tuples read as lists).
        meta[CHECKSUM_FIELD] = trial_log_checksum(json.loads(json.dumps(meta)), arrays)
        path.parent.mkdir(parents=True, exist_ok=True)
        with (temporary_sibling(path, start=NPZ_START) as temporary,
              open(temporary, "wb") as f):
            # A full disk or Ctrl-C leaves no truncated log, and an earlier one whole; what a
            # save of this log killed by SIGKILL left beside it is removed first.
            np.savez_compressed(f, meta=np.array(json.dumps(meta, sort_keys=True)), **arrays)
        return path

    @property
    def sa(self) -> np.ndarray:
        """SA_left, SA_right (M, 2) [N] at the RA times (held between taxel samples)."""
        return self.channels[:, :2]

    @property
    def ra(self) -> np.ndarray:
        return self.channels[:, 2:]


CHECKSUM_FIELD = "checksum"


def trial_log_checksum(meta: dict, arrays: dict) -> str:
    """The SHA-256 (hex) of a trial log's contents: its metadata without CHECKSUM_FIELD as
    canonical JSON (keys sorted, no spaces, ASCII), then each array of ARRAY_FIELDS in that
    order, its name, dtype, shape and bytes (C order). TrialLog.save stores it as meta
    'checksum'; load_trial_log refuses a log whose contents give another."""
    digest = hashlib.sha256()
    body = {key: value for key, value in meta.items() if key != CHECKSUM_FIELD}
    digest.update(json.dumps(body, sort_keys=True, separators=(",", ":"),
                             ensure_ascii=True).encode("ascii"))
    for name in ARRAY_FIELDS:
        array = np.asanyarray(arrays[name])
        digest.update(f"\0{name}\0{array.dtype.str}\0{array.shape}\0".encode("ascii"))
        contiguous = np.ascontiguousarray(array)  # its bytes in C order, not copied again
        if contiguous.size:
            digest.update(memoryview(contiguous).cast("B"))
    return digest.hexdigest()


def checksum_problem(meta: dict, arrays: dict) -> str | None:
    """What is wrong with a trial log's checksum (meta 'checksum', trial_log_checksum of the
    rest), in words that follow the log's name, else None: one its contents do not give
    (edited after writing). A log that holds none is unchecksummed_log_refusal's."""
    stored = meta.get(CHECKSUM_FIELD)
    actual = trial_log_checksum(meta, arrays)
    if not isinstance(stored, str) or stored != actual:
        return (f"was changed after it was written (its stored checksum "
                f"{shorten(repr(stored), 80)} is not its contents' SHA-256 {actual})")
    return None


def unchecksummed_log_refusal(path) -> str:
    """The refusal of the trial log at `path` that holds no checksum (meta 'checksum'): one an
    earlier version of the package wrote, before trial logs carried one. A run that reuses a
    stored log (a campaign's LOGS_DIR, a sweep's --logs read by its reports) would meet it
    again on every run, so the words say to delete it, which makes that run write it anew."""
    return (f"trial log '{path}' was written by an earlier version of the package, without "
            f"a checksum (meta '{CHECKSUM_FIELD}'), so an edited log cannot be told from a "
            f"trial's; delete '{path}' (a run that reuses its logs then writes it anew) or run "
            "the trial again to replace it")


class LogNotWritten(Exception):
    """Raised by a run that finished but could not write its optional log copy (`tegrasp
    sweep --logs`): carries the run's `result`, which its caller keeps as any result, and
    the log's `path` and the OS `reason`, which its caller reports."""

    def __init__(self, result, path, reason: str):
        super().__init__(result, str(path), reason)
        self.result, self.path, self.reason = result, str(path), reason


def save_log_copy(save: Callable, path, result):
    """save(path), the optional log copy of a finished run whose result is `result`; an
    OSError (a full disk, a folder made read-only) is LogNotWritten carrying the result, so
    a log that cannot be written never turns the run's result into an error."""
    try:
        save(path)
    except OSError as error:
        reason = os.strerror(error.errno) if error.errno else str(error)
        raise LogNotWritten(result, path, reason) from None


def check_trial_log_file(path: PathLike) -> None:
    """TrialLogError naming `path` unless it is a regular file, asked before a byte is read:
    every reader of a trial log (plot, the myRIO emulator) starts here."""
    path = pathlib.Path(path)
    problem = file_problem(path)
    if problem == "does not exist":
        raise TrialLogError(f"trial log '{path}' does not exist (make one with `tegrasp trial "
                            "--out DIR`: DIR/trial.npz, or `tegrasp demo`: out/demo/trial.npz)")
    if problem:
        raise TrialLogError(f"trial log '{path}' {problem} (a "
                            "trial log is the trial.npz that `tegrasp trial --out DIR` writes)")


@public_api
def load_trial_log(path: PathLike, *, rejudge: bool = True) -> TrialLog:
    """Reads a TrialLog; raises TrialLogError naming the file on any defect, a stored result
    other than the judge's of the log's data among them (trial_judge.stored_verdict_problem;
    rejudge=False: not asked, for a reader that judges the log anew, as
    analysis/rejudge_from_logs.py does after the judge changed)."""
    path = pathlib.Path(path)
    meta, arrays = written_trial_log(path)
    problem = trial_log_problem(meta, arrays, rejudge=rejudge)
    if problem:
        raise TrialLogError(f"trial log '{path}': {problem}; run the trial again to remake it")
    return TrialLog(meta=meta, **arrays)


def written_trial_log(path: pathlib.Path, *,
                      any_version: bool = False) -> tuple[dict, dict]:
    """(metadata, arrays) of the trial log at `path` as TrialLog.save wrote it: a trial
    log's arrays and metadata of this format version, holding the checksum of them all
    (checksum_problem); TrialLogError naming the file otherwise. What load_trial_log reads
    before it checks what the log holds. With `any_version`, a log of any format version
    written before logs carried a checksum is taken too (one an earlier version of the
    package wrote; a log with a checksum must still match it): what a run asks of an earlier
    run's log it would replace (a file of the user's, or a log edited by hand, is not one)."""
    check_trial_log_file(path)
    try:  # a log this user cannot open (another user's) is not a damaged one: no remake
        os.close(os.open(path, os.O_RDONLY | os.O_NONBLOCK))
        return _checked_trial_log(path, any_version)
    except OSError as e:
        if not is_read_failure(e):
            raise
        raise TrialLogError(f"trial log '{path}' cannot be read ({os_error_text(e)}); "
                            f"{read_error_remedy(e)}") from None


def _checked_trial_log(path: pathlib.Path, any_version: bool) -> tuple[dict, dict]:
    """written_trial_log's checks of a log it could open; the system's error reading it
    (files.is_read_failure) raised as that OSError."""
    try:
        arrays = checked_npz_arrays(path, ("meta", *ARRAY_FIELDS),
                                    max_bytes=MAX_TRIAL_LOG_BYTES, text=("meta",),
                                    max_text_chars=MAX_META_CHARS,
                                    known=("meta", *ARRAY_FIELDS), kind="a trial log",
                                    declared_problem=declared_arrays_problem)
        meta = load_json(str(arrays.pop("meta")))
    except (DuplicateKeyError, JsonValueError) as e:  # JSON that parses, but is no metadata
        raise TrialLogError(f"trial log '{path}': its metadata {e}; run the trial again to "
                            "remake it") from None
    except NpzHeaderError as e:
        raise TrialLogError(trial_log_npz_refusal(path, e)) from None
    except RecursionError:
        raise TrialLogError(f"trial log '{path}': its metadata nests too deeply; it is not "
                            "a trial log") from None
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile, zlib.error,
            UnicodeDecodeError) as e:
        if is_read_failure(e):
            raise
        raise TrialLogError(f"trial log '{path}' is truncated or corrupt ({type(e).__name__}: "
                            f"{e}); run the trial again to remake it") from None
    if not isinstance(meta, dict):
        raise TrialLogError(f"trial log '{path}': its metadata is a JSON "
                            f"{type(meta).__name__}, not the object a trial log holds; it is "
                            "not a trial log (`tegrasp trial --out DIR` writes one)")
    version = meta.get("format_version")
    if version is None:  # absent (or null): no trial log of any version
        raise TrialLogError(f"trial log '{path}': its metadata has no format version, so "
                            "`tegrasp trial` did not write it; run the trial again "
                            "(`tegrasp trial --out DIR` writes DIR/trial.npz)")
    if any_version and is_integer(version) and CHECKSUM_FIELD not in meta:
        return meta, arrays  # written before logs carried a checksum
    if not is_integer(version) or version != FORMAT_VERSION:
        raise TrialLogError(f"trial log '{path}' has format version "
                            f"{shorten(repr(version))}, this package reads "
                            f"{FORMAT_VERSION}; run the trial again with this package to "
                            "remake it")
    if meta.get(CHECKSUM_FIELD) is None:
        raise TrialLogError(unchecksummed_log_refusal(path))
    problem = checksum_problem(meta, arrays)  # before what an edit would make of its contents
    if problem:
        raise TrialLogError(f"trial log '{path}' {problem}; run the trial again to remake it")
    return meta, arrays


def trial_log_npz_refusal(path, error: NpzHeaderError) -> str:
    """The refusal of the trial log at `path` whose file checked_npz_arrays refused with
    `error`, in one line naming it: no .npz at all (NotAnNpzError: not a trial log), one cut
    short or damaged (DamagedNpzError, or a log of this package's that lacks arrays:
    incomplete, not an earlier version's, whose format version its metadata would give), arrays
    whose headers declare what no trial log holds (DeclaredArraysError), else truncated or
    corrupt. What every reader of a trial log's file says (load_trial_log, the myRIO
    emulator's load_tactile_recording)."""
    remake = "run the trial again to remake it"
    if isinstance(error, NotAnNpzError):
        return (f"'{path}' is not a trial log (an .npz zip archive written by tegrasp): "
                f"{error}; give the trial.npz that `tegrasp trial --out DIR` writes")
    if isinstance(error, DamagedNpzError):
        return (f"trial log '{path}' is incomplete or damaged, not one an earlier version "
                f"wrote: {error}; {remake}")
    if isinstance(error, DeclaredArraysError):
        return f"trial log '{path}': {error} (from its .npy headers); {remake}"
    if "lacks the arrays" in str(error):
        if holds_this_versions_metadata(path):
            return (f"trial log '{path}' is incomplete, not one an earlier version wrote: it "
                    f"{error}, which every log of its format version {FORMAT_VERSION} holds; "
                    f"{remake}")
        return (f"trial log '{path}' {error}; it is not a trial log (`tegrasp trial --out "
                "DIR` writes one)")
    return f"trial log '{path}' is truncated or corrupt ({error}); {remake}"


def holds_this_versions_metadata(path) -> bool:
    """Whether the .npz at `path` holds a trial log's metadata of this format version with a
    checksum: what this package's TrialLog.save wrote, whatever else it lacks."""
    try:
        text = checked_npz_arrays(path, ("meta",), max_bytes=4 * MAX_META_CHARS,
                                  text=("meta",), max_text_chars=MAX_META_CHARS)["meta"]
        meta = load_json(str(text))
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile, zlib.error,
            RecursionError):
        return False
    return (isinstance(meta, dict) and meta.get("format_version") == FORMAT_VERSION
            and CHECKSUM_FIELD in meta)


def trial_log_problem(meta: dict, arrays: dict, *, rejudge: bool = True) -> str | None:
    """What is wrong with a trial log's metadata and arrays together, in words, else None:
    its scenario, its arrays (trial_arrays_problem), its metadata against them
    (meta_problem) and, with `rejudge`, its stored result against the judge's of its data
    (stored_verdict_problem: an edited verdict). load_trial_log refuses such a log and
    TrialLog.save never writes one."""
    from tegrasp_drake.scenario.trial_judge import stored_verdict_problem  # Drake: on use
    scenario, problem = logged_scenario(meta)
    return (problem or trial_arrays_problem(arrays, scenario)
            or meta_problem(meta, arrays, scenario)
            or (stored_verdict_problem(meta, arrays, scenario) if rejudge else None))


def _is_time(value) -> bool:
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value))


def _is_name_list(value) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(n, str) for n in value)


def _is_mode_names(value) -> bool:
    """The controllers' modes' labels in Mode's order, as a controller trial writes them."""
    from tegrasp_drake.control.grasp_modes import Mode
    return value == [mode.label for mode in Mode]


def _is_event_times(value) -> bool:
    return isinstance(value, dict) and all(
        isinstance(name, str) and (t is None or _is_time(t)) for name, t in value.items())


def _is_phase_starts(value) -> bool:
    return isinstance(value, dict) and all(
        isinstance(name, str) and _is_time(t) for name, t in value.items())


def _is_duration(value) -> bool:
    return _is_time(value) and value >= 0.0


def _is_grip_force(value) -> bool:
    """A grip force [N] the scenario's grasp.grip_force could hold (its declared range)."""
    from tegrasp_drake.control.scripted_grasp import GraspScriptConfig  # Drake: on use
    from tegrasp_drake.rig.ranges import field_range
    return _is_time(value) and field_range(GraspScriptConfig, "grip_force").contains(value)


def _is_versions(value) -> bool:
    return isinstance(value, dict) and all(
        isinstance(name, str) and isinstance(v, str) for name, v in value.items())


# The metadata fields a reader uses or the writer stores (optional but REQUIRED_META_FIELDS),
# what each must hold, and its check. The writer is trial_log_writer.collect_trial_log with
# the runs' `meta` (runs/trial.py). The times among them are checked against the log's span
# in meta_problem.
META_FIELDS = {
    "scenario": ("be the scenario's YAML text", lambda v: isinstance(v, str)),
    "controller": ("be a controller name, one of " + ", ".join(CONTROLLER_NAMES),
                   lambda v: isinstance(v, str) and v in CONTROLLER_NAMES),
    "campaign_run": ("be a recording run's label", lambda v: isinstance(v, str)),
    "mode_names": ("be the modes' labels in their order, Reach to Failed", _is_mode_names),
    "phases": ("be a non-empty list of names", _is_name_list),
    "phase_starts": ("map phase names to times [s]", _is_phase_starts),
    "events": ("map event names to times [s] or null", _is_event_times),
    # Its fields are TrialResult's (figures/trial_annotations.logged_result reads them).
    "result": ("be a trial result's JSON form (an object)", lambda v: isinstance(v, dict)),
    "grip_force": ("be a grip force in grasp.grip_force's range, 20 to 235 N (the 2F-85's)",
                   _is_grip_force),
    "sim_time_s": ("be a duration of at least 0 s", _is_duration),
    "wall_time_s": ("be a duration of at least 0 s", _is_duration),
    "versions": ("map package names to version text", _is_versions),
}


META_KEYS = frozenset({*META_FIELDS, "transitions", "format_version", CHECKSUM_FIELD})
# The fields every trial log holds: each of its writers stores the controller that ran it
# (runs/trial.py the scenario's, runs/ideal_grasp.py the open-loop script's), and the
# figures' labels and the transition scores' check read it; a log without one was not
# written by this package or was edited.
REQUIRED_META_FIELDS = ("controller",)
# [characters] The metadata's JSON holds the scenario's YAML (its file at most
# typed_yaml.MAX_YAML_BYTES, 1 MB), the transitions twice (in 'transitions' and the result;
# a sweep record, result and all, is at most records.MAX_RECORD_BYTES, 1 MB) and a few short
# fields: under 3 MB; 4 M characters bound it before its 16 MB are decompressed.
MAX_META_CHARS = 4_000_000


def most_transitions(span_s: float, controller=None) -> int:
    """The most transitions a trial's timeline of `span_s` [s] can hold, its controller's
    config `controller` (a GraspControllerConfig; None: the defaults). A pass through the state
    machine enters each mode at most once: len(Mode) - 1 transitions (Reach to Done or
    Failed). Each correction a controller counts (Re-Reach, Lift-Load, re-grasp) starts at
    most one more such pass, and each is limited by its configuration's range
    (max_re_reaches, max_lift_loads, max_regrasps: at most 10 each): 9 * (1 + 30) = 279.
    Avoid is not counted but timed: Hold -> Avoid -> Hold, two transitions, after
    hit_refractory_s of Hold, sense_s and move_s (0.93 s at the defaults), each transition at
    least one controller update (update_period_s) after the one before; so at most two a
    cycle over the span, plus one cycle begun at its end. A 12 s grasp takes about 6."""
    from tegrasp_drake.control.controller_config import (GraspControllerConfig, LiftLoadConfig,
                                                         RegraspConfig, ReReachConfig,
                                                         TaxelAwareConfig)
    from tegrasp_drake.control.grasp_modes import Mode
    from tegrasp_drake.rig.ranges import field_range
    if not hasattr(controller, "avoid"):  # none given, or one that never Avoids (open loop)
        controller = GraspControllerConfig()
    one_pass = len(Mode) - 1
    re_reaches = max(field_range(ReReachConfig, "max_re_reaches").high,
                     field_range(TaxelAwareConfig, "max_re_reaches").high)
    corrections = (re_reaches + field_range(LiftLoadConfig, "max_lift_loads").high
                   + field_range(RegraspConfig, "max_regrasps").high)
    avoid = controller.avoid
    cycle_s = max(avoid.hit_refractory_s + avoid.sense_s + avoid.move_s,
                  2 * controller.update_period_s)
    return int(one_pass * (1 + corrections) + 2 * (math.floor(max(span_s, 0.0) / cycle_s) + 1))


def _time_span(arrays: dict) -> tuple[float, float]:
    """[s] from the first sample of the log's time bases to one sample period past the last
    (the simulation ends at most one logging period after the last sample it logged)."""
    bases = [np.asarray(arrays[name]) for name in _TIME_BASES if name in arrays]
    start = min(float(times[0]) for times in bases)
    end = max(float(times[-1] + (times[-1] - times[-2])) for times in bases)
    return start, end


def _timeline_problem(transitions: list, span: tuple[float, float]) -> str | None:
    """What is wrong with the timeline as a whole, or None: in time order (one transition per
    controller update), inside the log's time span, each leaving the mode the one before
    entered."""
    start, end = span
    for k, entry in enumerate(transitions):
        t = entry["t"]
        if not start <= t <= end:
            return (f"meta 'transitions[{k}]' at {number_text(t)} s lies outside the log's "
                    f"time span, {number_text(start)} to {number_text(end)} s")
        if k and t <= transitions[k - 1]["t"]:
            return (f"meta 'transitions[{k}]' at {number_text(t)} s comes before or with "
                    f"transitions[{k - 1}] at {number_text(transitions[k - 1]['t'])} s; a "
                    "timeline is in time order, one transition per controller update")
        if k and entry["from"] != transitions[k - 1]["to"]:
            return (f"meta 'transitions[{k}]' starts from '{shorten(str(entry['from']))}', but "
                    f"transitions[{k - 1}] went to '{shorten(str(transitions[k - 1]['to']))}'")
    return None


def _sim_time_problem(meta: dict, arrays: dict) -> str | None:
    """What is wrong if meta 'sim_time_s' (the simulated time the run ended at; its start is
    0 s: simulator_config.start_time) disagrees with the log's samples or its stored result's
    sim_time_s, or None. Each logger samples at its period from 0 s until the run ends
    (trial_log_writer), so each time base's last sample lies at or before sim_time_s and
    less than one of its periods before it (STEP_TOLERANCE of a period for float rounding)."""
    sim_time = meta.get("sim_time_s")
    if sim_time is None:
        return None
    for name in _TIME_BASES:
        if name not in arrays:
            continue
        times = np.asarray(arrays[name], dtype=float)
        last = len(times) - 1
        period = float(times[-1] - times[-2])
        slack = STEP_TOLERANCE * period
        if times[-1] > sim_time + slack or sim_time - times[-1] > period + slack:
            return (f"meta 'sim_time_s' is {number_text(sim_time)} s, but '{name}' ends at "
                    f"sample {last}, {number_text(float(times[-1]))} s; a run's loggers sample "
                    f"until it ends, so its last sample lies at or before sim_time_s and within "
                    f"one period ({number_text(period)} s) of it")
    result_time = (meta.get("result") or {}).get("sim_time_s")
    if _is_time(result_time) and abs(result_time - sim_time) > _SAME_TIME_S:
        return (f"meta 'sim_time_s' is {number_text(sim_time)} s, but its 'result' "
                f"sim_time_s is {number_text(result_time)} s (one run's simulated time)")
    return None


def _times_problem(meta: dict, span: tuple[float, float]) -> str | None:
    """A phase start or event time outside the log's time span, or None."""
    start, end = span
    for key in ("phase_starts", "events"):
        for name, t in (meta.get(key) or {}).items():
            if t is not None and not start <= t <= end:
                return (f"meta '{key}' time of '{shorten(name)}' ({number_text(t)} s) lies "
                        f"outside the log's time span, {number_text(start)} to "
                        f"{number_text(end)} s")
    return None


def _hit_problem(meta: dict, arrays: dict, scenario, span: tuple[float, float]) -> str | None:
    """What is wrong with the log's hit marker (meta 'events' 'hit', the figures' "hit" line)
    against its scenario's hit (disturbance.hit_time_s; negative: none) and its samples, or
    None: a hit at or after the log's start; 'events' marks the scenario's hit, and only it,
    when it came by the last slow sample (trial_judge.physical_event_times), none otherwise (a
    hit after the log's end is a trial that ended first: Failed or Done)."""
    from tegrasp_drake.scenario.trial_result import HIT_EVENT
    if scenario is None:
        return None
    hit = scenario.disturbance.hit_time_s
    if 0.0 <= hit < span[0]:
        return (f"meta 'scenario' field 'disturbance.hit_time_s' ({number_text(hit)} s) lies "
                f"before the log's start, {number_text(span[0])} s (a trial logs from 0 s)")
    events = meta.get("events")
    if not isinstance(events, dict):
        return None  # a log without events (an ideal grasp's) marks no hit
    marked = events.get(HIT_EVENT)
    last = float(np.asarray(arrays["t_slow"])[-1])
    if marked is not None and hit < 0.0:
        return (f"meta 'events' marks a 'hit' at {number_text(marked)} s, but its 'scenario' "
                f"has none (disturbance.hit_time_s {number_text(hit)}: negative, no hit)")
    if marked is not None and abs(marked - hit) > _SAME_TIME_S:
        return (f"meta 'events' marks the 'hit' at {number_text(marked)} s, but its "
                f"'scenario' hits at {number_text(hit)} s (disturbance.hit_time_s)")
    if marked is None and 0.0 <= hit <= last:
        return (f"meta 'events' marks no 'hit', but its 'scenario' hits at {number_text(hit)} "
                f"s (disturbance.hit_time_s), within the log (to {number_text(last)} s)")
    return None


# How far a phase start may be from the transition it records [s]: the two are one float
# (runs/trial.py copies it), so only rounding, far below the 5 ms controller period, is let by.
_SAME_TIME_S = 1e-9


def _phase_starts_problem(meta: dict) -> str | None:
    """What is wrong with meta 'phase_starts' against the log's timeline, or None. A controller
    trial's (it holds 'transitions') names each mode the timeline enters, at the time of the
    first transition entering it (runs/trial.py); an ideal grasp's (no timeline, its script's
    'phases') starts its phases in the order 'phases' lists them (scripted_grasp)."""
    starts = meta.get("phase_starts")
    if starts is None:
        return None
    if "transitions" in meta:
        entered = {}
        for k, entry in enumerate(meta["transitions"]):
            entered.setdefault(entry["to"], (k, entry["t"]))
        for name, t in starts.items():
            if name not in entered:
                return (f"meta 'phase_starts' names '{shorten(name)}', which no transition "
                        "enters")
            k, first = entered[name]
            if abs(t - first) > _SAME_TIME_S:
                return (f"meta 'phase_starts' gives '{shorten(name)}' starting at "
                        f"{number_text(t)} s, but the transitions first enter it at "
                        f"{number_text(first)} s (transitions[{k}])")
        for name, (k, first) in entered.items():
            if name not in starts:
                return (f"meta 'phase_starts' lacks '{shorten(name)}', which transitions[{k}] "
                        f"enters at {number_text(first)} s")
        return None
    phases = meta.get("phases")
    if phases is None:
        return None
    previous = None
    for name in phases:
        if name in starts:
            if previous is not None and starts[name] < starts[previous]:
                return (f"meta 'phase_starts' gives '{shorten(name)}' starting at "
                        f"{number_text(starts[name])} s, before '{shorten(previous)}' at "
                        f"{number_text(starts[previous])} s, which 'phases' lists first")
            previous = name
    unknown = [name for name in starts if name not in phases]
    if unknown:
        return (f"meta 'phase_starts' names '{shorten(unknown[0])}', which is not one of the "
                "phases")
    return None


def _seed_problem(meta: dict, scenario) -> str | None:
    """What is wrong if meta's result is of another seed than its Scenario's random_seed
    (`scenario`, the log's, parsed once by logged_scenario; the seed the trial ran with:
    runs/trial.py), or None."""
    seed = (meta.get("result") or {}).get("seed")
    if seed is None or scenario is None or scenario.random_seed == seed:
        return None
    return (f"meta 'result' is of seed {shorten(repr(seed))}, but its 'scenario' ran with "
            f"random_seed {shorten(repr(scenario.random_seed))}")


def _copied_fields_problem(meta: dict, scenario) -> str | None:
    """What is wrong if a metadata field copied from elsewhere differs from its source, or
    None: 'grip_force' [N] is its scenario's grasp.grip_force, 'events' its result's
    physical_events (runs/trial.py copies both; a copy differs from its source in no digit)."""
    grip = meta.get("grip_force")
    if scenario is not None and grip is not None and grip != scenario.grasp.grip_force:
        ours, theirs = distinct_number_texts(grip, scenario.grasp.grip_force)
        return (f"meta 'grip_force' is {ours} N, but its 'scenario' grips with {theirs} N "
                "(grasp.grip_force, the value it copies)")
    physical = (meta.get("result") or {}).get("physical_events")
    events = meta.get("events")
    if events is not None and physical is not None and events != physical:
        name = next((key for key in (*events, *physical)
                     if events.get(key, "absent") != physical.get(key, "absent")))
        ours, theirs = (_event_text(events, name), _event_text(physical, name))
        return (f"meta 'events' gives '{shorten(name)}' {ours}, but its 'result' "
                f"physical_events {theirs} (the times it copies)")
    return None


def _event_text(events: dict, name: str) -> str:
    """An event's time in `events` as a message gives it: to its last digit [s], or why not."""
    if name not in events:
        return "absent"
    return "null" if events[name] is None else f"{shorten(repr(events[name]))} s"


def _result_problem(meta: dict, transitions: list, scenario) -> str | None:
    """What is wrong with meta 'result' against the rest of the log, or None: a TrialResult's
    JSON form (its own relations: TrialResult), of the log's controller, of its scenario's
    object (`scenario`, the log's Scenario, when it stores one), its transitions the log's
    timeline ('transitions', [] when absent: one timeline, checked by _timeline_problem)."""
    from tegrasp_drake.control.grasp_modes import Transition
    from tegrasp_drake.scenario.trial_result import TrialResult
    data = meta.get("result")
    if data is None:
        return None
    try:
        result = TrialResult.from_dict(data)
    except ValueError as e:
        return f"meta 'result' is {shorten(str(e), 300)}"
    if "controller" in meta and "controller" in data and result.controller != meta["controller"]:
        return (f"meta 'controller' is '{shorten(meta['controller'])}', but its 'result' is of "
                f"'{shorten(result.controller)}'")
    if scenario is not None and "object" in data and result.object != scenario.object.name:
        return (f"meta 'result' is of object '{shorten(result.object)}', but its 'scenario' "
                f"grasps '{shorten(scenario.object.name)}'")
    if "transitions" in data:
        timeline = tuple(Transition.from_dict(entry) for entry in transitions)
        for k in range(max(len(timeline), len(result.transitions))):
            ours = timeline[k] if k < len(timeline) else None
            theirs = result.transitions[k] if k < len(result.transitions) else None
            if ours != theirs and ours is not None and theirs is not None:
                return (f"meta 'result' transitions[{k}] and the log's 'transitions[{k}]' "
                        f"({_transition_text(ours)}) differ in "
                        f"{_transition_differences(theirs, ours)} (a trial has one timeline)")
            if ours != theirs:
                return (f"meta 'result' transitions[{k}] is {_transition_text(theirs)}, but "
                        f"the log's 'transitions[{k}]' is {_transition_text(ours)} (a trial "
                        "has one timeline)")
    return None


def _transition_differences(result_entry, log_entry) -> str:
    """The fields two Transitions' JSON forms differ in, each with both values in full
    (repr: floats to their last digit, so no two sides print the same)."""
    theirs, ours = result_entry.as_dict(), log_entry.as_dict()
    fields = [key for key in (*ours, *(k for k in theirs if k not in ours))
              if theirs.get(key) != ours.get(key)]
    return "; ".join(f"'{key}': {_field_text(theirs, key)} in the result, "
                     f"{_field_text(ours, key)} in the log" for key in fields)


def _field_text(entry: dict, key: str) -> str:
    return shorten(repr(entry[key]), 120) if key in entry else "absent"


def _transition_text(entry) -> str:
    if entry is None:
        return "absent"
    return (f"{entry.from_mode.label} -> {entry.to_mode.label} at {number_text(entry.t)} s"
            f" ({entry.trigger.value})")


def meta_problem(meta: dict, arrays: dict, scenario=None) -> str | None:
    """What is wrong with a trial log's metadata, checked as a whole against the log's
    `arrays` (already checked by trial_arrays_problem) and its Scenario (`scenario`, None when
    it stores none), or None: transitions as Transition entries forming one timeline
    (_timeline_problem) with the scores its controller's detector gives, each field of
    META_FIELDS as it says, its result that of the log (_result_problem), its times within the
    log's span, phase starts (required with a result) agreeing with the timeline
    (_phase_starts_problem), `phase` indexing the phase names."""
    from tegrasp_drake.scenario.trial_result import transition_scores_problem
    from tegrasp_drake.control.grasp_modes import Mode, Transition
    transitions = meta.get("transitions", [])
    if not isinstance(transitions, list):
        return f"meta 'transitions' must be a list, got {type(transitions).__name__}"
    span = _time_span(arrays)
    limit = most_transitions(span[1] - span[0],
                             scenario.controller if scenario is not None else None)
    if len(transitions) > limit:  # before reading each of a crafted many
        return (f"meta 'transitions' holds {len(transitions)} entries; a trial's timeline of "
                f"{number_text(span[1] - span[0])} s holds at most {limit} (every correction "
                "a controller can make, and an Avoid and its return each Avoid cycle)")
    for k, entry in enumerate(transitions):
        try:
            if not isinstance(entry, dict) or not _is_time(entry.get("t")):
                raise ValueError("needs a finite time 't'")
            Transition.from_dict(entry)
        except (TypeError, ValueError) as e:
            if str(e).startswith("lacks the field"):
                return f"meta 'transitions[{k}]' {e}"
            return f"meta 'transitions[{k}]' is not a transition ({shorten(str(e))})"
    unknown = sorted(key for key in meta if key not in META_KEYS)
    if unknown:
        return (f"meta holds the key '{shorten(str(unknown[0]))}', which no trial log has (its "
                f"keys: {', '.join(sorted(META_KEYS))})")
    for key in REQUIRED_META_FIELDS:
        if key not in meta:
            what = META_FIELDS[key][0].removeprefix("be ")
            return f"meta lacks the field '{key}', which every trial log holds ({what})"
    for key, (what, is_valid) in META_FIELDS.items():
        if key in meta and not is_valid(meta[key]):
            return f"meta '{key}' must {what}, got {shorten(repr(meta[key]))}"
    problem = (_result_problem(meta, transitions, scenario) or _seed_problem(meta, scenario)
               or _copied_fields_problem(meta, scenario)
               or transition_scores_problem(list(map(Transition.from_dict, transitions)),
                                            meta.get("controller")))
    if problem:
        return problem if problem.startswith("meta") else f"meta {problem}"
    problem = (_sim_time_problem(meta, arrays) or _timeline_problem(transitions, span)
               or _times_problem(meta, span) or _hit_problem(meta, arrays, scenario, span)
               or _phase_starts_problem(meta))
    if problem:
        return problem
    if "result" in meta and "phase_starts" not in meta:  # run_trial writes both
        return ("meta lacks 'phase_starts', which a trial's log holds with its 'result' (when "
                "each mode of its timeline began)")
    phase = arrays["phase"]
    count = len(meta.get("mode_names") or meta.get("phases") or Mode)
    if phase.size and (not np.all(np.isfinite(phase)) or np.any(phase != np.round(phase))
                       or phase.min() < 0 or phase.max() >= count):
        return f"'phase' must hold indices 0 to {count - 1} of the {count} phase names"
    return phase_samples_problem(meta, arrays)


def _logged_timeline(meta: dict):
    """(change times [s], the value 'phase' holds from each on, the one before the first,
    the values' names) of the log's timeline: its transitions' Modes (a controller trial's),
    else its phases' starts in the order 'phases' lists them (an ideal grasp's); None when
    it records neither."""
    from tegrasp_drake.control.grasp_modes import Mode
    if "transitions" in meta:
        entries = meta["transitions"]
        first = Mode.from_label(entries[0]["from"]) if entries else Mode.REACH
        return ([entry["t"] for entry in entries],
                [int(Mode.from_label(entry["to"])) for entry in entries], int(first),
                [mode.label for mode in Mode])
    phases, starts = meta.get("phases"), meta.get("phase_starts")
    if not phases or not starts:
        return None
    started = sorted((starts[name], k) for k, name in enumerate(phases) if name in starts)
    if not started:
        return None
    return [t for t, _ in started], [k for _, k in started], started[0][1], list(phases)


def phase_samples_problem(meta: dict, arrays: dict) -> str | None:
    """The first 'phase' sample (indices checked by meta_problem) other than the value of the
    last change of the log's timeline (_logged_timeline) at or before its time, named with
    its sample and time, else None. A sample within _SAME_TIME_S of a change may hold the
    value before it or after it: the logger and the controller's update share that instant."""
    timeline = _logged_timeline(meta)
    if timeline is None:
        return None
    times, values, first, names = timeline
    t = np.asarray(arrays["t_slow"], dtype=float)
    phase = np.asarray(arrays["phase"], dtype=float)
    held = np.array([first, *values], dtype=float)
    changes = np.asarray(times, dtype=float)
    after = np.searchsorted(changes, t + _SAME_TIME_S, side="right")
    last = np.append(changes, -np.inf)[after - 1]  # the last change by then (none: -inf)
    near = last >= t - _SAME_TIME_S
    before = held[np.maximum(after - 1, 0)]
    wrong = np.flatnonzero((phase != held[after]) & ~(near & (phase == before)))
    if not wrong.size:
        return None
    k = wrong[0]
    which = ("its 'transitions'" if "transitions" in meta
             else "its 'phase_starts' of 'phases'")

    def named(value):
        label = names[int(value)] if int(value) < len(names) else "no such name"
        return f"{number_text(value)} ({shorten(label)})"
    return (f"'phase' sample {k} (t = {number_text(float(t[k]))} s) holds "
            f"{named(float(phase[k]))}, but {which} give {named(float(held[after[k]]))} then; "
            "a log's phases are those its timeline enters")


# The arrays sampled at each time base, and their columns (None: a vector).
_TIME_BASES = {"t_sa": {"taxels": 24, "true_taxels": 24},
               "t_ra": {"channels": 4, "pad_acceleration": 6},
               "t_slow": {"arm_q": 6, "arm_q_desired": 6, "gripper_command": 3,
                          "gripper_status": 8, "phase": None, "object_state": 13}}


# How far a time base's steps may differ from their median, relative to it. The loggers sample
# at a fixed period (LogVectorOutput's publish period: trial_log_writer), so the steps differ
# only by float64 rounding of the sample times: at most eps * t_end / period, 2e-11 for the
# 1 ms RA period over the longest run (275 s, grasp_diagram.longest_trial_s); measured in
# eleven real logs (12 to 18.5 s, four controllers): at most 2.2e-12. 1e-6 is five orders
# above that and far below any missing or displaced sample (a step off by its whole size).
STEP_TOLERANCE = 1e-6


def trial_arrays_problem(arrays: dict, scenario=None) -> str | None:
    """What is wrong with the trial-log arrays in `arrays`, or None: each time base at least
    two finite, increasing times sampled at one period (STEP_TOLERANCE), the bases covering
    one run at their loggers' periods (time_bases_problem), one row per time,
    finite signals within their physical ranges (out_of_range_signals, and sensor_range_problem
    for the sensors of `scenario`, the log's Scenario, or of any scenario when None), the
    channels Eq. 1-2 of the taxels and pad accelerations (logged_channels_problem). Every
    reader applies it."""
    problem = array_types_problem(arrays) or declared_arrays_problem(
        {name: (np.shape(array), np.asarray(array).dtype) for name, array in arrays.items()})
    if problem:
        return problem
    for time_name, columns in _TIME_BASES.items():
        if time_name not in arrays:
            continue
        times = arrays[time_name]
        if not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
            return f"'{time_name}' is not a finite, increasing list of times"
        steps = np.diff(times)
        period = float(np.median(steps))
        off = int(np.argmax(np.abs(steps - period)))
        if abs(steps[off] - period) > STEP_TOLERANCE * period:
            return (f"'{time_name}' is not sampled at one period: its step from sample {off} "
                    f"to {off + 1} is {number_text(float(steps[off]))} s, its others "
                    f"{number_text(period)} s")
    return (time_bases_problem(arrays, scenario)
            or nonfinite_signals(arrays) or out_of_range_signals(arrays)
            or sensor_range_problem(arrays, scenario) or logged_channels_problem(arrays)
            or object_path_problem(arrays, scenario)
            or object_orientation_problem(arrays) or joint_angle_problem(arrays))


def declared_arrays_problem(declared: dict) -> str | None:
    """What is wrong with the trial-log arrays' shapes, {name: (shape, dtype)} of those there,
    else None: each time base a vector of at least two times, each array sampled at one a row
    per time with its columns (_TIME_BASES). Asked of the .npy headers before any array is
    decompressed (a few-kB log may declare hundreds of MB; what they declare together is
    bounded by checked_npz_arrays' max_bytes), and by trial_arrays_problem of arrays in
    memory: one wording for both. Their dtypes are array_types_problem's, asked after the
    checksum (an edit to another dtype is said to be an edit)."""
    for time_name, columns in _TIME_BASES.items():
        if time_name not in declared:
            continue
        shape = tuple(declared[time_name][0])
        if len(shape) != 1 or shape[0] < 2:
            return (f"'{time_name}' holds {math.prod(shape)} time(s); a trial needs at least "
                    "two")
        for name, width in columns.items():
            if name not in declared:
                continue
            expected = (shape[0],) if width is None else (shape[0], width)
            if tuple(declared[name][0]) != expected:
                return (f"'{name}' has shape {tuple(declared[name][0])}, but {shape[0]} samples "
                        f"of '{time_name}' need {expected}")
    return None


def array_types_problem(arrays: dict) -> str | None:
    """The first array of ARRAY_FIELDS in `arrays` that is not float64 (what the loggers
    record and TrialLog.save writes), named with its dtype, else None."""
    for name in ARRAY_FIELDS:
        if name in arrays and np.asarray(arrays[name]).dtype != np.float64:
            return (f"'{name}' holds {np.asarray(arrays[name]).dtype} values, but a trial "
                    "log's arrays are float64")
    return None


def logger_periods(scenario) -> dict:
    """[s] The period each time base is logged at in a trial of `scenario` (a Scenario): the
    taxels at the SA rate, the RA channels at the RA rate, the rest at SLOW_LOG_PERIOD
    (trial_log_writer.AddTrialLogging)."""
    from tegrasp_drake.scenario.trial_log_writer import SLOW_LOG_PERIOD  # Drake: on use
    return {"t_sa": 1.0 / scenario.tactile.sample_rate_hz,
            "t_ra": 1.0 / scenario.vibration.sample_rate_hz, "t_slow": SLOW_LOG_PERIOD}


def time_bases_problem(arrays: dict, scenario=None) -> str | None:
    """What is wrong if the time bases in `arrays` (each finite, increasing, at one period)
    do not cover one run, or None. With `scenario` (the log's Scenario), each base's period is
    the one its logger writes at (logger_periods, within STEP_TOLERANCE: the same float
    rounding as its steps). Every logger samples from the simulation's start at its own period
    until the run ends, so the bases' first samples coincide and their last ones lie within
    one period of the run's end: two bases start and end within the slower of the periods
    (the loggers' with a scenario, else the bases' own steps). A bare recording (no scenario)
    may be sampled at any rates, so only its bases' span is checked."""
    periods = {name: float(np.median(np.diff(arrays[name]))) for name in _TIME_BASES
               if name in arrays}
    if scenario is not None:
        for name, expected in logger_periods(scenario).items():
            if name in periods and abs(periods[name] - expected) > STEP_TOLERANCE * expected:
                return (f"'{name}' is sampled every {number_text(periods[name])} s, but its "
                        f"scenario's logger writes it every {number_text(expected)} s")
        periods = {name: logger_periods(scenario)[name] for name in periods}
    names = list(periods)
    for k, first in enumerate(names):
        for second in names[k + 1:]:
            slower = max(periods[first], periods[second])
            for index, which in ((0, "starts"), (-1, "ends")):
                a, b = float(arrays[first][index]), float(arrays[second][index])
                if abs(a - b) > slower:
                    return (f"'{first}' {which} at {number_text(a)} s but '{second}' at "
                            f"{number_text(b)} s; a trial's time bases cover one run, "
                            f"starting and ending within {number_text(slower)} s (the slower "
                            "one's period)")
    return None


# How far a logged joint angle may lie past the JACO2's declared limit [rad]: the plant holds
# a limit as a compliant constraint, which the arm's drive can push a little past (real logs
# stay inside: joint 2 at 4.29 to 4.54 rad in [0.82, 5.46], joint 3 at 0.86 to 1.16 in
# [0.33, 5.95]); 0.01 rad is 0.6 degrees, a margin, not a pose.
JOINT_LIMIT_MARGIN_RAD = 0.01


def joint_angle_problem(arrays: dict) -> str | None:
    """The first logged joint angle (arm_q, arm_q_desired; finite, of their shape) outside its
    joint's declared limits (modelgen/jaco2_dh.JOINTS: joints 2 and 3; the others are
    continuous) by more than JOINT_LIMIT_MARGIN_RAD, named, else None."""
    from tegrasp_drake.modelgen.jaco2_dh import JOINTS
    for name in ("arm_q", "arm_q_desired"):
        if name not in arrays:
            continue
        q = np.asarray(arrays[name], dtype=float)
        for column, joint in enumerate(JOINTS):
            if joint.lower is None or column >= q.shape[1]:
                continue
            low, high = joint.lower - JOINT_LIMIT_MARGIN_RAD, joint.upper + JOINT_LIMIT_MARGIN_RAD
            outside = (q[:, column] < low) | (q[:, column] > high)
            if np.any(outside):
                return (f"'{name}' column {column} (joint {column + 1}) holds "
                        f"{number_text(float(q[outside, column][0]))} rad, outside the "
                        f"JACO2's limits {number_text(joint.lower)} to "
                        f"{number_text(joint.upper)} rad")
    return None


# How far the norm of the object's logged orientation quaternion may be from 1. object_state is
# the free body's MultibodyPlant state, [qw qx qy qz, x y z, w (3), v (3)]; the integrator
# lets the quaternion's norm drift (the logged state is not renormalized). Measured in
# eleven real logs (12 to 18.5 s, four controllers): |norm - 1| at most 2.4e-4 (a 13 s
# taxel-aware trial); a drift growing in proportion to time would reach 1.6e-3 over the
# longest run (85 s). 1e-2 is six times that; a zero or a scaled quaternion is not
# an orientation.
QUATERNION_NORM_TOLERANCE = 1e-2


def object_orientation_problem(arrays: dict) -> str | None:
    """What is wrong if an orientation in `arrays`' object_state (finite, of its shape) is not
    a unit quaternion within QUATERNION_NORM_TOLERANCE, else None."""
    if "object_state" not in arrays:
        return None
    norms = np.linalg.norm(np.asarray(arrays["object_state"], dtype=float)[:, :4], axis=1)
    off = np.flatnonzero(np.abs(norms - 1.0) > QUATERNION_NORM_TOLERANCE)
    if off.size:
        return (f"'object_state' sample {off[0]} holds an orientation quaternion of norm "
                f"{number_text(float(norms[off[0]]))} (columns 0 to 3, w x y z); a rigid "
                f"body's orientation is a unit quaternion (within {QUATERNION_NORM_TOLERANCE})")
    return None


# The logged channels with a physical range: (their columns' names, the columns checked, low,
# high, why). Measured taxels, pad accelerations and the object's position have the ranges of
# the log's sensors and workspace instead (sensor_range_problem), and so has true_taxels (the
# ideal force transducer's); SA has none here (the force transducer's noise dips below zero at
# rest).
_PHYSICAL_RANGES = {
    "gripper_command": (ru.COMMAND_NAMES, range(ru.COMMAND_SIZE), 0.0, ru.BYTE_MAX,
                        "the 2F-85's request registers are bytes"),
    "gripper_status": (ru.STATUS_NAMES, range(ru.STATUS_SIZE), 0.0, ru.BYTE_MAX,
                       "the 2F-85's status registers are bytes"),
    "channels": (CHANNEL_NAMES, RA_CHANNELS, 0.0, None,
                 "RA is the magnitude of a pad's vibration (Eq. 2) [m/s^2]"),
}


def out_of_range_signals(arrays: dict) -> str | None:
    """The first logged channel in `arrays` (finite, of its shape) outside its physical range
    (_PHYSICAL_RANGES), named with its column and a value, else None."""
    for name, (names, columns, low, high, why) in _PHYSICAL_RANGES.items():
        if name not in arrays:
            continue
        array = np.asarray(arrays[name], dtype=float)
        for column in columns:
            if column >= array.shape[1]:
                continue
            values = array[:, column]
            outside = (values < low) | (values > high if high is not None else False)
            if np.any(outside):
                bounds = f"0 to {number_text(high)}" if high is not None else "at least 0"
                return (f"'{name}' column {column} ({names[column]}) holds "
                        f"{number_text(float(values[outside][0]))}, outside {bounds} ({why})")
    return None


def nonfinite_signals(arrays: dict) -> str | None:
    """What is wrong if any logged array present in `arrays` (the signals, and the states a
    figure or an outcome reads: object_state, arm_q, ...) holds NaN or infinities (a trial
    log's, or the part of one a reader loads), else None."""
    bad = [name for name in ARRAY_FIELDS if name in arrays and name != "phase"  # meta_problem's
           and np.asarray(arrays[name]).dtype.kind in "fc"
           and not np.all(np.isfinite(arrays[name]))]
    if bad:
        return f"the arrays {bad} hold NaN or infinite values"
    return None


def logged_scenario(meta: dict):
    """(the Scenario of meta 'scenario', None) when the log stores one, (None, None) when not,
    or (None, what is wrong) when its text is not a scenario or not a simulated one."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import scenario_from_yaml  # Drake: on use
    text = meta.get("scenario")
    if not isinstance(text, str):
        return None, None  # none stored, or not text (meta_problem names it)
    try:
        scenario = scenario_from_yaml(text, "meta 'scenario'")
    except ConfigError as e:
        return None, shorten(str(e), 300)
    from tegrasp_drake.hardware.config import HardwareStationConfig
    if isinstance(scenario.station, HardwareStationConfig):  # no trial log of a real run
        return None, ("meta 'scenario' names the real devices (station: "
                      "!HardwareStationConfig), but a trial log is written by a simulated "
                      "trial (tegrasp trial); a run on the devices is an LCM log, read by "
                      "tegrasp replay")
    return scenario, None


@dataclasses.dataclass(frozen=True)
class SensorBounds:
    """The physical range of the logged sensor channels and object position, each from where
    its model is declared: taxels [low, high] (N, or counts: taxel_reading_range),
    pad_acceleration, the largest |reading| [m/s^2] (pad_reading_bound_mps2), object_xyz,
    the (low, high) [m, world] of the object's x, y and z over the whole log
    (object_position_bounds), object_speed [m/s] (object_speed_bound_mps) and gravity
    [m/s^2], from which object_path_problem bounds each sample by its own time."""
    taxels: tuple[float, float]
    taxel_unit: str
    pad_acceleration: float
    object_xyz: tuple
    whose: str
    object_speed: float = 0.0
    gravity: float = 0.0
    true_taxels: tuple[float, float] = (0.0, math.inf)


# Why the noise-free taxel forces (true_taxels) lie where sensor_bounds puts them.
_TRUE_TAXELS_WHY = ("a noise-free taxel force: what an ideal force taxel (no offset, noise or "
                    "quantization) reads, a share of its pad's normal force")


def ideal_taxel_range() -> tuple[float, float]:
    """[N] The range of a noise-free taxel force (true_taxels): taxel_reading_range of the
    ideal force transducer (no offset, noise or quantization), 0 to the 2F-85's whole grip
    force (tactile_pads.taxel_reading_range)."""
    from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig, taxel_reading_range
    return tuple(float(value) for value in taxel_reading_range(TactileSensorConfig(
        transducer="force", offset_n=0.0, noise_std_n=0.0, quantization_n=0.0)))


def _pad_speed_mps() -> float:
    """The fastest a pad moves [m/s]: with the hand (HAND_SPEED_BOUND_MPS), and its finger
    closing at the 2F-85's top speed."""
    from tegrasp_drake.rig.jaco_velocity_tracker import HAND_SPEED_BOUND_MPS
    return HAND_SPEED_BOUND_MPS + ru.SPEED_MAX_MPS


def _hit_impulse_n_s(disturbance) -> float:
    """The impulse [N s] of a scenario's hit (0 without one)."""
    if disturbance.hit_time_s < 0:
        return 0.0
    return math.hypot(*disturbance.hit_force_n) * disturbance.hit_duration_s


def widest_configs():
    """(tactile configs, vibration configs, largest hit impulse [N s], shortest plant step
    [s]): the corners of the declared ranges at which the sensors' ranges are widest (a
    log that stores no scenario may be of any)."""
    from tegrasp_drake.rig.ranges import field_range
    from tegrasp_drake.scenario.scenario import MAX_HIT_FORCE_N, MIN_TIME_STEP_S
    from tegrasp_drake.simulation.body_force_pulse import DisturbanceConfig
    from tegrasp_drake.simulation.capacitive_taxels import CapacitiveTaxelConfig
    from tegrasp_drake.simulation.pad_vibration_sensor import FilmConfig, VibrationSensorConfig
    from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig

    def low(cls, name):
        return field_range(cls, name).low

    def high(cls, name):
        return field_range(cls, name).high

    T, C, F, V = TactileSensorConfig, CapacitiveTaxelConfig, FilmConfig, VibrationSensorConfig
    noisy = C(noise_std_counts=high(C, "noise_std_counts"))
    tactile = [T(transducer="force", offset_n=offset, noise_std_n=high(T, "noise_std_n"),
                 quantization_n=high(T, "quantization_n"))
               for offset in (low(T, "offset_n"), high(T, "offset_n"))]
    tactile.append(T(capacitive=dataclasses.replace(noisy, output="counts")))
    # The most newtons a count is: the stiffest pad, the thinnest dielectric, the lightest
    # calibration weight, the least gap left.
    tactile.append(T(pad_modulus_pa=high(T, "pad_modulus_pa"), capacitive=dataclasses.replace(
        noisy, relative_permittivity=low(C, "relative_permittivity"),
        calibration_force_n=low(C, "calibration_force_n"),
        minimum_gap_fraction=low(C, "minimum_gap_fraction"))))
    # The least sensitive film (S = G_Q / (w^2 C_f)) read without a converter at the widest swing.
    film = F(film_charge_gain_c_per_m=low(F, "film_charge_gain_c_per_m"),
             mode_frequency_hz=high(F, "mode_frequency_hz"),
             feedback_capacitance_f=high(F, "feedback_capacitance_f"))
    vibration = [V(film=film, amplifier_swing_v=high(V, "amplifier_swing_v"), adc_input="ideal"),
                 V(transducer="accelerometer", noise_std_mps2=high(V, "noise_std_mps2"))]
    impulse = MAX_HIT_FORCE_N * high(DisturbanceConfig, "hit_duration_s")
    return tactile, vibration, impulse, MIN_TIME_STEP_S


def sensor_bounds(scenario, duration_s: float) -> SensorBounds:
    """The SensorBounds of a log of `scenario` (a Scenario; None: the widest of any scenario)
    lasting duration_s [s] of simulated time."""
    from pydrake.multibody.tree import UniformGravityFieldElement  # the plant's gravity
    from tegrasp_drake.scenario.object_placement import (object_position_bounds,
                                                         object_speed_bound_mps)
    from tegrasp_drake.simulation.pad_vibration_sensor import pad_reading_bound_mps2
    from tegrasp_drake.simulation.tactile_pads import taxel_reading_range
    if scenario is None:
        tactile, vibration, impulse, time_step = widest_configs()
        whose, unit = "any scenario's", "N or counts"
    else:
        tactile, vibration = [scenario.tactile], [scenario.vibration]
        impulse, time_step = _hit_impulse_n_s(scenario.disturbance), scenario.plant_config.time_step
        counts = (scenario.tactile.transducer == "capacitive"
                  and scenario.tactile.capacitive.output == "counts")
        whose, unit = "its scenario's", "counts" if counts else "N"
    taxel_ranges = [taxel_reading_range(config) for config in tactile]
    pad = max(pad_reading_bound_mps2(config, time_step_s=time_step,
                                     pad_speed_mps=_pad_speed_mps()) for config in vibration)
    speed, gravity = object_speed_bound_mps(impulse), UniformGravityFieldElement.kDefaultStrength
    xyz = object_position_bounds(duration_s, speed, gravity)
    return SensorBounds(taxels=(min(r[0] for r in taxel_ranges), max(r[1] for r in taxel_ranges)),
                        taxel_unit=unit, pad_acceleration=pad, object_xyz=xyz, whose=whose,
                        object_speed=speed, gravity=gravity, true_taxels=ideal_taxel_range())


def _sensor_limits(bounds: SensorBounds, duration_s: float) -> list[tuple]:
    """(array, column, its name or "", low, high, unit, why) of each column sensor_range_problem
    checks: the taxels, their noise-free forces and the pads' accelerations, then Eq. 1's SA
    (a pad's 12 taxels' sum) and Eq. 2's RA (the size of its 3 axes' vector) computed from
    them (a sample out of range is named before the channel it makes so), the object's
    position (object_state 4 to 6)."""
    whose, (low, high), unit = bounds.whose, bounds.taxels, bounds.taxel_unit
    pad = bounds.pad_acceleration
    taxel_why = f"what {whose} taxels can read (their model, noise to 10 sigma)"
    pad_why = f"what {whose} RA transducer can read (its full scale)"
    rows = [("taxels", column, "", low, high, unit, taxel_why)
            for column in range(len(CHANNEL_NAMES) // 2 * TAXELS_PER_PAD)]
    rows += [("true_taxels", column, "", *bounds.true_taxels, "N", _TRUE_TAXELS_WHY)
             for column in range(len(CHANNEL_NAMES) // 2 * TAXELS_PER_PAD)]
    rows += [("pad_acceleration", column, "", -pad, pad, "m/s^2", pad_why)
             for column in range(len(RA_CHANNELS) * PAD_ACCELERATION_AXES)]
    rows += [("channels", column, CHANNEL_NAMES[column], TAXELS_PER_PAD * low,
              TAXELS_PER_PAD * high, unit, f"{TAXELS_PER_PAD} times {taxel_why}")
             for column in SA_CHANNELS]
    rows += [("channels", column, CHANNEL_NAMES[column], 0.0,
              math.sqrt(PAD_ACCELERATION_AXES) * pad, "m/s^2",
              f"the size of {PAD_ACCELERATION_AXES} axes' {pad_why}") for column in RA_CHANNELS]
    object_why = (f"where {whose} object can be by {number_text(duration_s)} s (on the table at "
                  "the start, moving no faster than the hand or a hit drives it, or falling)")
    rows += [("object_state", 4 + k, axis, *bounds.object_xyz[k], "m", object_why)
             for k, axis in enumerate("xyz")]
    return rows


def sensor_range_problem(arrays: dict, scenario=None) -> str | None:
    """The first logged taxel reading, SA or RA sample, pad acceleration or object position in
    `arrays` (finite, of their shapes) outside the range its sensors or the workspace give it
    (sensor_bounds of `scenario`, over the log's simulated time), named with its column and
    value, else None."""
    if not any(name in arrays for name in ("taxels", "true_taxels", "channels",
                                           "pad_acceleration", "object_state")):
        return None
    duration = _time_span(arrays)[1]
    for name, column, label, low, high, unit, why in _sensor_limits(
            sensor_bounds(scenario, duration), duration):
        if name not in arrays or column >= arrays[name].shape[1]:
            continue
        values = np.asarray(arrays[name][:, column], dtype=float)
        outside = np.flatnonzero((values < low) | (values > high))
        if outside.size:
            k = outside[0]
            named = f" ({label})" if label else ""
            return (f"'{name}' sample {k} column {column}{named} holds "
                    f"{number_text(float(values[k]))} {unit}, outside {number_text(low)} to "
                    f"{number_text(high)} {unit}, {why}")
    return None


# [m] What the object's logged position may move between two samples beyond its speed bound:
# the contact solver's penetration corrections are sub-millimetre (a pad's squeeze of a held
# object is 0.1 mm, grasp_outcome.PADS_MEET_OPENING_M's note); 1 mm is ten times that.
OBJECT_STEP_SLACK_M = 1e-3


def object_path_problem(arrays: dict, scenario=None) -> str | None:
    """The first object position in `arrays` (object_state 4 to 6 at t_slow; finite, of their
    shapes) off where the object can be by its own time (object_position_bounds at that time),
    or that moved from the sample before farther than it can move (sideways: its sideways speed
    bound; vertically: the speed bound plus what gravity adds by then; each plus
    OBJECT_STEP_SLACK_M), named with its sample and time; else None.
    sensor_range_problem checks the same bounds over the whole log."""
    from tegrasp_drake.scenario.object_placement import (object_position_bounds,
                                                         object_sideways_speed_bound_mps)
    if "object_state" not in arrays or "t_slow" not in arrays or not len(arrays["t_slow"]):
        return None
    t = np.asarray(arrays["t_slow"], dtype=float)
    xyz = np.asarray(arrays["object_state"], dtype=float)[:, 4:7]
    bounds = sensor_bounds(scenario, float(t[-1]))
    elapsed = np.maximum(t, 0.0)
    for k, ((low, high), axis) in enumerate(zip(
            object_position_bounds(elapsed, bounds.object_speed, bounds.gravity), "xyz")):
        outside = np.flatnonzero((xyz[:, k] < low) | (xyz[:, k] > high))
        if outside.size:
            i = outside[0]
            return (f"'object_state' sample {i} (t = {number_text(float(t[i]))} s) puts the "
                    f"object's {axis} at {number_text(float(xyz[i, k]))} m, outside "
                    f"{number_text(float(np.broadcast_to(low, t.shape)[i]))} to "
                    f"{number_text(float(np.broadcast_to(high, t.shape)[i]))} m, where "
                    f"{bounds.whose} object can be by then (on the table at the start, moving "
                    "no faster than the hand or a hit drives it, or falling)")
    if len(t) < 2:
        return None
    # Sideways (world x, y) and vertically (world z) apart: gravity speeds the object only
    # along z (a fall: the speed bound plus g t by then), sideways it is bounded by what can
    # push it (the hand carrying it, the scenario's hit) and a fall turned by a contact
    # (object_placement.object_sideways_speed_bound_mps), however long the trial has run.
    dt, step = np.diff(t), np.diff(xyz, axis=0)
    sideways = object_sideways_speed_bound_mps(bounds.object_speed, bounds.gravity)
    for name, moved, reach in (
            ("sideways", np.linalg.norm(step[:, :2], axis=1),
             sideways * dt + OBJECT_STEP_SLACK_M),
            ("vertically", np.abs(step[:, 2]),
             (bounds.object_speed + bounds.gravity * elapsed[1:]) * dt + OBJECT_STEP_SLACK_M)):
        too_far = np.flatnonzero(moved > reach)
        if too_far.size:
            i = too_far[0] + 1
            return (f"'object_state' sample {i} (t = {number_text(float(t[i]))} s) puts the "
                    f"object {number_text(float(moved[i - 1]))} m {name} from the sample "
                    f"before, more than the {number_text(float(reach[i - 1]))} m "
                    f"{bounds.whose} object can move {name} in "
                    f"{number_text(float(t[i] - t[i - 1]))} s")
    return None
