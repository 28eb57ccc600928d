"""A memorized tactile event, and its files: one JSON file per event plus an index.

Layout (see FORMAT.md for every field):

    events/index.json                      the list of events, with their metadata
    events/<object>/<transition>.json      one event: four max-normalised windows

Files are plain JSON, written with sorted keys, one-space indent, each window on one line
and Python's shortest round-trip float repr, so that a file reads back to the same float64 values and re-running
the record step on the same data produces identical bytes. Any problem when loading (a
missing, truncated or invalid file, a wrong format_version, a missing field, a window of
the wrong length) raises MemorizedEventError, whose message names the file and the command
that remakes it.
"""

import dataclasses
import importlib.metadata
import json
import math
import os
import pathlib
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

import tegrasp_drake
from tegrasp_drake.rig.channels import CHANNEL_NAMES
from tegrasp_drake.rig.files import interruptions_deferred, staged_file
from tegrasp_drake.rig.objects import DESCRIPTION_FIELDS, OBJECT_NAME_PATTERN
from tegrasp_drake.tactile.sampling import samples_per_window
from tegrasp_drake.events.transitions import (
    REQUIRED_TRANSITIONS, TRANSITIONS, transition_order)

FORMAT_VERSION = 2
# Version 1 files lack `object_description`; they are read by taking it from the object
# section of their `scenario` text (FORMAT.md, Versions).
MIGRATED_VERSIONS = (1,)
EVENT_FORMAT = "tegrasp.memorized_event"
INDEX_FORMAT = "tegrasp.memorized_event_index"
INDEX_FILE = "index.json"
RECORD_COMMAND = "tegrasp record-events"
NORMALIZATION = "max"
_NAME_PATTERN = OBJECT_NAME_PATTERN
_NORMALIZATION_TOLERANCE = 1e-9


class MemorizedEventError(Exception):
    """A memorized event or index file is missing or unusable."""

    def __init__(self, path, problem: str, object_name: str | None = None):
        self.path = pathlib.Path(path)
        remake = f"{RECORD_COMMAND} --object {object_name}" if object_name else RECORD_COMMAND
        super().__init__(f"{self.path}: {problem}. Remake it with `{remake}`.")


