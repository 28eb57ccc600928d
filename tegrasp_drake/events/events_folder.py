"""An events folder: save an object's memorized events with the index, load them back,
find the folder that holds an object's events. Saving is all or nothing (staged files
renamed together with Ctrl-C held back, the index last) and holds the folder, so that two
processes saving into one folder cannot interleave their index writes."""

import contextlib
import os
import pathlib
from typing import Annotated
from collections.abc import Iterable, Sequence

from tegrasp_drake.rig.files import (JSON_OBJECT_START, FolderHeldError, folder_problem,
                                     held_folder,
                                     interruptions_deferred, replace_problem,
                                     remove_stale_staging_files_of, staged_file)
from tegrasp_drake.rig.objects import object_name_problem
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.events.event_file import (
    EVENT_FORMAT, FORMAT_VERSION, INDEX_FILE, INDEX_FORMAT, RECORD_COMMAND, MemorizedEventError,
    NotAnEventsFolderError, remake_advice, event_json_text, event_problem, event_summary,
    event_to_json, events_folder_problem, has_index, read_index, read_memorized_event,
    record_again_advice, recorded_file_problem, refuse_unusable_events_folder,
    unlisted_event_files)
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.one_grasp import object_events_problem
from tegrasp_drake.events.transitions import (REQUIRED_TRANSITIONS, TRANSITIONS,
                                              transition_order)
from tegrasp_drake.rig.api_boundary import OUTPUT_FOLDER, PathLike, public_api


def _sorted_events(events: Iterable[MemorizedEvent]) -> list[MemorizedEvent]:
    return sorted(events, key=lambda e: (e.object_name, transition_order(e.transition)))


class EventsDestinationError(ValueError):
    """An events folder cannot take an object's new events; the message names the path, what
    is there, and what to do."""


def check_events_destination(events_dir, object_names: Iterable[str], *,
                             keep_other_objects: bool = True) -> None:
    """EventsDestinationError unless save_memorized_events can put `object_names`' events and the
    index into `events_dir`: no folder or non-folder path part where a file belongs and, when other
    objects' entries are kept, an index that reads; the folder and each object's folder ones
    this user can write in (folder_problem); and no file there that the recording
    did not write (recorded_file_problem): a save replaces an object's event files and the
    index, and removes the object's event files it does not write again, so a file of the
    user's at one of those paths would be lost; and a folder that holds no index but other
    files (events_folder_problem, the readers' check too) is not one. Asked before recording
    and by the save."""
    events_dir = pathlib.Path(events_dir)
    index = events_dir / INDEX_FILE
    targets = [(index, INDEX_FORMAT)] + [
        (events_dir / object_name / f"{transition}.json", EVENT_FORMAT)
        for object_name in object_names for transition in TRANSITIONS]
    for path, expected_format in targets:
        problem = replace_problem(path)
        if problem:
            raise EventsDestinationError(f"{path} {problem}, or give another events folder")
        problem = (not (path == index and keep_other_objects)  # read_index's, below
                   and recorded_file_problem(path, expected_format))
        if problem:
            raise EventsDestinationError(
                f"{path} {problem}, and the recording writes or removes a file there; move it "
                "out of the folder, or give another events folder")
    problem = events_folder_problem(events_dir, writing=True)  # the readers' one check
    if problem:
        raise EventsDestinationError(f"{events_dir} {problem}")
    for folder in [events_dir, *(events_dir / name for name in object_names)]:
        # The save stages each file beside its target and renames it there, and removes an
        # object's stale files: the folder (or, not there yet, the one it is made in) must be
        # one this user writes in, whoever made it.
        problem = folder_problem(folder)
        if problem:
            raise EventsDestinationError(
                f"{problem} (the recording writes the event files there); give an events "
                "folder you can write")
    if keep_other_objects and os.path.lexists(index):
        try:
            read_index(events_dir)
        except MemorizedEventError as e:
            raise EventsDestinationError(
                f"{index}: {e.problem}; it lists the other objects' events, which the new "
                "recording keeps: repair it or move it away, or give another events "
                "folder") from None


