"""The JSON files of memorized events: one event's file and the folder's index.

    events/index.json                      the list of events, with their metadata
    events/<object>/<transition>.json      one event: four max-normalised windows

Sorted keys, one window a line, shortest round-trip floats: a file reads back to the same
float64 values, and recording the same data again gives identical bytes. A bad file raises
MemorizedEventError naming the file and the command that remakes it (FORMAT.md)."""

import functools
import json
import math
import os
import pathlib

import numpy as np

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS
from tegrasp_drake.rig.files import (JsonFileError, NotAFileError, error_line, load_json,
                                     one_line, read_bounded, read_error_remedy,
                                     read_json_file)
from tegrasp_drake.rig.objects import (BUILTIN_OBJECTS, DESCRIPTION_FIELDS, ObjectConfig,
                                       description_differences, object_name_problem)
from tegrasp_drake.tactile.sampling import samples_per_window
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import TRANSITIONS

FORMAT_VERSION = 3
# Version 1 takes `object_description` from its `scenario` text; version 2 (no quiet RA
# windows) reads as it is (FORMAT.md, Versions).
MIGRATED_VERSIONS = (1, 2)
EVENT_FORMAT = "tegrasp.memorized_event"
INDEX_FORMAT = "tegrasp.memorized_event_index"
INDEX_FILE = "index.json"
RECORD_COMMAND = "tegrasp record-events"


# An event file is about 30 kB at the paper's rates (0.5 s, 1 kHz RA); 16 MB leaves room
# for 20 kHz windows.
MAX_EVENT_FILE_BYTES = 16_000_000


class MemorizedEventError(Exception):
    """A memorized event or index file is missing or unusable."""

    def __init__(self, path, problem: str, object_name: str | None = None,
                 remedy: str | None = None):
        self.path = pathlib.Path(path)
        self.problem = one_line(problem)  # what is wrong, without the path and the remedy
        remedy = remedy or remake_advice(object_name)
        super().__init__(error_line(f"{self.path}: {problem}. {remedy}"))


def _sentence(words: str) -> str:
    """`words` begun with a capital and ended with a full stop (a remedy's sentence)."""
    return words[:1].upper() + words[1:] + "."


def remake_advice(object_name: str | None) -> str:
    """The sentence that says how to remake a file of `object_name`'s events, naming only
    options `tegrasp record-events` accepts for that name (none for a name it refuses)."""
    if not object_name:
        return f"Remake it with `{RECORD_COMMAND}`."
    if object_name in BUILTIN_OBJECTS:
        return f"Remake it with `{RECORD_COMMAND} --object {object_name}`."
    problem = object_name_problem(object_name)
    if problem:
        return f"No events are recorded under this name: object.name {problem}."
    return (f"Remake it with `{RECORD_COMMAND}` and the options that describe "
            f"'{object_name}': `--scenario FILE --scenario-name NAME`, or `--set "
            f"object.name={object_name}` with its other object.* settings.")


# ---- Writing -------------------------------------------------------------------------


def event_summary(event: MemorizedEvent) -> dict:
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
    data = event_summary(event)
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


def event_json_text(data: dict) -> str:
    """The file text of a JSON object: _render's layout and a final newline."""
    return _render(data) + "\n"


# ---- Reading -------------------------------------------------------------------------


def _read_json(path: pathlib.Path, expected_format: str, object_name: str | None) -> dict:
    def format_problem(data) -> str | None:
        if not isinstance(data, dict) or data.get("format") != expected_format:
            return f"is not a '{expected_format}' file"
        version = data.get("format_version")  # 3.0 reads as 3; JSON's true is no version
        if version is None:  # absent (or null): not written by any version
            return f"has no format_version, so `{RECORD_COMMAND}` did not write it"
        if isinstance(version, bool) or version not in (*MIGRATED_VERSIONS, FORMAT_VERSION):
            return (f"has format_version {data.get('format_version')!r}; this tegrasp reads "
                    f"versions {', '.join(map(str, (*MIGRATED_VERSIONS, FORMAT_VERSION)))}")
        return None
    try:
        return read_json_file(path, limit=MAX_EVENT_FILE_BYTES, check=format_problem,
                              kind="an event file or index")
    except JsonFileError as error:
        # A file this user cannot read (no permission, an I/O error) is not damaged, so
        # remaking it is no remedy.
        raise MemorizedEventError(path, error.problem, object_name, remedy=(
            _sentence(read_error_remedy(error.unreadable))
            if error.unreadable else None)) from None