@dataclasses.dataclass(frozen=True, eq=False)
class MemorizedEvent:
    """The four channels of one object's tactile event around one grasp transition.

    sa: (2, window_s * sa_rate_hz) SA windows [left, right], each divided by its max |value|.
    ra: (2, window_s * ra_rate_hz) RA windows [left, right], likewise.
    The window starts `pre_transition_s` [s] before the transition's physical event, which
    happened at `transition_time_s` [s] in the source trial.
    """
    object_name: str
    transition: str
    sa: np.ndarray
    ra: np.ndarray
    sa_rate_hz: float  # [Hz]
    ra_rate_hz: float  # [Hz]
    window_s: float = 0.5  # [s]
    pre_transition_s: float = 0.25  # [s]
    transition_time_s: float = 0.0  # [s] in the source trial
    scenario: str = ""  # name or text of the scenario that produced the trial
    package_versions: Mapping[str, str] = dataclasses.field(default_factory=dict)
    # The object the event was felt on: {shape, size, mass, friction, file}
    # (rig/objects.object_description); {} when unknown (synthetic events in tests).
    object_description: Mapping = dataclasses.field(default_factory=dict)
    normalization: str = NORMALIZATION
    channel_names: tuple[str, ...] = CHANNEL_NAMES

    def __post_init__(self):
        if not _NAME_PATTERN.match(self.object_name):
            raise ValueError(f"object name '{self.object_name}' must match "
                             f"{_NAME_PATTERN.pattern} (it names a folder)")
        transition_order(self.transition)
        if tuple(self.channel_names) != CHANNEL_NAMES:
            raise ValueError(f"channels {list(self.channel_names)} must be "
                             f"{list(CHANNEL_NAMES)}")
        if self.normalization != NORMALIZATION:
            raise ValueError(f"normalisation '{self.normalization}' is not "
                             f"'{NORMALIZATION}'")
        if not 0.0 <= self.pre_transition_s <= self.window_s:
            raise ValueError(f"pre_transition_s {self.pre_transition_s} must lie within "
                             f"the {self.window_s} s window")
        for name, rate in (("sa", self.sa_rate_hz), ("ra", self.ra_rate_hz)):
            window = np.array(getattr(self, name), dtype=float)
            expected = (2, samples_per_window(self.window_s, rate))
            if window.shape != expected:
                raise ValueError(f"'{name}' has shape {window.shape}; {self.window_s} s at "
                                 f"{rate} Hz for two fingers needs {expected}")
            if not np.all(np.isfinite(window)):
                raise ValueError(f"'{name}' holds non-finite values")
            peaks = np.max(np.abs(window), axis=1)
            if np.any((peaks != 0.0) & (np.abs(peaks - 1.0) > _NORMALIZATION_TOLERANCE)):
                raise ValueError(f"'{name}' is not normalised by its maximum "
                                 f"(max |value| per finger: {peaks.tolist()})")
            window.setflags(write=False)
            object.__setattr__(self, name, window)
        versions = dict(self.package_versions)
        if not all(isinstance(k, str) and isinstance(v, str) for k, v in versions.items()):
            raise ValueError("package_versions must map package names to version text")
        object.__setattr__(self, "package_versions", versions)
        object.__setattr__(self, "channel_names", tuple(self.channel_names))
        description = dict(self.object_description)
        if description and sorted(description) != sorted(DESCRIPTION_FIELDS):
            raise ValueError(f"object_description has fields {sorted(description)}; "
                             f"expected {sorted(DESCRIPTION_FIELDS)}")
        object.__setattr__(self, "object_description", description)

    def channel(self, name: str) -> np.ndarray:
        """The window of channel `name` (one of CHANNEL_NAMES)."""
        index = CHANNEL_NAMES.index(name)
        return self.sa[index] if index < 2 else self.ra[index - 2]

    def channel_rate_hz(self, name: str) -> float:
        return self.sa_rate_hz if CHANNEL_NAMES.index(name) < 2 else self.ra_rate_hz

    def sample_times(self, name: str) -> np.ndarray:
        """Times [s] of channel `name`'s samples relative to the transition."""
        rate = self.channel_rate_hz(name)
        return np.arange(len(self.channel(name))) / rate - self.pre_transition_s

    def zero_channels(self) -> list[str]:
        """Names of the channels that are zero throughout the window."""
        return [name for name in CHANNEL_NAMES if not np.any(self.channel(name))]

    def relative_path(self) -> str:
        """Path of the event's file inside the events folder."""
        return f"{self.object_name}/{self.transition}.json"


def current_package_versions() -> dict[str, str]:
    """Versions of the packages that shape a recording, for the files' provenance."""
    versions = {"tegrasp-drake": tegrasp_drake.__version__}
    for package in ("drake", "numpy"):
        try:
            versions[package] = importlib.metadata.version(package)
        except importlib.metadata.PackageNotFoundError:
            versions[package] = "unknown"
    return versions


# ---- Writing -------------------------------------------------------------------------


def _summary(event: MemorizedEvent) -> dict:
    """The metadata shared by an event's file and its index entry."""
    return {
        "object": event.object_name,
        "transition": event.transition,
        "channels": list(event.channel_names),
        "sa_rate_hz": float(event.sa_rate_hz),
        "ra_rate_hz": float(event.ra_rate_hz),
        "window_s": float(event.window_s),
        "pre_transition_s": float(event.pre_transition_s),
        "normalization": event.normalization,
        "scenario": event.scenario,
        "package_versions": dict(sorted(event.package_versions.items())),
        "object_description": dict(event.object_description),
    }


