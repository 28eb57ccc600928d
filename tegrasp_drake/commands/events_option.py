"""The `--events DIR` option every command that reads memorized events takes: checked to be a
folder before the command looks for an index in it."""

from tegrasp_drake.rig.api_boundary import INPUT_FOLDER
from tegrasp_drake.rig.files import UserPathError


def check_events_folder(events) -> None:
    """UserPathError (one line, exit 1) unless --events `events` (None: not given) names an
    existing folder (api_boundary.INPUT_FOLDER): a file, a pipe or a device there is said as
    such, before a command looks for an index in it."""
    if events is None:
        return
    problem = INPUT_FOLDER.problem(events)
    if problem:
        raise UserPathError(f"--events {events}: {problem} of memorized events")