class EventsFolderHeldError(EventsDestinationError):
    """Another process is saving or recording events into the folder (held_events_folder)."""


@contextlib.contextmanager
def held_events_folder(events_dir):
    """Holds `events_dir` (made if missing) for the block: the hold save_memorized_events takes
    for each save and `tegrasp record-events` for its whole recording (rig.files.held_folder,
    shared, so a save inside this process's recording shares it). Another process's save or
    recording there is refused at once (EventsFolderHeldError) rather than read the index
    before this one writes it and then drop this one's entries; OSError when the folder
    cannot be made or opened."""
    events_dir = pathlib.Path(events_dir)
    events_dir.mkdir(parents=True, exist_ok=True)
    with contextlib.ExitStack() as stack:
        try:
            stack.enter_context(held_folder(events_dir, shared=True))
        except FolderHeldError:
            raise EventsFolderHeldError(
                f"{events_dir}: another process is saving or recording events there now; "
                "wait for it to end, or give another folder") from None
        yield


@public_api
def save_memorized_events(events_dir: Annotated[PathLike, OUTPUT_FOLDER],
                          events: Iterable[MemorizedEvent], *,
                          keep_other_objects: bool = True,
                          required: Sequence[str] = REQUIRED_TRANSITIONS) -> list[pathlib.Path]:
    """Write the events' files and the index; returns the paths written.

    Each object given replaces its previous events (stale files removed); keep_other_objects
    keeps the other objects' index entries. Every object needs the `required` transitions;
    no events at all is refused (ValueError), and so are events that load_memorized_events
    would refuse once saved (UnreadableEventsError, a ValueError), before anything is
    written. The folder is held while it is read and written (held_events_folder): a save
    while another process saves or records there is refused (EventsFolderHeldError, an
    EventsDestinationError)."""
    events_dir = pathlib.Path(events_dir)
    events = list(events)
    if not events:
        raise ValueError("save_memorized_events: no events given; there is nothing to save "
                         "(record some with record_events)")
    _refuse_a_repeated_event(events)
    events = _sorted_events(events)
    keys = [(e.object_name, e.transition) for e in events]
    objects = sorted({e.object_name for e in events})
    for object_name in objects:
        missing = [t for t in required if (object_name, t) not in keys]
        if missing:
            raise ValueError(f"save_memorized_events: object '{shorten(object_name)}' lacks "
                             f"the transitions {', '.join(map(repr, missing))} (each object "
                             f"needs {', '.join(required)}); nothing was saved")
    _refuse_unreadable(events_dir, events, objects)
    check_events_destination(events_dir, objects, keep_other_objects=keep_other_objects)
    with held_events_folder(events_dir):
        return _save_held(events_dir, events, objects, keep_other_objects)


def _refuse_a_repeated_event(events: list[MemorizedEvent]) -> None:
    """ValueError naming the object, the transition and the two positions in `events` of the
    first two events of one object and transition: one file holds each, so one would be
    written over the other (or one dropped) without a word."""
    first = {}
    for position, event in enumerate(events):
        key = (event.object_name, event.transition)
        if key in first:
            raise ValueError(
                f"save_memorized_events: events[{first[key]}] and events[{position}] are both "
                f"object '{shorten(key[0])}', transition '{shorten(key[1])}' (one file, "
                f"{shorten(event.relative_path())}, holds it); give one event per object and "
                "transition; nothing was saved")
        first[key] = position


class UnreadableEventsError(ValueError):
    """Events that the folder's reader would refuse, so save_memorized_events does not write
    them; the message names the event's file and field and what is wrong."""


