"""A user's object model (SDF, URDF, OBJ, glTF) is checked before any trial simulates: a file
Drake cannot load or warns about, meshes and material files it cannot use, included models,
geometry not of an object's size, bodies jointed or welded to anything, and objects too small
for the contact geometry are refused in one line naming object.file; the same model done
right is accepted."""

import base64
import json
import os
import pathlib
import struct
import subprocess
import sys

import pytest

import tegrasp_drake
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.bad_input.probes import (USER_OBJECT, assert_one_line_error, mesh_collision,
                                    one_line_of, run_cli, sdf_model_file)


# --- object model files ----------------------------------------------------------------

TWO_LINKS = """<?xml version="1.0"?><sdf version="1.9"><model name="two">
<link name="a"><inertial><mass>0.1</mass></inertial></link>
<link name="b"><inertial><mass>0.1</mass></inertial></link></model></sdf>"""


@pytest.mark.parametrize("content, expected", [
    ("this is not SDF", "is not a model Drake can load"),
    (TWO_LINKS, "must hold one model with one body"),
    (None, "is not a model Drake can load"),  # a package:// URL that does not exist
])
def test_a_bad_object_model_file_is_named(content, expected, tmp_path, capfd):
    if content is None:
        file = "package://tegrasp/no_such_object.sdf"
    else:
        file = tmp_path / "object.sdf"
        file.write_text(content)
    code, text = run_cli(["trial", "--set", "object.name=mine", "--set", "object.shape=file",
                          "--set", f"object.file={file}", "--set", "object.size=[0.04,0.04,0.1]",
                          "--set", "object.mass=0.1", "--set", "object.friction=0.5"], capfd)
    assert_one_line_error(code, text, "field 'object.file'", expected)


@pytest.mark.parametrize("kind, words", [
    ("fifo", "is a named pipe"), ("folder", "is a folder"), ("device", "is a device")])
def test_an_object_file_that_is_not_a_file_says_what_it_is(tmp_path, kind, words):
    path = {"folder": tmp_path, "device": pathlib.Path("/dev/zero")}.get(kind)
    if kind == "fifo":
        path = tmp_path / "objfile.sdf"
        os.mkfifo(path)
    overrides = ["object.name=zz", "object.shape=file", "object.size=[0.05, 0.05, 0.1]",
                 f"object.file={path}", "object.mass=0.1", "object.friction=0.5"]
    with pytest.raises(ConfigError) as refused:
        tegrasp_drake.LoadScenario(name="box", overrides=overrides)
    assert "'object.file'" in one_line_of(refused.value) and words in str(refused.value)
    assert "does not exist" not in str(refused.value)


@pytest.mark.parametrize("override, words", [
    ("object.mass=1.0e-9", "field 'object.mass' must lie in [0.01, 5] kg"),
    ("object.mass=1e-30", "field 'object.mass' must lie in [0.01, 5] kg"),  # read as a number
    ("object.size=[1.0e-4,1.0e-4,0.11]", "field 'object.size[0]' must lie in [0.005, 0.5] m"),
])
def test_a_tiny_object_is_refused_before_drake_sees_it(override, words):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    with pytest.raises(ConfigError) as error:
        LoadScenario(name="box", overrides=[override])
    assert words in str(error.value)


def test_the_smallest_object_is_one_the_contact_geometry_resolves():
    from tegrasp_drake.rig.objects import MIN_SIZE_M
    from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y
    from tegrasp_drake.simulation.object_model import MESH_RESOLUTION_M
    assert MESH_RESOLUTION_M <= MIN_SIZE_M <= min(CELL_X, CELL_Y)


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
    file = sdf_model_file(tmp_path, mesh_collision(mesh(tmp_path)))
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
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
    file = sdf_model_file(tmp_path, mesh_collision("/nonexistent/m.obj"))
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
    (lambda tmp_path: sdf_model_file(tmp_path, ""), "has no collision geometry"),
    (lambda tmp_path: sdf_model_file(tmp_path, f'<visual name="v">{_BOX}</visual>'),
     "has no collision geometry"),
    (lambda tmp_path: _write(tmp_path, _EXPANDING), "declares a document type"),
    (lambda tmp_path: _write(tmp_path, _EXPANDING.replace(
        f'<collision name="c">{_BOX}</collision>', "")), "declares a document type"),
], ids=["inertia-only", "visual-only", "entities", "entities-no-geometry"])
def test_a_model_with_nothing_to_grasp_or_a_dtd_is_refused_before_the_trial(
        model, words, tmp_path, no_simulation, capfd):
    file = model(tmp_path)
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text and words in text, text

_REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def _box_gltf(buffer_uri=None) -> tuple[dict, bytes]:
    """A glTF document of a 4 x 4 x 10 cm box (glTF is y up: Drake turns its y into z, so
    the box stands on its base's centre) and the bytes of its one buffer, to be named by
    `buffer_uri` (None: a data: URI holding them)."""
    corners = [(x, y, z) for x in (-0.02, 0.02) for y in (0.0, 0.1) for z in (-0.02, 0.02)]
    # Two triangles per face, wound outwards.
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    positions = b"".join(struct.pack("<3f", *corner) for corner in corners)
    indices = b"".join(struct.pack("<3H", *face) for face in faces)
    data = positions + indices
    uri = buffer_uri or "data:application/octet-stream;base64," + base64.b64encode(
        data).decode()
    document = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"uri": uri, "byteLength": len(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                        {"buffer": 0, "byteOffset": len(positions),
                         "byteLength": len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                       "min": [-0.02, 0.0, -0.02], "max": [0.02, 0.1, 0.02]},
                      {"bufferView": 1, "componentType": 5123, "count": 36,
                       "type": "SCALAR"}]}
    return document, data


def _gltf_model(tmp_path, buffer_uri=None, image_uri=None):
    """A model file whose collision mesh is the box glTF, its buffer at `buffer_uri`."""
    document, data = _box_gltf(buffer_uri)
    if image_uri is not None:
        document["images"] = [{"uri": image_uri}]
    (tmp_path / "box.bin").write_bytes(data)
    (tmp_path / "box.gltf").write_text(json.dumps(document))
    return sdf_model_file(tmp_path, mesh_collision("box.gltf"))


def _cli_in_its_own_process(argv) -> tuple[int, str]:
    """(exit code, stderr) of `tegrasp ARGV` run in a process of its own: a Drake assertion
    ends the process it fails in."""
    environment = dict(os.environ, PYTHONPATH=str(_REPOSITORY))
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake", *argv], env=environment,
                          capture_output=True, text=True, timeout=300)
    return done.returncode, done.stderr


# Rule: each file a mesh of a user's model names in turn is checked as every other user
# file: a glTF's buffers and images are data: URIs or files in the glTF's folder that Drake
# reads (its glTF reader resolves them there), each a regular file of bounded size; else one
# line naming object.file and the URI, never Drake's assertion (which ends the process).
@pytest.mark.parametrize("buffer_uri, image_uri, words", [
    ("file:///dev/zero", None, "names 'file:///dev/zero' in its buffers, which Drake does not"),
    ("/dev/zero", None, "names '/dev/zero' in its buffers, which Drake does not read"),
    ("../box.bin", None, "names '../box.bin' in its buffers, which Drake does not read"),
    (None, "file:///dev/zero", "names 'file:///dev/zero' in its images, which Drake does not"),
    ("huge.bin", None, "names the file 'huge.bin' in its buffers, which is larger than"),
], ids=["file-url-device", "absolute-device", "out-of-folder", "image-file-url", "too-large"])
def test_a_gltf_naming_a_file_drake_does_not_read_is_refused(tmp_path, buffer_uri, image_uri,
                                                              words):
    from tegrasp_drake.rig.object_file import MAX_SUPPORTING_FILE_BYTES
    with open(tmp_path / "huge.bin", "wb") as stream:
        stream.truncate(MAX_SUPPORTING_FILE_BYTES + 1)  # sparse: no disk space used
    file = _gltf_model(tmp_path, buffer_uri, image_uri)
    code, text = _cli_in_its_own_process(
        ["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"), *USER_OBJECT,
         "--set", f"object.file={file}"])
    assert code == 1 and len(text.strip().splitlines()) == 1, (code, text)
    assert text.startswith("tegrasp: error:") and "field 'object.file'" in text, text
    assert str(file) in text and words in text, text


@pytest.mark.parametrize("buffer_uri", [None, "box.bin"], ids=["data-uri", "relative-file"])
def test_a_gltf_whose_buffer_drake_reads_is_accepted(tmp_path, buffer_uri):
    from tegrasp_drake.rig.object_file import check_model_file
    check_model_file(str(_gltf_model(tmp_path, buffer_uri)), "scenario", [0.04, 0.04, 0.1])

