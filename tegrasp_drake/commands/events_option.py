"""The `--events DIR` option every command that reads memorized events takes: checked to be a
folder (or the folder TEGRASP_EVENTS_DIR names) before the command looks for an index in it."""

import os

from tegrasp_drake.rig.api_boundary import INPUT_FOLDER
from tegrasp_drake.rig.files import UserPathError


def check_events_folder(events) -> None:
    """UserPathError (one line, exit 1) unless --events `events` (None: not given) names an
    existing folder (api_boundary.INPUT_FOLDER): a file, a pipe or a device there is said as
    such, before a command looks for an index in it. Not given: the folder TEGRASP_EVENTS_DIR
    names must exist (rig/paths.py), whether or not the command's controllers read events,
    and hold events or nothing yet (_refuse_a_variable_folder_of_other_files)."""
    if events is None:
        from tegrasp_drake.rig.paths import events_search_path
        events_search_path()
        _refuse_a_variable_folder_of_other_files()
        return
    problem = INPUT_FOLDER.problem(events)
    if problem:
        raise UserPathError(f"--events {events}: {problem} of memorized events")


def _refuse_a_variable_folder_of_other_files() -> None:
    """UserPathError naming TEGRASP_EVENTS_DIR when the folder it names holds no events index
    (in it or its events subfolders) but other files: another folder than the user meant,
    whose events would be the package's in silence, as `--events` there is refused. An empty
    one (hidden files aside) holds no events yet, and is passed over."""
    from tegrasp_drake.events.event_file import INDEX_FILE, has_index
    from tegrasp_drake.rig.echo import shown
    from tegrasp_drake.rig.objects import EVENTS_SUBFOLDERS
    from tegrasp_drake.rig.paths import EVENTS_ENV, user_events_setting
    folder, named = user_events_setting()
    if not named.startswith(EVENTS_ENV) or any(
            has_index(place) for place in (folder, *(folder / s for s in EVENTS_SUBFOLDERS))):
        return
    remedy = "point it at your events folder (`tegrasp record-events` makes it), or unset it"
    try:
        with os.scandir(folder) as entries:
            other = next((e.name for e in entries if not e.name.startswith(".")), None)
    except OSError as error:
        raise UserPathError(f"{named}: {folder} cannot be read ({error.strerror or error}); "
                            f"{remedy}") from None
    if other is not None:
        raise UserPathError(f"{named}: {folder} holds no memorized events (no {INDEX_FILE}) "
                            f"but other files (e.g. {shown(other)}); {remedy}")
