"""Where the package's data (read-only models and events, from importlib.resources or
a source checkout) and the user's recorded events live ($TEGRASP_EVENTS_DIR, else
$XDG_DATA_HOME/tegrasp/events when that is an absolute path, else
~/.local/share/tegrasp/events). Readers search --events
alone, else the user's folder, then the package's. The folder TEGRASP_EVENTS_DIR names must
exist for a reader, as --events must (the variable names events and nothing else: a typo
would read other events than meant, in silence). The folder below XDG_DATA_HOME, or the
default, may be absent, as XDG_DATA_HOME itself may (a variable every application shares,
set before any of them wrote there): no events recorded yet; a writer (record-events)
makes it."""

import importlib.resources
import logging
import os
import pathlib

from pydrake.multibody.parsing import Parser

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.echo import shown

PACKAGE_NAME = "tegrasp"  # models are reachable as package://tegrasp/...
PACKAGE_DIR = pathlib.Path(__file__).resolve().parents[1]  # tegrasp_drake/ (this file: rig/)


def _data_dir(package: str, source_folder: str) -> pathlib.Path:
    checkout = PACKAGE_DIR.parent
    if (checkout / "pyproject.toml").is_file() and (checkout / source_folder).is_dir():
        return checkout / source_folder  # imported from a source checkout: its own data
    return pathlib.Path(str(importlib.resources.files(package)))


def models_dir() -> pathlib.Path:
    """The folder holding package.xml and the SDF models."""
    return _data_dir("tegrasp_drake.models_data", "models")


EVENTS_ENV = "TEGRASP_EVENTS_DIR"


def package_events_dir() -> pathlib.Path:
    """The folder holding the package's memorized tactile events and their index
    (read-only: `tegrasp record-events` writes to user_events_dir())."""
    return _data_dir("tegrasp_drake.events_data", "events")


_IGNORED_DATA_HOMES = set()  # relative XDG_DATA_HOME values warned about (once each)


def user_events_dir() -> pathlib.Path:
    """Where the user's recorded events go (module docstring); UserPathError naming the
    variable when $TEGRASP_EVENTS_DIR names something that is not a folder or cannot be one."""
    return user_events_setting()[0]


def user_events_setting() -> tuple[pathlib.Path, str]:
    """(user_events_dir(), the setting that chose it in words, e.g. "XDG_DATA_HOME='/data'
    (events in /data/tegrasp/events)"), for a refusal to name what the user set."""
    folder, named, _ = _user_events_choice()
    return folder, named


def _user_events_choice() -> tuple[pathlib.Path, str, tuple[pathlib.Path, str] | None]:
    """user_events_setting() and (the folder TEGRASP_EVENTS_DIR names, what that folder should
    be), which a reader needs to exist (module docstring); None for XDG_DATA_HOME's folder
    and the default."""
    chosen = os.environ.get(EVENTS_ENV, "").strip()
    if chosen:
        folder = pathlib.Path(chosen).expanduser()
        named = f"{EVENTS_ENV}={shown(chosen)}"
        _check_folder_path(folder, named, "an events folder")
        return folder, named, (folder,
                               "your events folder (`tegrasp record-events` makes it)")
    data_home = os.environ.get("XDG_DATA_HOME", "").strip()
    if data_home and not os.path.isabs(data_home):
        # The XDG Base Directory spec: "If an implementation encounters a relative path in any
        # of these variables it should consider the path invalid and ignore it" (else the
        # events would land below whatever folder the command is run from).
        if data_home not in _IGNORED_DATA_HOMES:
            _IGNORED_DATA_HOMES.add(data_home)
            logging.getLogger(__name__).warning(
                "XDG_DATA_HOME=%r is not an absolute path, which the XDG Base Directory spec "
                "says to ignore; your events folder is ~/.local/share/tegrasp/events", data_home)
        data_home = ""
    base = pathlib.Path(data_home) if data_home else pathlib.Path.home() / ".local" / "share"
    folder = base / "tegrasp" / "events"
    if not data_home:
        return folder, f"the default events folder {folder}", None
    named = f"XDG_DATA_HOME={shown(data_home)} (events in {folder})"
    _check_folder_path(folder, named, "your data folder")
    return folder, named, None


def _user_events_to_read() -> pathlib.Path:
    """user_events_dir() for a reader: UserPathError naming the variable when the folder it
    names does not exist (module docstring)."""
    from tegrasp_drake.rig.files import UserPathError
    folder, named, named_folder = _user_events_choice()
    if named_folder is not None and not named_folder[0].is_dir():
        raise UserPathError(f"{named}: {named_folder[0]} does not exist; point it at "
                            f"{named_folder[1]}, or unset it")
    return folder


def _check_folder_path(folder: pathlib.Path, named: str, meant: str) -> None:
    """UserPathError naming the environment setting `named` (which should point at `meant`)
    unless `folder` is a folder, or could be made as one (files.non_folder_on_path)."""
    from tegrasp_drake.rig.files import UserPathError, non_folder_on_path
    blocked = non_folder_on_path(folder)
    if blocked is None:
        return
    place, error = blocked
    if error:
        raise UserPathError(f"{named} cannot be used ({os_error_text(error)}); point it at "
                            f"{meant}, or unset it")
    what = ("is not a folder" if place == folder
            else f"passes through {place}, which is not a folder")
    raise UserPathError(f"{named} {what}; point it at {meant}, or unset it")


def events_search_path(explicit=None, hand_folder: str = "") -> list[pathlib.Path]:
    """The folders to read events from, first first: [explicit], else the user's and the
    package's (its `hand_folder` for a hand's own events, e.g. "prismatic")."""
    if explicit:
        return [pathlib.Path(explicit).expanduser()]
    package = package_events_dir()
    return [_user_events_to_read(), package / hand_folder if hand_folder else package]


def is_installed_package_data(folder) -> bool:
    """True for the events folder of an installed (non-source) copy of the package, which
    `pip install` replaces: nothing may be written there."""
    if (PACKAGE_DIR.parent / "pyproject.toml").is_file():
        return False  # a source checkout: its events/ folder is remade by its maintainers
    try:
        installed = pathlib.Path(str(importlib.resources.files("tegrasp_drake.events_data")))
    except ModuleNotFoundError:
        return False
    try:
        folder, installed = pathlib.Path(folder).resolve(), installed.resolve()
    except (OSError, RuntimeError):  # a symlink loop: not the package (and not writable)
        return False
    return folder == installed or installed in folder.parents  # ensemble/, corrective/ too


def scenarios_file() -> pathlib.Path:
    """The file of named built-in scenarios."""
    return pathlib.Path(str(importlib.resources.files("tegrasp_drake"))) / "scenarios" / (
        "scenarios.yaml")


def make_parser(plant) -> Parser:
    """A Parser for `plant` that resolves package://tegrasp/ to models_dir()."""
    parser = Parser(plant)
    package_map = parser.package_map()
    if not package_map.Contains(PACKAGE_NAME):
        package_map.Add(PACKAGE_NAME, str(models_dir()))
    return parser