@functools.lru_cache(maxsize=16)
def _parsed_scenario_object(text: str) -> tuple | None:
    """scenario_object's answer as a hashable tuple (name, shape, size, mass, friction, file);
    cached, so the text an object's events share (one grasp, one text) is parsed once."""
    from tegrasp_drake.rig.typed_yaml import YamlSyntaxError, parse_yaml
    try:
        scenario = parse_yaml(text, "field 'scenario'")
    except YamlSyntaxError:
        return None  # no YAML at all: a note (an ensemble's combined runs)
    section = scenario.get("object") if isinstance(scenario, dict) else None
    if not isinstance(section, dict) or not section.get("shape") or not section.get("size"):
        return None  # no object described (a note, or a built-in named without its shape)
    try:
        size = tuple(float(v) for v in section["size"])
        mass, friction = float(section["mass"]), float(section["friction"])
        name, shape, file = (section.get("name", ObjectConfig.name), section["shape"],
                             section.get("file", ""))
        if not all(isinstance(v, str) for v in (name, shape, file)):
            raise TypeError(name)
    except (TypeError, KeyError, ValueError):
        raise ValueError("field 'scenario' holds an object section that does not describe an "
                         "object (name, shape and file as text, size, mass and friction as "
                         "numbers)") from None
    return name, shape, size, mass, friction, file


def scenario_object(text: str) -> tuple[str, dict] | None:
    """(name, description) of the object an event's `scenario` text grasps: the object section
    a recording stores (scenario_to_yaml, the object resolved), in object_description's form;
    None when the text is a note (no YAML) or describes no object (no shape or size).
    ConfigError for YAML no scenario reader accepts (a Python object tag, a duplicate key,
    nesting or size past the reader's limits), ValueError for an object section that is not
    an object's."""
    parsed = _parsed_scenario_object(text)
    if parsed is None:
        return None
    name, shape, size, mass, friction, file = parsed
    return name, {"shape": shape, "size": list(size), "mass": mass, "friction": friction,
                  "file": file}


def _description_from_scenario(scenario_text: str, path, object_name) -> dict:
    """A version-1 file's object description: the object section of its scenario text."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    try:
        described = scenario_object(scenario_text)
    except ConfigError as error:
        raise MemorizedEventError(path, str(error), object_name) from None
    except ValueError:
        described = None
    if described is None:
        raise MemorizedEventError(
            path, "is a format_version 1 file whose scenario text does not describe the "
            "object (shape, size, mass, friction), so it cannot be checked against the "
            "object it is used for", object_name)
    return described[1]


def event_problem(event: MemorizedEvent) -> str | None:
    """Why the event files' reader refuses `event`, whatever file holds it, in words naming
    the field, else None: windows no recording gives (MemorizedEvent.shape_problem), or a
    `scenario` text no scenario reader accepts or whose object (scenario_object) is not the
    event's `object` and `object_description`. Asked of every event read and saved."""
    problem = event.shape_problem()
    if problem:
        return problem
    try:
        described = scenario_object(event.scenario)
    except ValueError as error:  # a ConfigError too
        return str(error)
    if described is None:
        return None
    name, description = described
    advice = "an event is felt on the object of the scenario it was recorded in"
    if name != event.object_name:
        return (f"field 'scenario' grasps object '{name}', but field 'object' is "
                f"'{event.object_name}': {advice}")
    differences = (description_differences(description, event.object_description,
                                           labels=("field 'scenario'",
                                                   "field 'object_description'"))
                   if event.object_description else [])
    if differences:
        return (f"field 'scenario' describes another object than field "
                f"'object_description': {'; '.join(differences)}: {advice}")
    return None


def _object_description(data: dict, path, object_name) -> dict:
    """The file's object description (version 2), or its migration (version 1)."""
    if data.get("format_version") == 1:
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
          "list": lambda v: isinstance(v, list), "object": lambda v: isinstance(v, dict),
          "list of texts": lambda v: isinstance(v, list) and all(isinstance(i, str) for i in v),
          "object of texts": lambda v: isinstance(v, dict) and all(isinstance(i, str)
                                                                    for i in v.values())}


def _field(data: dict, name: str, kind: str, path, object_name, prefix: str = ""):
    """data[name], checked to be of `kind` (a key of _KINDS); a null is named as one (a
    value the file must hold, never read as "left out"). `prefix`: the object's field path
    in the file ("events[3].")."""
    if name not in data:
        raise MemorizedEventError(path, f"field '{prefix}{name}' is missing", object_name)
    article = "an" if kind[0] in "aeiou" else "a"
    if data[name] is None:
        raise MemorizedEventError(path, f"field '{prefix}{name}' is null, where the file must "
                                  f"hold {article} {kind}", object_name)
    if not _KINDS[kind](data[name]):
        raise MemorizedEventError(path, f"field '{prefix}{name}' is not {article} {kind}",
                                  object_name)
    return data[name]