_CUBE_OBJ = "".join(f"v {x} {y} {z}\n" for z in (0, 0.1) for x, y in (
    (-0.02, -0.02), (0.02, -0.02), (0.02, 0.02), (-0.02, 0.02))) + (
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n")


def _obj_model(tmp_path, library: str, texture: str | None = None):
    """A model file whose collision mesh is a 4 x 4 x 10 cm box OBJ naming the material
    library `library` (a file beside it naming `texture`, when given)."""
    (tmp_path / "box.obj").write_text(f"mtllib {library}\n{_CUBE_OBJ}")
    if texture is not None:
        (tmp_path / library).write_text(f"newmtl m\nKd 1 1 1\nmap_Kd -s 1 1 1 {texture}\n")
    return sdf_model_file(tmp_path, mesh_collision("box.obj"))


# Rule: an OBJ's material libraries (mtllib) and the textures they name are regular files
# that exist and are of bounded size (Drake's visualizer reads them), in one line naming
# object.file and the file.
@pytest.mark.parametrize("library, texture, words", [
    ("/dev/zero", None, "names the material library '/dev/zero', which is a device"),
    ("missing.mtl", None, "names the material library 'missing.mtl', which does not exist"),
    ("box.mtl", "/dev/zero", "names the texture '/dev/zero', which is a device"),
], ids=["device", "missing", "texture-device"])
def test_an_obj_naming_a_material_file_that_is_not_a_file_is_refused(
        tmp_path, library, texture, words, no_simulation, capfd):
    file = _obj_model(tmp_path, library, texture)
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text and words in text, text


def test_an_obj_with_its_material_library_is_accepted(tmp_path):
    from tegrasp_drake.rig.object_file import check_model_file
    (tmp_path / "wood.png").write_bytes(b"\x89PNG\r\n\x1a\n")
    check_model_file(str(_obj_model(tmp_path, "box.mtl", "wood.png")), "scenario",
                     [0.04, 0.04, 0.1])


# Rule: a user's model includes no other model (SDF <include>): its one body needs none, and
# what an include names is another model file Drake would read unchecked.
def test_a_model_including_another_model_is_refused(tmp_path, no_simulation, capfd):
    file = sdf_model_file(tmp_path, '<collision name="c"><geometry><box><size>0.04 0.04 0.1</size>'
                            '</box></geometry><pose>0 0 0.05 0 0 0</pose></collision>')
    file.write_text(file.read_text().replace(
        "</link>", "</link><include><uri>file:///dev/zero</uri></include>"))
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text, text
    assert "includes another model (<include>)" in text, text


def _obj_mesh_model(tmp_path, obj_text: str, scale: str = "1 1 1"):
    """A model file whose collision mesh is the OBJ `obj_text`, scaled by `scale`."""
    (tmp_path / "shape.obj").write_text(obj_text)
    return sdf_model_file(tmp_path, '<collision name="c"><geometry><mesh><uri>shape.obj</uri>'
                            f'<scale>{scale}</scale></mesh></geometry></collision>')

_FLAT_OBJ = "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0.1\nv 0.04 0.04 0.1\nf 1 2 3\nf 2 4 3\n"


def _urdf_mirrored_mesh(tmp_path):
    (tmp_path / "box.obj").write_text(_CUBE_OBJ)
    file = tmp_path / "object.urdf"
    file.write_text('<?xml version="1.0"?><robot name="mine"><link name="body"><inertial>'
                    '<mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" '
                    'ixz="0" iyz="0"/></inertial><collision><geometry><mesh filename="box.obj" '
                    'scale="-1 1 1"/></geometry></collision></link></robot>')
    return file

_SPANS = "has collision geometry spanning"


# Rule: a user model's geometry is what object.size says, since the grasp plan uses the
# size: its collision geometry's box in its body frame (centre of the base, z up) matches
# object.size within the fingers' clearance on each side; each collision shape is a solid
# (no flat hull), each mesh scale positive; else one line naming object.file.
@pytest.mark.parametrize("model, words", [
    (lambda tmp_path: _obj_mesh_model(tmp_path, _CUBE_OBJ, "1e30 1e30 1e30"), _SPANS),
    (lambda tmp_path: _obj_mesh_model(tmp_path, _CUBE_OBJ, "2 2 2"), _SPANS),
    (lambda tmp_path: sdf_model_file(tmp_path, '<collision name="c"><geometry><box><size>0.04 0.04 '
                                       '0.1</size></box></geometry></collision>'), _SPANS),
    (lambda tmp_path: _obj_mesh_model(tmp_path, _FLAT_OBJ), "it is flat or a needle"),
    (_urdf_mirrored_mesh, "by [-1, 1, 1]: each factor must be positive"),
    (lambda tmp_path: sdf_model_file(tmp_path, '<collision name="c"><geometry><plane><normal>0 0 1'
                                       '</normal></plane></geometry></collision>'),
     "has a collision shape HalfSpace, which is no bounded solid"),
], ids=["scaled-1e30", "twice-the-size", "centred-not-on-its-base", "flat", "mirrored",
        "half-space"])
def test_a_model_whose_geometry_is_not_object_size_is_refused(model, words, tmp_path,
                                                               no_simulation, capfd):
    file = model(tmp_path)
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text and words in text, text


@pytest.mark.parametrize("collision, size", [
    ('<pose>0 0 0.05 0 0 0</pose><geometry><box><size>0.04 0.04 0.1</size></box></geometry>',
     [0.04, 0.04, 0.1]),
    # A cylinder lying along y: it reaches its radius along x and z, half its length along y.
    ('<pose>0 0 0.02 1.5707963 0 0</pose><geometry><cylinder><radius>0.02</radius><length>'
     '0.06</length></cylinder></geometry>', [0.06, 0.04, 0.04]),
], ids=["box-on-its-base", "lying-cylinder"])
def test_a_model_whose_geometry_is_object_size_is_accepted(tmp_path, collision, size):
    from tegrasp_drake.rig.object_file import check_model_file
    check_model_file(str(sdf_model_file(tmp_path, f'<collision name="c">{collision}</collision>')),
                     "scenario", size)


# Rule: a warning Drake gives while loading a user's model (an OBJ face naming a vertex the
# OBJ does not have, which Drake drops with a warning) refuses the model, in one line naming
# object.file and the warning; the run does not go on with what Drake made of it.
def test_a_model_drake_warns_about_is_refused(tmp_path, no_simulation, capfd):
    file = _obj_mesh_model(tmp_path, _CUBE_OBJ + "f 1 2 3 999999999\n")
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text, text
    assert "is not a model Drake loads cleanly" in text and "Vertex indices out of" in text, text

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
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
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


# Rule: a NUL in object.file (a file, --set, a Scenario changed in Python) is refused naming
# the field, not left to the file checks' ValueError (exit 70).
def test_a_nul_in_the_object_file_is_refused_naming_the_field(tmp_path, capfd, no_simulation):
    import dataclasses
    scenarios = tmp_path / "s.yaml"
    scenarios.write_text('x: {controller: {name: open_loop}, object: {name: myobj, shape: file, '
                         'file: "sdf/good\\0.sdf", size: [0.04, 0.04, 0.1], mass: 0.1, '
                         'friction: 0.5}}\n')
    with pytest.raises(ConfigError) as refused:
        tegrasp_drake.LoadScenario(scenarios, "x")
    assert "field 'object.file' holds a NUL" in one_line_of(refused.value)
    code, text = run_cli(["trial", "--scenario", str(scenarios), "--scenario-name", "x",
                          "--out", str(tmp_path / "run")], capfd)
    assert_one_line_error(code, text, "field 'object.file' holds a NUL")
    assert code == 1
    scenario = tegrasp_drake.LoadScenario(name="box")
    with pytest.raises(ConfigError) as refused:  # the config refuses it as it is made
        dataclasses.replace(scenario.object, name="myobj", shape="file", file="a\0b",
                            mass=0.1, friction=0.5, size=[0.04, 0.04, 0.1])
    assert "field 'file' holds a NUL" in one_line_of(refused.value)


# Rule: a model's centre of mass (its <inertial> pose) lies within the object's box, which its
# collision geometry fills; one 8.7 m away (metres typed for millimetres) is refused when the
# scenario is checked, naming object.file and the pose, before anything is simulated.
def test_a_model_whose_centre_of_mass_lies_outside_it_is_refused(tmp_path, no_simulation,
                                                               capfd):
    file = _write(tmp_path, '<?xml version="1.0"?><sdf version="1.9"><model name="mine">'
                  '<link name="body"><inertial><pose>5 5 5 0 0 0</pose><mass>0.1</mass>'
                  '<inertia><ixx>1e-4</ixx><iyy>1e-4</iyy><izz>1e-4</izz></inertia>'
                  f'</inertial><collision name="c"><pose>0 0 0.05 0 0 0</pose>{_BOX}'
                  '</collision></link></model></sdf>')
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert_one_line_error(code, text, "field 'object.file'", str(file),
                          "centre of mass at [5000, 5000, 5000] mm", "<inertial> <pose>")
