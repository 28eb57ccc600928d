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


def test_the_users_events_folder_is_the_variable_else_the_users_data_folder(monkeypatch,
                                                                          tmp_path):
    monkeypatch.setenv(paths.EVENTS_ENV, str(tmp_path / "mine"))
    assert paths.user_events_dir() == tmp_path / "mine"
    monkeypatch.delenv(paths.EVENTS_ENV)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    assert paths.user_events_dir() == tmp_path / "data" / "tegrasp" / "events"
    monkeypatch.delenv("XDG_DATA_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert paths.user_events_dir() == tmp_path / "home" / ".local" / "share" / "tegrasp" / (
        "events")


def test_readers_look_in_the_given_folder_alone_else_the_users_then_the_packages(tmp_path):
    assert paths.events_search_path(tmp_path) == [tmp_path]
    assert paths.events_search_path() == [paths.user_events_dir(), paths.package_events_dir()]


def test_a_source_checkouts_events_may_be_remade_but_never_an_installed_copys():
    assert not paths.is_installed_package_data(paths.package_events_dir())