# Every file's `format` and `format_version` (a number: 3.0 reads as 3; _read_json checks
# the values).
FORMAT_FIELD_KINDS = {"format": "text", "format_version": "number"}
# The fields of an event file (event_to_json) and the type of each, every version's (a
# version-1 file has no object_description).
EVENT_FIELD_KINDS = {
    **FORMAT_FIELD_KINDS, "object": "text", "transition": "text", "physical_event": "text",
    "channels": "list of texts", "sa_rate_hz": "number", "ra_rate_hz": "number",
    "window_s": "number", "pre_transition_s": "number", "transition_time_s": "number",
    "normalization": "text", "scenario": "text", "package_versions": "object of texts",
    "object_description": "object", "samples": "object"}
# The index's fields (save_memorized_events writes these, and no other) and each entry's
# (event_summary and `file`; an entry a version-1 index kept has no object_description).
INDEX_FIELD_KINDS = {**FORMAT_FIELD_KINDS, "remake_command": "text", "events": "list"}
INDEX_ENTRY_KINDS = {
    "object": "text", "transition": "text", "file": "text", "channels": "list of texts",
    "sa_rate_hz": "number", "ra_rate_hz": "number", "window_s": "number",
    "pre_transition_s": "number", "normalization": "text", "scenario": "text",
    "package_versions": "object of texts", "object_description": "object"}


def _declared_fields(data: dict, kinds: dict, which: str, path, object_name, *,
                     optional=(), prefix: str = "") -> None:
    """MemorizedEventError naming the first field of `data` that is not one of `kinds`
    (`which`: what they are, in words), or one of them missing (unless `optional`), null or
    not of its declared kind."""
    _no_unknown_fields(data, kinds, prefix, which, path, object_name)
    for name, kind in kinds.items():
        if name in data or name not in optional:
            _field(data, name, kind, path, object_name, prefix)


def _no_unknown_fields(data: dict, known, prefix: str, which: str, path, object_name) -> None:
    """MemorizedEventError naming the first key of `data` not in `known` (a forged or
    misspelt field would otherwise be ignored); `prefix`: the object's field path; `which`:
    what the known keys are, for the message."""
    unknown = sorted(set(data) - set(known))
    if unknown:
        raise MemorizedEventError(path, f"field '{prefix}{unknown[0]}' is not {which}",
                                  object_name)


def _samples(data: dict, name: str, length: int, path, object_name) -> list[float]:
    samples = _field(data, "samples", "object", path, object_name)
    _no_unknown_fields(samples, CHANNEL_NAMES, "samples.",
                       f"a channel (the channels are {', '.join(CHANNEL_NAMES)})", path,
                       object_name)
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
    _declared_fields(data, EVENT_FIELD_KINDS, "a field of an event file (FORMAT.md lists them)",
                     path, owner,
                     optional=("object_description",) if data["format_version"] == 1 else ())
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
    problem = event_problem(event)
    if problem:
        raise MemorizedEventError(path, problem, owner)
    version = data.get("format_version")
    quiet = [CHANNEL_NAMES[i] for i in RA_CHANNELS if np.all(event.ra[i - 2] == 1.0)]
    if version != FORMAT_VERSION and quiet:
        raise MemorizedEventError(
            path, f"field 'samples.{quiet[0]}' is a window of ones, a quiet RA window, which "
            f"a format_version {version} file never holds: its windows are as cut, and a cut "
            "vibration window is never constant (quiet windows came with version 3)", owner)
    for name, expected, found in (("object", object_name, event.object_name),
                                  ("transition", transition, event.transition)):
        if expected is not None and expected != found:
            raise MemorizedEventError(path, f"holds {name} '{found}', expected '{expected}'",
                                      owner)
    return event


