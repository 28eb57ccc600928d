"""A user's object model whose body is jointed or welded to anything (the world included):
the object must be one free body the hand can lift, so such a model is refused at load, in
one line naming object.file, before any trial simulates. SDF and URDF models."""

import pytest

from tests.test_bad_input import run_cli
from tests.test_bad_input_round18 import _USER_OBJECT, no_simulation  # noqa: F401 (fixture)

_SIZE = [0.04, 0.04, 0.1]  # the box both forms below hold: 40 x 40 x 100 mm on its base
_SDF_LINK = ('<link name="body"><inertial><mass>0.1</mass><inertia><ixx>1e-4</ixx>'
             '<iyy>1e-4</iyy><izz>1e-4</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>'
             '</inertial><collision name="c"><pose>0 0 0.05 0 0 0</pose><geometry><box><size>'
             '0.04 0.04 0.1</size></box></geometry></collision></link>')
_URDF_LINK = ('<link name="body"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" '
              'izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial><collision><origin '
              'xyz="0 0 0.05"/><geometry><box size="0.04 0.04 0.1"/></geometry></collision>'
              '</link>')


def _sdf(tmp_path, model_contents: str = "", model_first: str = ""):
    """An SDF file of one model of the one link _SDF_LINK, `model_first` before the link
    (a <static>) and `model_contents` after it (a <joint>)."""
    file = tmp_path / "object.sdf"
    file.write_text(f'<?xml version="1.0"?><sdf version="1.9"><model name="mine">'
                    f"{model_first}{_SDF_LINK}{model_contents}</model></sdf>")
    return file


def _sdf_joint(kind: str) -> str:
    axis = "" if kind in ("fixed", "ball") else "<axis><xyz>0 0 1</xyz></axis>"
    return (f'<joint name="j" type="{kind}"><parent>world</parent><child>body</child>{axis}'
            f"</joint>")


def _urdf(tmp_path, robot_contents: str = ""):
    """A URDF file of the one link _URDF_LINK, then `robot_contents` (a world link, a joint)."""
    file = tmp_path / "object.urdf"
    file.write_text(f'<?xml version="1.0"?><robot name="mine">{_URDF_LINK}{robot_contents}'
                    "</robot>")
    return file


def _urdf_joint(kind: str) -> str:
    extra = ('<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
             if kind in ("revolute", "prismatic") else "")
    return (f'<link name="world"/><joint name="j" type="{kind}"><parent link="world"/>'
            f'<child link="body"/>{extra}</joint>')


_JOINTED = {
    "sdf-revolute-to-world": lambda tmp_path: _sdf(tmp_path, _sdf_joint("revolute")),
    "sdf-prismatic-to-world": lambda tmp_path: _sdf(tmp_path, _sdf_joint("prismatic")),
    "sdf-ball-to-world": lambda tmp_path: _sdf(tmp_path, _sdf_joint("ball")),
    "sdf-fixed-to-world": lambda tmp_path: _sdf(tmp_path, _sdf_joint("fixed")),
    "sdf-static-model": lambda tmp_path: _sdf(tmp_path, model_first="<static>true</static>"),
    "urdf-fixed-to-world": lambda tmp_path: _urdf(tmp_path, _urdf_joint("fixed")),
    "urdf-revolute-to-world": lambda tmp_path: _urdf(tmp_path, _urdf_joint("revolute")),
    "urdf-prismatic-to-world": lambda tmp_path: _urdf(tmp_path, _urdf_joint("prismatic")),
}


# Rule: a user's object model must be one free body ("one model of one body", user guide
# "Your own object"): a model whose body has a joint of any kind, to the world or anything,
# or is welded to the world (an SDF <static>true</static> model), is refused as it is loaded,
# naming object.file, its joint and what to do; the hinged object could not be lifted.
@pytest.mark.parametrize("model", _JOINTED.values(), ids=_JOINTED.keys())
def test_a_model_whose_body_is_jointed_or_welded_is_refused(tmp_path, model):
    from tegrasp_drake.rig.object_file import check_model_file
    from tegrasp_drake.rig.typed_yaml import ConfigError
    file = model(tmp_path)
    with pytest.raises(ConfigError) as refused:
        check_model_file(str(file), "scenario", _SIZE)
    text = str(refused.value)
    assert len(text.splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text, text
    assert "one free body" in text and "'body'" in text, text


# Rule: the refusal comes before the trial simulates, one line from the command line (the
# case: an SDF link hinged to the world by a revolute joint).
def test_a_model_hinged_to_the_world_is_refused_before_the_trial(tmp_path, no_simulation,
                                                                  capfd):
    file = _sdf(tmp_path, _sdf_joint("revolute"))
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text and "one free body" in text, text
    assert not (tmp_path / "run").exists()


# Rule (control): the same one link with no joint and no <static>, SDF or URDF, is accepted.
@pytest.mark.parametrize("model", [_sdf, _urdf], ids=["sdf", "urdf"])
def test_the_same_free_body_is_accepted(tmp_path, model):
    from tegrasp_drake.rig.object_file import check_model_file
    check_model_file(str(model(tmp_path)), "scenario", _SIZE)


# Rule: the station build refuses it too (a file changed since the scenario's check, or an
# object config given straight to the builder), one line naming object.file, never a hinged
# object in the simulation.
def test_a_jointed_model_is_refused_at_station_build(tmp_path):
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
    from pydrake.systems.framework import DiagramBuilder

    from tegrasp_drake.rig.files import UserPathError
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.simulation.object_model import AddObject
    file = _sdf(tmp_path, _sdf_joint("revolute"))
    config = ObjectConfig(name="mine", shape="file", size=_SIZE, mass=0.1, friction=0.5,
                          file=str(file))
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), DiagramBuilder())
    with pytest.raises(UserPathError) as refused:
        AddObject(Parser(plant), config)
    text = str(refused.value)
    assert "\n" not in text and "field 'object.file'" in text and str(file) in text, text
    assert "one free body" in text, text
