"""Bad inputs the twenty-second review found, one test per rule."""

import base64
import json
import os
import pathlib
import struct
import subprocess
import sys

import pytest

from tests.test_bad_input import run_cli
from tests.test_bad_input_round18 import (_USER_OBJECT, _mesh_collision, _model,
                                          no_simulation)  # noqa: F401 (a fixture)

_REPOSITORY = pathlib.Path(__file__).resolve().parents[1]


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
    return _model(tmp_path, _mesh_collision("box.gltf"))


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
        ["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"), *_USER_OBJECT,
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
    return _model(tmp_path, _mesh_collision("box.obj"))


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
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
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
    file = _model(tmp_path, '<collision name="c"><geometry><box><size>0.04 0.04 0.1</size>'
                            '</box></geometry><pose>0 0 0.05 0 0 0</pose></collision>')
    file.write_text(file.read_text().replace(
        "</link>", "</link><include><uri>file:///dev/zero</uri></include>"))
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text, text
    assert "includes another model (<include>)" in text, text


def _obj_mesh_model(tmp_path, obj_text: str, scale: str = "1 1 1"):
    """A model file whose collision mesh is the OBJ `obj_text`, scaled by `scale`."""
    (tmp_path / "shape.obj").write_text(obj_text)
    return _model(tmp_path, '<collision name="c"><geometry><mesh><uri>shape.obj</uri>'
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
    (lambda tmp_path: _model(tmp_path, '<collision name="c"><geometry><box><size>0.04 0.04 '
                                       '0.1</size></box></geometry></collision>'), _SPANS),
    (lambda tmp_path: _obj_mesh_model(tmp_path, _FLAT_OBJ), "it is flat or a needle"),
    (_urdf_mirrored_mesh, "by [-1, 1, 1]: each factor must be positive"),
    (lambda tmp_path: _model(tmp_path, '<collision name="c"><geometry><plane><normal>0 0 1'
                                       '</normal></plane></geometry></collision>'),
     "has a collision shape HalfSpace, which is no bounded solid"),
], ids=["scaled-1e30", "twice-the-size", "centred-not-on-its-base", "flat", "mirrored",
        "half-space"])
def test_a_model_whose_geometry_is_not_object_size_is_refused(model, words, tmp_path,
                                                               no_simulation, capfd):
    file = model(tmp_path)
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
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
    check_model_file(str(_model(tmp_path, f'<collision name="c">{collision}</collision>')),
                     "scenario", size)


# Rule: a warning Drake gives while loading a user's model (an OBJ face naming a vertex the
# OBJ does not have, which Drake drops with a warning) refuses the model, in one line naming
# object.file and the warning; the run does not go on with what Drake made of it.
def test_a_model_drake_warns_about_is_refused(tmp_path, no_simulation, capfd):
    file = _obj_mesh_model(tmp_path, _CUBE_OBJ + "f 1 2 3 999999999\n")
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "run"),
                          *_USER_OBJECT, "--set", f"object.file={file}"], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert "field 'object.file'" in text and str(file) in text, text
    assert "is not a model Drake loads cleanly" in text and "Vertex indices out of" in text, text