def recorded_file_problem(path, expected_format: str) -> str | None:
    """Why the file at `path` is not one `tegrasp record-events` wrote in `expected_format`
    (EVENT_FORMAT: an event's file, INDEX_FORMAT: the index), in words that follow it, or None:
    it is one, or nothing is there. A recording replaces only its own files; the user's (a
    text file named like an event file) are never replaced. Known by the JSON object's
    "format" field, or, in a file damaged past JSON (which re-recording remakes), by that
    field as the writer writes it."""
    try:
        raw = read_bounded(path, MAX_EVENT_FILE_BYTES)
    except (FileNotFoundError, NotADirectoryError):
        return None
    except NotAFileError as error:
        return error.strerror.split(";")[0]
    except OSError as error:  # too large, unreadable
        return f"cannot be checked ({os_error_text(error)})"
    text = raw.decode("utf-8", errors="replace")
    try:
        data = load_json(text)
    except (ValueError, RecursionError):
        data = None
    if (isinstance(data, dict) and data.get("format") == expected_format) or (
            data is None and f'"format": {json.dumps(expected_format)}' in text):
        return None
    return f"is not a '{expected_format}' file {RECORD_COMMAND} wrote"


# A file the package keeps in an events folder beside the events: a transfer world's settings,
# written before its events are recorded (transfer/matrix.py).
WORLD_FILE = "world.json"
# [entries] How many of a folder's entries events_folder_contents looks at: a recording's
# folder holds the index, a world's file and a folder per object; a folder of more
# without an index is no events folder whatever the rest holds.
MAX_FOLDER_ENTRIES = 1000


def events_folder_contents(events_dir) -> tuple[str, str | None]:
    """What a folder given for events holds, (kind, an entry's name or None), its entries
    looked at, not read: "index" (it holds one, or one of its EVENTS_SUBFOLDERS does:
    read_index judges it), "none" (nothing is
    there, or no entry but hidden ones: no events yet), "unfinished" (no index, only what
    a recording writes before its index, last: object folders of event files and staging
    files, an events subfolder of the same, a world's settings; the name of an object
    folder, or None), "other" (no index but another file: the name of the first) or
    "unreadable" (its error's words)."""
    from tegrasp_drake.rig.files import is_staging_name
    from tegrasp_drake.rig.objects import EVENTS_SUBFOLDERS
    folder = pathlib.Path(events_dir)
    if has_index(folder) or any(has_index(folder / sub) for sub in EVENTS_SUBFOLDERS):
        return "index", None
    if not folder.is_dir():
        return "none", None
    try:
        with os.scandir(folder) as scan:
            entries = [entry for _, entry in zip(range(MAX_FOLDER_ENTRIES + 1), scan)]
    except OSError as error:
        return "unreadable", error.strerror or str(error)
    objects = []
    shown_entries = sorted((entry for entry in entries  # hidden ones: staging files
                            if not entry.name.startswith(".") and entry.name != WORLD_FILE),
                           key=lambda e: (e.is_dir(follow_symlinks=False), e.name))
    for entry in shown_entries:  # files first: the first named is the plainest
        name = entry.name
        if len(entries) > MAX_FOLDER_ENTRIES or not entry.is_dir(follow_symlinks=False):
            return "other", name
        if name in EVENTS_SUBFOLDERS:
            kind, found = events_folder_contents(entry.path)
            if kind in ("other", "unreadable"):
                return kind, f"{name}/{found}" if kind == "other" else found
            continue
        if object_name_problem(name) is not None:
            return "other", name
        most = len(TRANSITIONS) * 4  # its event files, and a killed save's staging files
        try:
            with os.scandir(entry.path) as scan:
                inside = sorted(e.name for _, e in zip(range(most + 1), scan))
        except OSError as error:
            return "unreadable", error.strerror or str(error)
        if len(inside) > most:
            return "other", name
        for file in inside:
            path = pathlib.Path(entry.path) / file
            if not (is_staging_name(file) or (
                    file.removesuffix(".json") in TRANSITIONS and file.endswith(".json")
                    and recorded_file_problem(path, EVENT_FORMAT) is None)):
                return "other", f"{name}/{file}"
        objects.append(name)
    return ("unfinished", objects[0] if objects else None) if objects else ("none", None)


def events_folder_problem(events_dir, *, writing: bool, remedy: str | None = None) -> str | None:
    """Why `events_dir` cannot be read as an events folder (writing=False) or recorded into
    (writing=True), in words that follow its path, with what to do (`remedy`, else what a
    reader or writer is given instead); None when it can (or, for a reader, when it holds an
    index, which read_index judges, or nothing yet). The one check of a folder's contents: a
    folder holding no index but other files is no events folder, neither read (its events
    would be "missing") nor written (the recording's files would mix with the user's); what a
    recording stopped before its index left is recorded into again, and a reader says so
    (events_folder_contents)."""
    from tegrasp_drake.rig.echo import shown
    kind, found = events_folder_contents(events_dir)
    if kind == "other":
        remedy = remedy or (
            "give a new or empty folder, or your events folder (the one holding "
            f"{INDEX_FILE})" if writing else f"give the folder `{RECORD_COMMAND}` wrote (it "
            f"holds {INDEX_FILE} and a folder per object)")
        return (f"is not an events folder: it holds no {INDEX_FILE} but other files (e.g. "
                f"{shown(found)}); {remedy}")
    if kind == "unreadable":
        return f"cannot be read ({found}); {remedy or 'give a folder you can read'}"
    if kind == "unfinished" and not writing:
        return (f"holds event files ({found}/...) but no {INDEX_FILE} listing them: a "
                f"recording stopped before it wrote its index; "
                f"{record_again_advice(found, events_dir)}" + (f"; or {remedy}" if remedy else ""))
    return None