def _refuse_unreadable(events_dir: pathlib.Path, events: list[MemorizedEvent],
                       objects: list[str]) -> None:
    """UnreadableEventsError for the first of `events` that load_memorized_events would refuse
    once saved, by the reader's own checks: each event's (event_file.event_problem) and each
    object's events together (one_grasp.object_events_problem)."""
    for event in events:
        problem = event_problem(event)
        if problem:
            raise _unreadable(events_dir, event, problem)
    for object_name in objects:
        refused = object_events_problem(e for e in events if e.object_name == object_name)
        if refused:
            raise _unreadable(events_dir, *refused)


def _unreadable(events_dir: pathlib.Path, event: MemorizedEvent,
                problem: str) -> UnreadableEventsError:
    """The refusal of saving `event` into `events_dir`, naming the file it would have been."""
    path = events_dir.joinpath(event.relative_path())
    return UnreadableEventsError(f"{path}: {problem}; nothing was saved")


def _save_held(events_dir: pathlib.Path, events: list[MemorizedEvent], objects: list[str],
               keep_other_objects: bool) -> list[pathlib.Path]:
    """save_memorized_events's reading of the index and writing, in the folder it holds."""
    kept_entries = []
    if keep_other_objects and (events_dir / INDEX_FILE).exists():
        kept_entries = [entry for entry in read_index(events_dir)
                        if entry["object"] not in objects]
    entries = kept_entries + [dict(event_summary(e), file=e.relative_path()) for e in events]
    entries.sort(key=lambda entry: (entry["object"], transition_order(entry["transition"])))
    index = {"format": INDEX_FORMAT, "format_version": FORMAT_VERSION,
             "remake_command": RECORD_COMMAND, "events": entries}
    # All or nothing: every file is staged beside its target first, then the renames and
    # the stale files' removal commit together with Ctrl-C held back, the index last. The
    # staging files of these same files a writer killed past its handlers (SIGKILL) left go
    # first.
    staged = []
    for event in events:
        (events_dir / event.relative_path()).parent.mkdir(parents=True, exist_ok=True)
    _remove_stale_staging([events_dir / e.relative_path() for e in events]
                          + [events_dir / INDEX_FILE])
    try:
        for event in events:
            path = events_dir / event.relative_path()
            staged.append((staged_file(path, event_json_text(event_to_json(event))), path))
        staged.append((staged_file(events_dir / INDEX_FILE, event_json_text(index)),
                       events_dir / INDEX_FILE))
        with interruptions_deferred():
            for object_name in objects:
                object_dir = events_dir / object_name
                new_files = {f"{e.transition}.json" for e in events
                             if e.object_name == object_name}
                for transition in TRANSITIONS:  # the object's own event files only
                    stale = object_dir / f"{transition}.json"
                    if stale.name not in new_files and stale.is_file():
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


def _load_entry(events_dir: pathlib.Path, entry: dict) -> MemorizedEvent:
    event = read_memorized_event(events_dir / entry["file"], object_name=entry["object"],
                                 transition=entry["transition"])
    expected = dict(event_summary(event), file=event.relative_path())
    if "object_description" not in entry:  # a version-1 index: migrated from the file
        expected.pop("object_description")
    for name, value in expected.items():
        if entry.get(name) != value:
            raise MemorizedEventError(
                events_dir / INDEX_FILE,
                f"entry {entry['object']}/{entry['transition']} says {name} = "
                f"{shorten(repr(entry.get(name)))} but {entry['file']} says "
                f"{shorten(repr(value))}", entry["object"])
    return event


def _remove_stale_staging(targets: list[pathlib.Path]) -> None:
    """Removes the staging files of `targets` that ended writers left (stale_staging_files_of:
    named for one of them and holding JSON's start); a live writer's are its own (its save
    commits or removes them), and other files of the folder are the user's."""
    for target in targets:
        remove_stale_staging_files_of(target, JSON_OBJECT_START)


