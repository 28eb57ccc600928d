"""The `--events DIR` option every command that reads memorized events takes: checked to be a
folder (or the folder TEGRASP_EVENTS_DIR names) before the command looks for an index in it."""

from tegrasp_drake.rig.api_boundary import INPUT_FOLDER
from tegrasp_drake.rig.files import UserPathError


def check_events_folder(events) -> None:
    """UserPathError (one line, exit 1) unless --events `events` (None: not given) names an
    existing folder (api_boundary.INPUT_FOLDER): a file, a pipe or a device there is said as
    such, before a command looks for an index in it. Not given: the folder TEGRASP_EVENTS_DIR
    names must exist (rig/paths.py), whether or not the command's controllers read events."""
    if events is None:
        from tegrasp_drake.rig.paths import events_search_path
        events_search_path()
        return
    problem = INPUT_FOLDER.problem(events)
    if problem:
        raise UserPathError(f"--events {events}: {problem} of memorized events")