def event_to_json(event: MemorizedEvent) -> dict:
    """The JSON object stored in an event's file."""
    data = _summary(event)
    data.update({
        "format": EVENT_FORMAT,
        "format_version": FORMAT_VERSION,
        "physical_event": TRANSITIONS[event.transition],
        "transition_time_s": float(event.transition_time_s),
        "samples": {name: event.channel(name).tolist() for name in CHANNEL_NAMES},
    })
    return data


def _render(value, indent: str = "") -> str:
    """JSON text with sorted keys, one item per line, but each list of numbers on one line."""
    inner = indent + " "
    if isinstance(value, dict) and value:
        items = [f"{inner}{json.dumps(key)}: {_render(value[key], inner)}"
                 for key in sorted(value)]
        return "{\n" + ",\n".join(items) + "\n" + indent + "}"
    if isinstance(value, list) and value and not all(_is_number(v) for v in value):
        items = [inner + _render(item, inner) for item in value]
        return "[\n" + ",\n".join(items) + "\n" + indent + "]"
    return json.dumps(value, allow_nan=False)


def _dumps(data: dict) -> str:
    return _render(data) + "\n"


def _sorted_events(events: Iterable[MemorizedEvent]) -> list[MemorizedEvent]:
    return sorted(events, key=lambda e: (e.object_name, transition_order(e.transition)))


def save_memorized_events(events_dir, events: Iterable[MemorizedEvent], *,
                          keep_other_objects: bool = True,
                          required: Sequence[str] = REQUIRED_TRANSITIONS) -> list[pathlib.Path]:
    """Write the events' files and the index; returns the paths written.

    Each object given replaces that object's previous events (stale files of that object
    are removed). With keep_other_objects, the index keeps the entries of objects not given
    (so recording one object keeps the others); otherwise the index lists only `events`.
    Every object must have the `required` transitions (REQUIRED_TRANSITIONS; a corrective
    events folder: CORRECTIVE_TRANSITIONS).
    """
    events_dir = pathlib.Path(events_dir)
    events = _sorted_events(events)
    keys = [(e.object_name, e.transition) for e in events]
    if len(set(keys)) != len(keys):
        raise ValueError("two events share an object and a transition")
    objects = sorted({e.object_name for e in events})
    for object_name in objects:
        missing = [t for t in required if (object_name, t) not in keys]
        if missing:
            raise ValueError(f"object '{object_name}' lacks transitions {missing}")
    kept_entries = []
    if keep_other_objects and (events_dir / INDEX_FILE).exists():
        kept_entries = [entry for entry in read_index(events_dir)
                        if entry["object"] not in objects]
    entries = kept_entries + [dict(_summary(e), file=e.relative_path()) for e in events]
    entries.sort(key=lambda entry: (entry["object"], transition_order(entry["transition"])))
    index = {"format": INDEX_FORMAT, "format_version": FORMAT_VERSION,
             "remake_command": RECORD_COMMAND, "events": entries}
    # All or nothing: every file is staged beside its target first, then the renames and
    # the stale files' removal commit together with Ctrl-C held back, the index last.
    staged = []
    events_dir.mkdir(parents=True, exist_ok=True)
    try:
        for event in events:
            path = events_dir / event.relative_path()
            path.parent.mkdir(parents=True, exist_ok=True)
            staged.append((staged_file(path, _dumps(event_to_json(event))), path))
        staged.append((staged_file(events_dir / INDEX_FILE, _dumps(index)),
                       events_dir / INDEX_FILE))
        with interruptions_deferred():
            for object_name in objects:
                object_dir = events_dir / object_name
                new_files = {f"{e.transition}.json" for e in events
                             if e.object_name == object_name}
                if object_dir.is_dir():
                    for stale in sorted(object_dir.glob("*.json")):
                        if stale.name not in new_files:
                            stale.unlink()
            for temporary, path in staged:
                os.replace(temporary, path)
    except BaseException:
        for temporary, _ in staged:
            if temporary.exists():
                temporary.unlink()
        raise
    written = [path for _, path in staged]
    return written