@public_api
def load_memorized_events(events_dir: PathLike, object_name: str, *,
                          required: Sequence[str] = REQUIRED_TRANSITIONS
                          ) -> dict[str, MemorizedEvent]:
    """The memorized events of `object_name`, by transition, in grasp order; the folder must hold
    its `required` transitions (a corrective events folder: CORRECTIVE_TRANSITIONS)."""
    unknown = [name for name in required if name not in TRANSITIONS]
    if unknown:
        raise ValueError(f"load_memorized_events: argument 'required' names "
                         f"{shorten(repr(unknown[0]))}, no transition; the transitions are "
                         f"{', '.join(TRANSITIONS)}")
    events_dir = pathlib.Path(events_dir)
    entries = [e for e in read_index(events_dir) if e["object"] == object_name]
    if not entries:
        _refuse_unlisted_events(events_dir, object_name)
        objects = sorted({e["object"] for e in read_index(events_dir)})
        raise MemorizedEventError(
            events_dir / INDEX_FILE,
            f"no memorized events for object '{object_name}' (it lists {objects})",
            object_name)
    events = _sorted_events(_load_entry(events_dir, entry) for entry in entries)
    refused = object_events_problem(events)
    if refused:
        event, problem = refused
        raise MemorizedEventError(events_dir / event.relative_path(), problem, object_name)
    missing = [t for t in required if t not in {e.transition for e in events}]
    if missing:
        raise MemorizedEventError(
            events_dir / INDEX_FILE, f"lists no {', '.join(missing)} event of object "
            f"'{object_name}' (every object needs {', '.join(required)})",
            object_name)
    return {event.transition: event for event in events}


def _refuse_unlisted_events(events_dir: pathlib.Path, object_name: str) -> None:
    """NotAnEventsFolderError when `events_dir`, whose index lists no `object_name`, holds its
    event files (unlisted_event_files): a recording of it stopped before it wrote the index,
    so neither "no events" nor another folder's events of it are what the user recorded."""
    files = unlisted_event_files(events_dir, object_name)
    if files:
        raise NotAnEventsFolderError(
            events_dir, f"holds event files of '{object_name}' ({', '.join(files)}) that its "
            f"{INDEX_FILE} does not list: a recording stopped before it wrote the index; "
            f"{record_again_advice(object_name, events_dir)}")


def _passed_over(folder: pathlib.Path, object_name: str) -> bool:
    """Whether a reader looking for `object_name`'s events in several folders passes over
    `folder`: it holds nothing yet (no index); one of other files, or with what a stopped
    recording left, is refused (events_folder_problem, _refuse_unlisted_events)."""
    if not has_index(folder):
        refuse_unusable_events_folder(folder)
        return True
    if any(e["object"] == object_name for e in read_index(folder)):
        return False
    _refuse_unlisted_events(folder, object_name)
    return True


def events_folder_of(folders, object_name: str) -> pathlib.Path | None:
    """The first of `folders` whose index lists `object_name` (None if none does)."""
    for folder in map(pathlib.Path, folders):
        if not _passed_over(folder, object_name):
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
        if not _passed_over(folder, object_name):
            return folder, load_memorized_events(folder, object_name, required=required)
        if not has_index(folder):
            looked.append(f"{folder} (no {INDEX_FILE})")
            continue
        objects = sorted({e["object"] for e in read_index(folder)})
        looked.append(f"{folder} (has {', '.join(objects) or 'none'})")
    error = MemorizedEventError(folders[0] / INDEX_FILE if folders else INDEX_FILE,
                                "no events", object_name)
    advice = (f"Record them with `{RECORD_COMMAND} ...` (they go to the first folder)."
              if object_name_problem(object_name) is None else remake_advice(object_name))
    error.problem = f"no memorized events of object '{object_name}' in {'; '.join(looked)}"
    error.args = (f"{error.problem}. {advice}",)
    raise error


def load_all_memorized_events(events_dir) -> dict[str, dict[str, MemorizedEvent]]:
    """Every object's memorized events: {object: {transition: event}}."""
    objects = sorted({e["object"] for e in read_index(events_dir)})
    return {name: load_memorized_events(events_dir, name) for name in objects}
