"""The package finds its models and events."""

import pathlib

import tegrasp_drake
from tegrasp_drake.rig import paths

CHECKOUT = pathlib.Path(tegrasp_drake.__file__).resolve().parents[1]


def test_a_source_checkout_uses_its_own_models_and_events():
    # Also when another checkout is installed editable in the same venv.
    assert (CHECKOUT / "pyproject.toml").is_file()
    assert paths.models_dir() == CHECKOUT / "models"
    assert paths.package_events_dir() == CHECKOUT / "events"
    assert (paths.models_dir() / "package.xml").is_file()
    assert (paths.package_events_dir() / "index.json").is_file()


def test_the_package_folder_is_the_one_imported():
    # paths.py sits one folder below the package; a wrong depth would hand out the data of
    # whichever checkout is installed instead of this one.
    assert paths.PACKAGE_DIR == pathlib.Path(tegrasp_drake.__file__).resolve().parent