# ---- Reading -------------------------------------------------------------------------


def _read_json(path: pathlib.Path, expected_format: str, object_name: str | None) -> dict:
    if not path.is_file():
        raise MemorizedEventError(path, "file is missing", object_name)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except UnicodeDecodeError as error:
        raise MemorizedEventError(path, f"is not UTF-8 text ({error})", object_name) from None
    except json.JSONDecodeError as error:
        raise MemorizedEventError(
            path, f"is not valid JSON, perhaps truncated ({error})", object_name) from None
    if not isinstance(data, dict) or data.get("format") != expected_format:
        raise MemorizedEventError(path, f"is not a '{expected_format}' file", object_name)
    version = data.get("format_version")
    if version != FORMAT_VERSION and version not in MIGRATED_VERSIONS:
        raise MemorizedEventError(
            path, f"has format_version {version!r}; this tegrasp reads versions "
            f"{', '.join(map(str, (*MIGRATED_VERSIONS, FORMAT_VERSION)))}", object_name)
    return data


def _description_from_scenario(scenario_text: str, path, object_name) -> dict:
    """A version-1 file's object description: the object section of its scenario text."""
    import yaml
    try:
        scenario = yaml.safe_load(scenario_text)
        obj = scenario["object"]
        description = {name: obj.get(name, "") for name in DESCRIPTION_FIELDS}
        description["size"] = [float(v) for v in description["size"]]
        description["mass"], description["friction"] = (float(obj["mass"]),
                                                        float(obj["friction"]))
        if not description["shape"] or not description["size"]:
            raise KeyError("shape")
    except (yaml.YAMLError, TypeError, KeyError, ValueError):
        raise MemorizedEventError(
            path, "is a format_version 1 file whose scenario text does not describe the "
            "object (shape, size, mass, friction), so it cannot be checked against the "
            "object it is used for", object_name) from None
    return description


def _object_description(data: dict, path, object_name) -> dict:
    """The file's object description (version 2), or its migration (version 1)."""
    if data.get("format_version") in MIGRATED_VERSIONS:
        return _description_from_scenario(
            _field(data, "scenario", "text", path, object_name), path, object_name)
    description = _field(data, "object_description", "object", path, object_name)
    if not description:
        return {}  # unknown (synthetic events); the controller refuses such events
    for name in DESCRIPTION_FIELDS:
        if name not in description:
            raise MemorizedEventError(path, f"field 'object_description.{name}' is missing",
                                      object_name)
    ok = (isinstance(description["shape"], str) and isinstance(description["file"], str)
          and isinstance(description["size"], list)
          and all(_is_number(v) for v in description["size"])
          and _is_number(description["mass"]) and _is_number(description["friction"]))
    if not ok:
        raise MemorizedEventError(path, "field 'object_description' must hold shape and file "
                                  "(text), size (list of numbers), mass and friction "
                                  "(numbers)", object_name)
    return dict(description)


def _is_number(value) -> bool:
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value))


_KINDS = {"number": _is_number, "text": lambda v: isinstance(v, str),
          "list": lambda v: isinstance(v, list), "object": lambda v: isinstance(v, dict)}


def _field(data: dict, name: str, kind: str, path, object_name):
    """data[name], checked to be of `kind` (a key of _KINDS)."""
    if name not in data:
        raise MemorizedEventError(path, f"field '{name}' is missing", object_name)
    if not _KINDS[kind](data[name]):
        article = "an" if kind == "object" else "a"
        raise MemorizedEventError(path, f"field '{name}' is not {article} {kind}",
                                  object_name)
    return data[name]


