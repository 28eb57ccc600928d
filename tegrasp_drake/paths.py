"""Where the package's data lives, for editable and non-editable installs alike.

models/ and events/ at the repository top level are installed as the packages
`tegrasp_drake.models_data` and `tegrasp_drake.events_data`; importlib.resources finds them
in either install.
"""

import importlib.resources
import pathlib

from pydrake.multibody.parsing import Parser

PACKAGE_NAME = "tegrasp"  # models are reachable as package://tegrasp/...


def _data_dir(package: str, source_folder: str) -> pathlib.Path:
    try:
        return pathlib.Path(str(importlib.resources.files(package)))
    except ModuleNotFoundError:
        # Running from a source tree that is not installed (PYTHONPATH=checkout).
        return pathlib.Path(__file__).resolve().parents[1] / source_folder


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
