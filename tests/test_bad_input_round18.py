"""Bad inputs the eighteenth review found, one test per rule."""

import pytest

from tests.test_bad_input import run_cli

_USER_OBJECT = ["--set", "object.name=mine", "--set", "object.shape=file",
                "--set", "object.size=[0.04,0.04,0.1]", "--set", "object.mass=0.1",
                "--set", "object.friction=0.5", "--set", "random_seed=640"]


def _model(tmp_path, link_contents: str, name: str = "object.sdf"):
    """An SDF file of one model of one link holding `link_contents` (after its inertia)."""
    file = tmp_path / name
    file.write_text('<?xml version="1.0"?><sdf version="1.9"><model name="mine">'
                    '<link name="body"><inertial><mass>0.1</mass></inertial>'
                    f"{link_contents}</link></model></sdf>")
    return file


def _mesh_collision(uri: str) -> str:
    return f'<collision name="c"><geometry><mesh><uri>{uri}</uri></mesh></geometry></collision>'


@pytest.fixture
def no_simulation(monkeypatch):
    """Fails a test whose trial reaches its simulator."""
    from tegrasp_drake.runs import trial

    def simulated(*args, **kwargs):
        raise AssertionError("the trial was simulated")
    monkeypatch.setattr(trial, "MakeSimulator", simulated)


def _empty_mesh(tmp_path):
    (tmp_path / "empty.obj").write_text("")
    return "empty.obj"  # relative to the model file, as Drake reads it


def _mesh_over_the_bound(tmp_path):
    from tegrasp_drake.rig.object_file import MAX_MESH_FILE_BYTES
    mesh = tmp_path / "huge.obj"
    with open(mesh, "wb") as stream:
        stream.truncate(MAX_MESH_FILE_BYTES + 1)  # sparse: no disk space used
    return str(mesh)


# Rule: a user's model file is checked as every other user file before anything simulates:
# each mesh it names is a regular file that exists, of bounded size, and Drake loads the
# model with its geometry (a convex hull it cannot make is refused), in one line naming
# object.file; never an internal error at station build.
@pytest.mark.parametrize("mesh, words", [
    (lambda tmp_path: "/dev/zero", "is a device"),
    (lambda tmp_path: "/nonexistent/m.obj", "does not exist"),
    (lambda tmp_path: "package://tegrasp/no_such_mesh.obj", "cannot be found"),
    (_empty_mesh, "is not a model Drake can load"),
    (_mesh_over_the_bound, "is larger than"),
], ids=["device", "missing", "missing-package-url", "no-vertices", "too-large"])
def test_a_model_file_naming_a_mesh_drake_cannot_use_is_refused_before_the_trial(
        mesh, words, tmp_path, no_simulation, capfd):
    file = _model(tmp_path, _mesh_collision(mesh(tmp_path)))
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text and words in text, text


# Rule: a model file Drake cannot load when the station is built (changed since it was
# checked, or an object config given straight to the builder) is one line naming the file.
def test_a_model_file_drake_cannot_load_at_station_build_is_named(tmp_path):
    from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
    from pydrake.multibody.parsing import Parser
    from pydrake.systems.framework import DiagramBuilder

    from tegrasp_drake.rig.files import UserPathError
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.simulation.object_model import AddObject
    file = _model(tmp_path, _mesh_collision("/nonexistent/m.obj"))
    config = ObjectConfig(name="mine", shape="file", size=[0.04, 0.04, 0.1], mass=0.1,
                          friction=0.5, file=str(file))
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), DiagramBuilder())
    with pytest.raises(UserPathError) as refused:
        AddObject(Parser(plant), config)
    assert "field 'object.file'" in str(refused.value) and str(file) in str(refused.value)
    assert "\n" not in str(refused.value)


_BOX = '<geometry><box><size>0.04 0.04 0.1</size></box></geometry>'
# Entities expanding the model's name a thousandfold per 3 levels (a "billion laughs" kind).
_EXPANDING = ('<?xml version="1.0"?>\n<!DOCTYPE sdf [<!ENTITY a "aaaaaaaaaa">'
              '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">'
              '<!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">]>\n'
              '<sdf version="1.9"><model name="&c;"><link name="body"><inertial><mass>0.1'
              f'</mass></inertial><collision name="c">{_BOX}</collision></link></model></sdf>')


def _write(tmp_path, text):
    file = tmp_path / "object.sdf"
    file.write_text(text)
    return file


# Rule: a model the hand cannot touch (a body with no collision geometry: nothing to grasp)
# and a model file declaring a DTD (a model has no use for one; its entities could expand
# without bound) are refused when the scenario is checked, in one line naming object.file.
@pytest.mark.parametrize("model, words", [
    (lambda tmp_path: _model(tmp_path, ""), "has no collision geometry"),
    (lambda tmp_path: _model(tmp_path, f'<visual name="v">{_BOX}</visual>'),
     "has no collision geometry"),
    (lambda tmp_path: _write(tmp_path, _EXPANDING), "declares a document type"),
    (lambda tmp_path: _write(tmp_path, _EXPANDING.replace(
        f'<collision name="c">{_BOX}</collision>', "")), "declares a document type"),
], ids=["inertia-only", "visual-only", "entities", "entities-no-geometry"])
def test_a_model_with_nothing_to_grasp_or_a_dtd_is_refused_before_the_trial(
        model, words, tmp_path, no_simulation, capfd):
    file = model(tmp_path)
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text and words in text, text


# Rule: the environment variable naming the events folder (TEGRASP_EVENTS_DIR) is refused by
# every command that reads events when the folder it names does not exist, as --events is, in
# one line naming the variable; never the package's events in silence. XDG_DATA_HOME is every
# application's: a folder it names may not be made yet (no events recorded).
@pytest.mark.parametrize("variable", ["TEGRASP_EVENTS_DIR"])
@pytest.mark.parametrize("command", [
    ["plot", "events"],
    ["trial", "--set", "random_seed=641"],  # the memorized controller reads its events
], ids=["plot-events", "trial"])
def test_an_events_variable_naming_no_folder_is_refused(variable, command, tmp_path,
                                                        monkeypatch, no_simulation, capfd):
    missing = tmp_path / "no_such_folder"
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    monkeypatch.setenv(variable, str(missing))
    code, text = run_cli([*command, "--out", str(tmp_path / "out.png" if command[0] == "plot"
                                                 else tmp_path / "run")], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert f"{variable}=" in text and f"{missing} does not exist" in text, text


@pytest.mark.parametrize("data_home", ["made", "not_made_yet"])
def test_a_data_folder_without_events_yet_reads_the_packages(data_home, tmp_path, monkeypatch,
                                                             capfd):
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    # no tegrasp/events in it (none recorded), or the folder itself not made yet
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path if data_home == "made"
                                            else tmp_path / "share"))
    code, text = run_cli(["plot", "events", "--out", str(tmp_path / "events.png")], capfd)
    assert code == 0 and (tmp_path / "events.png").is_file(), text