def _samples(data: dict, name: str, length: int, path, object_name) -> list[float]:
    samples = _field(data, "samples", "object", path, object_name)
    if name not in samples:
        raise MemorizedEventError(path, f"field 'samples.{name}' is missing", object_name)
    values = samples[name]
    if not isinstance(values, list) or not all(_is_number(v) for v in values):
        raise MemorizedEventError(
            path, f"field 'samples.{name}' is not a list of finite numbers", object_name)
    if len(values) != length:
        raise MemorizedEventError(
            path, f"field 'samples.{name}' has {len(values)} samples; the window needs "
            f"{length}", object_name)
    return values


def read_memorized_event(path, *, object_name: str | None = None,
                         transition: str | None = None) -> MemorizedEvent:
    """Load one event file; object_name and transition, if given, must match its content."""
    path = pathlib.Path(path)
    data = _read_json(path, EVENT_FORMAT, object_name)
    file_object = _field(data, "object", "text", path, object_name)
    owner = object_name or file_object
    numbers = {name: float(_field(data, name, "number", path, owner))
               for name in ("sa_rate_hz", "ra_rate_hz", "window_s", "pre_transition_s",
                            "transition_time_s")}
    texts = {name: _field(data, name, "text", path, owner)
             for name in ("transition", "normalization", "scenario")}
    channels = _field(data, "channels", "list", path, owner)
    versions = _field(data, "package_versions", "object", path, owner)
    description = _object_description(data, path, owner)
    try:
        lengths = [samples_per_window(numbers["window_s"], numbers[rate])
                   for rate in ("sa_rate_hz", "sa_rate_hz", "ra_rate_hz", "ra_rate_hz")]
    except ValueError as error:
        raise MemorizedEventError(path, str(error), owner) from None
    windows = [_samples(data, name, length, path, owner)
               for name, length in zip(CHANNEL_NAMES, lengths)]
    try:
        event = MemorizedEvent(
            object_name=file_object, transition=texts["transition"],
            sa=np.array(windows[:2], dtype=float), ra=np.array(windows[2:], dtype=float),
            sa_rate_hz=numbers["sa_rate_hz"], ra_rate_hz=numbers["ra_rate_hz"],
            window_s=numbers["window_s"], pre_transition_s=numbers["pre_transition_s"],
            transition_time_s=numbers["transition_time_s"], scenario=texts["scenario"],
            package_versions=versions, normalization=texts["normalization"],
            channel_names=tuple(channels), object_description=description)
    except ValueError as error:
        raise MemorizedEventError(path, str(error), owner) from None
    zero = event.zero_channels()
    if zero:
        raise MemorizedEventError(path, f"channels {zero} are zero throughout the window: "
                                  "Eq. 3 could never match them", owner)
    for name, expected, found in (("object", object_name, event.object_name),
                                  ("transition", transition, event.transition)):
        if expected is not None and expected != found:
            raise MemorizedEventError(path, f"holds {name} '{found}', expected '{expected}'",
                                      owner)
    return event


def read_index(events_dir) -> list[dict]:
    """The index's entries (object, transition, file and the events' metadata)."""
    path = pathlib.Path(events_dir) / INDEX_FILE
    data = _read_json(path, INDEX_FORMAT, None)
    entries = _field(data, "events", "list", path, None)
    for number, entry in enumerate(entries):
        if not isinstance(entry, dict):
            raise MemorizedEventError(path, f"entry {number} of 'events' is not an object")
        for name in ("object", "transition", "file"):
            _field(entry, name, "text", path, None)
        file = pathlib.PurePosixPath(entry["file"])
        if file.is_absolute() or ".." in file.parts:
            raise MemorizedEventError(path, f"entry {number} points outside the folder")
    return entries