def record_again_advice(object_name: str, events_dir) -> str:
    """What to do with `object_name`'s event files a stopped recording left in `events_dir`:
    record them again into that folder, with the options remake_advice names for the object."""
    if object_name in BUILTIN_OBJECTS:
        return (f"record them again (`{RECORD_COMMAND} --object {object_name} --events "
                f"{events_dir}`)")
    return f"record them again with --events {events_dir}: {remake_advice(object_name)}"


class NotAnEventsFolderError(MemorizedEventError):
    """A folder given for events holds no index but other files, or only what a stopped
    recording left (events_folder_problem); the message names it and says what to do."""

    def __init__(self, events_dir, problem: str):
        super().__init__(events_dir, problem)
        self.args = (error_line(f"{self.path} {problem}"),)


def refuse_unusable_events_folder(events_dir) -> None:
    """NotAnEventsFolderError for a folder a reader cannot take (events_folder_problem)."""
    problem = events_folder_problem(events_dir, writing=False)
    if problem:
        raise NotAnEventsFolderError(events_dir, problem)


def unlisted_event_files(events_dir, object_name: str) -> list[str]:
    """The event files of `object_name` in `events_dir` (its folder's `<transition>.json`)
    written by a recording that stopped before its index entry: asked when the index lists
    no such object."""
    folder = pathlib.Path(events_dir) / object_name
    if object_name_problem(object_name) is not None or not folder.is_dir():
        return []
    return [f"{object_name}/{t}.json" for t in TRANSITIONS if (folder / f"{t}.json").is_file()]


def has_index(events_dir) -> bool:
    """True when anything is at the folder's index path: a file, and as well a pipe, a folder,
    a device or a symlink that loops or leads nowhere, which read_index then refuses by name.
    False only when nothing is there (no events saved in that folder yet). Every reader that
    passes over a folder without an index asks this, not is_file(), so an index that cannot
    be read is never skipped in silence for the next folder's events; nor is one that cannot
    be looked at (a folder this user may list but not search, EACCES): True, for read_index
    to say so (os.path.lexists would call it absent)."""
    try:
        os.lstat(pathlib.Path(events_dir) / INDEX_FILE)
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError:
        return True
    return True


def read_index(events_dir) -> list[dict]:
    """The index's entries (object, transition, file and the events' metadata); an index
    that lists no events is refused here, for every reader of it."""
    path = pathlib.Path(events_dir) / INDEX_FILE
    if not has_index(events_dir):  # a folder of other files, or a stopped recording's
        refuse_unusable_events_folder(events_dir)
    data = _read_json(path, INDEX_FORMAT, None)
    _declared_fields(data, INDEX_FIELD_KINDS, "a field of an index (FORMAT.md lists them)",
                     path, None)
    entries = data["events"]
    if not entries:  # no writer makes one (a save needs events): a damaged or forged index
        raise MemorizedEventError(path, "lists no events (its 'events' list is empty)")
    listed = {}  # (object, transition) and file -> the entry that listed it first
    for number, entry in enumerate(entries):
        if not isinstance(entry, dict):
            raise MemorizedEventError(path, f"entry {number} of 'events' is not an object")
        _declared_fields(entry, INDEX_ENTRY_KINDS, "a field of an index entry (FORMAT.md "
                         "lists them)", path, None, optional=("object_description",),
                         prefix=f"events[{number}].")
        file = pathlib.PurePosixPath(entry["file"])
        if file.is_absolute() or ".." in file.parts:
            raise MemorizedEventError(path, f"entry {number} points outside the folder")
        for key, words in (((entry["object"], entry["transition"]),
                            f"the {entry['object']} {entry['transition']} event"),
                           (str(file), f"the file {file}")):
            if key in listed:
                raise MemorizedEventError(path, f"entries {listed[key]} and {number} both "
                                          f"list {words}; an index lists each event once")
            listed[key] = number
    return entries
