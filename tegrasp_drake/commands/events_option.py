"""The `--events DIR` option every command that reads memorized events takes: checked to be a
folder (or the folder TEGRASP_EVENTS_DIR names) before the command looks for an index in it."""

from tegrasp_drake.rig.api_boundary import INPUT_FOLDER
from tegrasp_drake.rig.files import UserPathError


def check_events_folder(events) -> None:
    """UserPathError (one line, exit 1) unless --events `events` (None: not given) names an
    existing folder (api_boundary.INPUT_FOLDER) that is an events folder or holds nothing yet
    (events_folder_problem): a file, a pipe or a device there is said as such, and so is a
    folder of other files (`--events /etc`), whether or not the command's controllers read
    events (given, the option is never ignored). Not given: the folder TEGRASP_EVENTS_DIR
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
    from tegrasp_drake.events.event_file import events_folder_problem
    problem = events_folder_problem(events, writing=False)
    if problem:
        raise UserPathError(f"--events {events} {problem}")


def _refuse_a_variable_folder_of_other_files() -> None:
    """UserPathError naming TEGRASP_EVENTS_DIR when the folder it names is no events folder
    (events_folder_problem, the readers' and writers' one check: no index but other files,
    or what a stopped recording left): another folder than the user meant, whose events
    would be the package's in silence, as `--events` there is refused. An empty one (hidden
    files aside) holds no events yet, and is passed over."""
    from tegrasp_drake.events.event_file import events_folder_problem
    from tegrasp_drake.rig.paths import EVENTS_ENV, user_events_setting
    folder, named = user_events_setting()
    if not named.startswith(EVENTS_ENV):
        return
    problem = events_folder_problem(folder, writing=False, remedy=(
        "point it at your events folder (`tegrasp record-events` makes it), or unset it"))
    if problem:
        raise UserPathError(f"{named}: {folder} {problem}")