def _load_entry(events_dir: pathlib.Path, entry: dict) -> MemorizedEvent:
    event = read_memorized_event(events_dir / entry["file"], object_name=entry["object"],
                                 transition=entry["transition"])
    expected = dict(_summary(event), file=event.relative_path())
    if "object_description" not in entry:  # a version-1 index: migrated from the file
        expected.pop("object_description")
    for name, value in expected.items():
        if entry.get(name) != value:
            raise MemorizedEventError(
                events_dir / INDEX_FILE,
                f"entry {entry['object']}/{entry['transition']} says {name} = "
                f"{entry.get(name)!r} but {entry['file']} says {value!r}", entry["object"])
    return event


def load_memorized_events(events_dir, object_name: str, *,
                          required: Sequence[str] = REQUIRED_TRANSITIONS
                          ) -> dict[str, MemorizedEvent]:
    """The memorized events of `object_name`, by transition, in grasp order; the folder
    must hold its `required` transitions (a corrective events folder:
    CORRECTIVE_TRANSITIONS)."""
    events_dir = pathlib.Path(events_dir)
    entries = [e for e in read_index(events_dir) if e["object"] == object_name]
    if not entries:
        objects = sorted({e["object"] for e in read_index(events_dir)})
        raise MemorizedEventError(
            events_dir / INDEX_FILE,
            f"no memorized events for object '{object_name}' (it lists {objects})",
            object_name)
    events = _sorted_events(_load_entry(events_dir, entry) for entry in entries)
    windows = {(e.window_s, e.sa_rate_hz, e.ra_rate_hz): e for e in events}
    if len(windows) > 1:
        shown = "; ".join(f"{e.relative_path()}: {w:g} s at {sa:g}/{ra:g} Hz"
                          for (w, sa, ra), e in windows.items())
        raise MemorizedEventError(
            events_dir / INDEX_FILE, f"the events of '{object_name}' have different windows "
            f"or rates (SA/RA), which one matcher cannot use ({shown})", object_name)
    missing = [t for t in required if t not in {e.transition for e in events}]
    if missing:
        raise MemorizedEventError(
            events_dir / INDEX_FILE, f"lists no {', '.join(missing)} event of object "
            f"'{object_name}' (every object needs {', '.join(required)})",
            object_name)
    return {event.transition: event for event in events}


def events_folder_of(folders, object_name: str) -> pathlib.Path | None:
    """The first of `folders` whose index lists `object_name` (None if none does)."""
    for folder in map(pathlib.Path, folders):
        if (folder / INDEX_FILE).is_file() and any(
                e["object"] == object_name for e in read_index(folder)):
            return folder
    return None


def find_memorized_events(folders, object_name: str, *,
                          required: Sequence[str] = REQUIRED_TRANSITIONS
                          ) -> tuple[pathlib.Path, dict[str, MemorizedEvent]]:
    """(folder, events) of `object_name` from the first of `folders` whose index lists it
    (a folder without an index is passed over); MemorizedEventError says where it looked."""
    folders = [pathlib.Path(f) for f in folders]
    looked = []
    for folder in folders:
        if not (folder / INDEX_FILE).is_file():
            looked.append(f"{folder} (no {INDEX_FILE})")
            continue
        if any(e["object"] == object_name for e in read_index(folder)):
            return folder, load_memorized_events(folder, object_name, required=required)
        objects = sorted({e["object"] for e in read_index(folder)})
        looked.append(f"{folder} (has {', '.join(objects) or 'none'})")
    error = MemorizedEventError(folders[0] / INDEX_FILE if folders else INDEX_FILE,
                                "no events", object_name)
    error.args = (f"no memorized events of object '{object_name}' in {'; '.join(looked)}. "
                  f"Record them with `{RECORD_COMMAND} ...` (they go to the first folder).",)
    raise error


def load_all_memorized_events(events_dir) -> dict[str, dict[str, MemorizedEvent]]:
    """Every object's memorized events: {object: {transition: event}}."""
    objects = sorted({e["object"] for e in read_index(events_dir)})
    return {name: load_memorized_events(events_dir, name) for name in objects}
