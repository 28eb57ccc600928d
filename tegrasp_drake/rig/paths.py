"""Where the package's data lives, for editable and non-editable installs alike.

models/ and events/ at the repository top level are installed as the packages
`tegrasp_drake.models_data` and `tegrasp_drake.events_data`; importlib.resources finds them
in either install. When the package is imported from a source checkout (its parent folder
holds pyproject.toml), that checkout's own folders are used: an editable install of another
checkout (a shared venv, with this checkout first on PYTHONPATH) would otherwise hand out
the other checkout's models and events.
"""

import importlib.resources
import pathlib

from pydrake.multibody.parsing import Parser

PACKAGE_NAME = "tegrasp"  # models are reachable as package://tegrasp/...


def _data_dir(package: str, source_folder: str) -> pathlib.Path:
    checkout = pathlib.Path(__file__).resolve().parents[2]  # above tegrasp_drake/rig/
    if (checkout / "pyproject.toml").is_file() and (checkout / source_folder).is_dir():
        return checkout / source_folder  # imported from a source checkout: its own data
    return pathlib.Path(str(importlib.resources.files(package)))


def models_dir() -> pathlib.Path:
    """The folder holding package.xml and the SDF models."""
    return _data_dir("tegrasp_drake.models_data", "models")


def events_dir() -> pathlib.Path:
    """The folder holding the memorized tactile events and their index."""
    return _data_dir("tegrasp_drake.events_data", "events")


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
