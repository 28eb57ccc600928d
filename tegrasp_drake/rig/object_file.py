"""The check of your own object's model file (object.file: an SDF or URDF path, or a
package:// URL) before anything simulates. It is checked as every other file the user
names: the file, and each mesh file it names, must be a regular file that exists and is at
most a bounded size, and so must each file a mesh names in turn (a glTF's buffers and images,
an OBJ's material libraries and their textures), resolved as Drake resolves them; the file
declares no DTD (a model has no use for one, and its
entities could expand a small file into gigabytes, the "billion laughs", before Drake reads
a body). Then Drake loads it as the station will, into a plant with a SceneGraph, so that
its geometry is made (mesh files read, convex hulls computed) and what Drake cannot use is
refused here, in one line naming object.file, not at station build. It must hold one model
of one body, with collision geometry: a body the hand cannot touch is nothing to grasp; it
includes no other model (<include>): one body needs none, and what an include names is
another model file, unchecked."""

import json
import pathlib
import re
import xml.parsers.expat

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.files import file_problem, read_bounded
from tegrasp_drake.rig.typed_yaml import ConfigError

# The most bytes of a model file: it describes one body (its inertia, a few geometries and
# their properties) in a few kilobytes, its meshes being files of their own; as a
# configuration file, it is bounded as YAML files are (rig/typed_yaml.MAX_YAML_BYTES).
MAX_MODEL_FILE_BYTES = 1_000_000
# The most bytes of a mesh file a model names: a 16 MB OBJ holds about 500 000 vertices,
# far more than a graspable object's convex hull or contact surface needs, and Drake holds
# it in memory in each sweep worker (sweep/runner.WORKER_MEMORY_BYTES, 330 MB each).
MAX_MESH_FILE_BYTES = 16_000_000
# A file a mesh names (a glTF buffer or image, an OBJ's material library or texture) is held
# in memory as the mesh is, in each sweep worker: it is bounded as a mesh file.
MAX_SUPPORTING_FILE_BYTES = MAX_MESH_FILE_BYTES
# The MTL keywords besides map_* whose value ends in a texture file's name (options before
# it), as tinyobjloader, Drake's OBJ reader, reads a material library.
_TEXTURE_KEYWORDS = ("bump", "disp", "decal", "refl", "norm")
_URI_SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
MODEL_SUFFIXES = (".sdf", ".urdf")  # the formats docs/user-guide.md names for object.file
_URL_SCHEMES = ("package://", "model://", "file://")  # what Drake's PackageMap resolves


def check_model_file(file: str, source: str) -> None:
    """ConfigError naming `source` and field object.file unless `file` (module docstring)
    is a model file with no DTD that Drake loads with its meshes, holding one model of one
    body with collision geometry."""
    if not file:
        raise ConfigError(f"{source}: field 'object.file' is required for shape 'file'")
    plant, parser = _plant_and_parser()
    path = _model_path(file, parser.package_map(), source)
    for mesh in _mesh_references(path, f"{source}: field 'object.file': '{file}'"):
        mesh_path = _check_mesh(mesh, path, file, parser.package_map(), source)
        _check_supporting_files(
            mesh_path, f"{source}: field 'object.file': '{file}' names the mesh '{mesh}', which")
    try:
        if file.startswith("package://"):
            instances = parser.AddModels(url=file)
        else:
            instances = parser.AddModels(file_name=file)
    except (RuntimeError, ValueError) as e:
        raise ConfigError(f"{source}: field 'object.file': '{file}' is not a model Drake "
                          f"can load: {drake_error_line(e)}") from None
    bodies = [plant.get_body(b).name() for i in instances for b in plant.GetBodyIndices(i)]
    if len(instances) != 1 or len(bodies) != 1:
        raise ConfigError(
            f"{source}: field 'object.file': '{file}' must hold one model with one body "
            f"(the object), it holds {len(instances)} model(s) with bodies {bodies}")
    if not plant.GetCollisionGeometriesForBody(plant.GetBodyByName(bodies[0], instances[0])):
        raise ConfigError(
            f"{source}: field 'object.file': '{file}' has no collision geometry on its body "
            f"'{bodies[0]}', so the hand has nothing to grasp; give its link a <collision>")


def drake_error_line(error: Exception) -> str:
    """The first line of a Drake parse error (its text, else its type's name)."""
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


def _plant_and_parser():
    """A plant registered with a SceneGraph (so that the parser makes its geometry, as in
    the station) and a parser resolving package://tegrasp/."""
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder
    plant, _ = AddMultibodyPlantSceneGraph(DiagramBuilder(), time_step=0.0)
    return plant, paths.make_parser(plant)


def _model_path(file: str, package_map, source: str) -> pathlib.Path:
    """The model file's path on disk, checked as a user's file: it exists, is a regular
    file (no device, FIFO or folder), is at most MAX_MODEL_FILE_BYTES, and is SDF or URDF."""
    named = f"{source}: field 'object.file': model file '{file}'"
    path = _resolved(file, package_map, pathlib.Path.cwd(),
                     f"{source}: field 'object.file': '{file}' is not a model Drake can load")
    _check_regular_file(path, MAX_MODEL_FILE_BYTES, named)
    if path.suffix.lower() not in MODEL_SUFFIXES:
        raise ConfigError(f"{named} is not an SDF or URDF file (its name ends in "
                          f"'{path.suffix}'); give a .sdf or .urdf file")
    return path


def _check_mesh(uri: str, model: pathlib.Path, file: str, package_map,
                source: str) -> pathlib.Path:
    """The file the mesh `uri` that `model` names resolves to; ConfigError unless it is a
    regular file of at most MAX_MESH_FILE_BYTES."""
    named = f"{source}: field 'object.file': '{file}' names the mesh '{uri}', which"
    path = _resolved(uri, package_map, model.parent, f"{named} cannot be found")
    _check_regular_file(path, MAX_MESH_FILE_BYTES, named)
    return path


def _check_supporting_files(mesh: pathlib.Path, named: str) -> None:
    """ConfigError, `named` (ending in "which") first, unless each file the mesh file `mesh`
    names is a regular file of at most MAX_SUPPORTING_FILE_BYTES: a glTF's buffers and images
    (data: URIs aside), an OBJ's material libraries (mtllib) and the textures they name."""
    suffix = mesh.suffix.lower()
    if suffix == ".gltf":
        for kind, uri in _gltf_uris(mesh, named):
            _check_regular_file(mesh.parent / _gltf_relative_path(uri, kind, named),
                                MAX_SUPPORTING_FILE_BYTES,
                                f"{named} names the file '{uri}' in its {kind}, which")
    elif suffix == ".obj":
        for library in _obj_file_names(mesh, "mtllib".__eq__, last_only=False):
            library_path = mesh.parent / library
            library_named = f"{named} names the material library '{library}', which"
            _check_regular_file(library_path, MAX_SUPPORTING_FILE_BYTES, library_named)
            for texture in _obj_file_names(library_path, _is_texture_keyword,
                                           last_only=True):
                _check_regular_file(library_path.parent / texture, MAX_SUPPORTING_FILE_BYTES,
                                    f"{library_named} names the texture '{texture}', which")


def _gltf_uris(mesh: pathlib.Path, named: str) -> list[tuple[str, str]]:
    """(buffers or images, uri) of each entry of the glTF file `mesh` that names a file (an
    entry without a uri is a .glb's own chunk, a data: URI holds its bytes)."""
    try:
        document = json.loads(read_bounded(mesh, MAX_MESH_FILE_BYTES, devices=()))
    except (ValueError, RecursionError) as e:
        raise ConfigError(f"{named} is not a glTF file Drake can read: it is not JSON "
                          f"({type(e).__name__}: {e})") from None
    uris = []
    for kind in ("buffers", "images"):
        entries = document.get(kind) if isinstance(document, dict) else None
        for entry in entries if isinstance(entries, list) else []:
            uri = entry.get("uri") if isinstance(entry, dict) else None
            if isinstance(uri, str) and not uri.lower().startswith("data:"):
                uris.append((kind, uri))
    return uris


def _gltf_relative_path(uri: str, kind: str, named: str) -> str:
    """`uri` as the path, relative to the glTF's folder, Drake reads it from; ConfigError
    for a URI Drake does not read. Drake's glTF reader (geometry/vtk_gltf_uri_loader.cc)
    reads data: URIs and file references it resolves against the glTF's own folder: an
    absolute path, a file:// or other scheme's URI, or a path out of that folder (..) is
    not read (Drake stops the process at a file URI it did not make). A percent-escape,
    query or fragment would be read differently by this check and by Drake's URI parser."""
    if (_URI_SCHEME.match(uri) or uri.startswith("/") or ".." in uri.split("/")
            or any(character in uri for character in "%?#\\") or not uri.strip()):
        raise ConfigError(
            f"{named} names '{uri}' in its {kind}, which Drake does not read: give a data: "
            f"URI or the name of a file in the glTF's folder (or below it), with no '..', "
            f"'%', '?', '#' or '\\'")
    return uri


def _obj_file_names(path: pathlib.Path, keyword, *, last_only: bool) -> list[str]:
    """The file names the OBJ or MTL file `path` gives on its lines whose first word is a
    `keyword` (a predicate), as tinyobjloader splits them: every word after it (an OBJ's
    mtllib may name several libraries), or the last word only (a texture, its options before
    it)."""
    names = []
    for line in read_bounded(path, MAX_SUPPORTING_FILE_BYTES, devices=()).decode(
            "utf-8", errors="replace").splitlines():
        words = line.split()
        if len(words) > 1 and keyword(words[0]):
            names.extend(words[-1:] if last_only else words[1:])
    return names


def _is_texture_keyword(word: str) -> bool:
    """Whether an MTL line starting with `word` names a texture file (map_Kd, bump, ...)."""
    return word.startswith("map_") or word in _TEXTURE_KEYWORDS


def _resolved(uri: str, package_map, folder: pathlib.Path, refusal: str) -> pathlib.Path:
    """The file `uri` names: a package://, model:// or file:// URL as Drake resolves it
    (ConfigError `refusal`: Drake's words when it cannot), else a path (relative to
    `folder`, as Drake reads it)."""
    if uri.startswith(_URL_SCHEMES):
        try:
            return pathlib.Path(package_map.ResolveUrl(uri))
        except RuntimeError as e:
            raise ConfigError(f"{refusal}: "
                              f"{drake_error_line(e).removeprefix('error: ')}") from None
    return folder / uri


def _check_regular_file(path: pathlib.Path, limit: int, named: str) -> None:
    """ConfigError, `named` first, unless `path` is a regular file of at most `limit` bytes
    (a model or mesh is never a device: not /dev/null or /dev/zero either)."""
    problem = file_problem(path, devices=())
    if problem is None and path.stat().st_size > limit:
        problem = f"is larger than {limit} bytes, the most this reads"
    if problem:
        raise ConfigError(f"{named} {problem}")


class _DocumentTypeDeclared(Exception):
    """The model file declares a DTD (refused before its entities are expanded)."""


class _ModelIncluded(Exception):
    """The model file includes another model (refused before Drake reads what it names)."""


def _mesh_references(path: pathlib.Path, named: str) -> list[str]:
    """The mesh files an SDF (<mesh><uri>) or URDF (<mesh filename=...>) file names, in the
    order given. ConfigError, `named` first, for a file that is not well-formed XML, that
    declares a DTD (<!DOCTYPE ...>), refused as the parser meets it: before any entity, or
    that includes another model (SDF <include>; URDF has no include)."""
    meshes, elements, text = [], [], []

    def start(name, attributes):
        elements.append(name.rpartition(":")[2])
        text.clear()
        if elements[-1] == "include":
            raise _ModelIncluded()
        if elements[-1] == "mesh" and attributes.get("filename"):
            meshes.append(attributes["filename"].strip())

    def end(name):
        if elements[-2:] == ["mesh", "uri"]:
            meshes.append("".join(text).strip())
        elements.pop()

    def document_type(*declaration):
        raise _DocumentTypeDeclared()

    parser = xml.parsers.expat.ParserCreate()
    parser.StartElementHandler, parser.EndElementHandler = start, end
    parser.CharacterDataHandler = text.append
    parser.StartDoctypeDeclHandler = document_type
    try:
        parser.Parse(read_bounded(path, MAX_MODEL_FILE_BYTES, devices=()), True)
    except _DocumentTypeDeclared:
        raise ConfigError(f"{named} declares a document type (<!DOCTYPE ...>), which a model "
                          "file has no use for and whose entities could expand without "
                          "bound; remove it (and any &entity; it defines)") from None
    except _ModelIncluded:
        raise ConfigError(f"{named} includes another model (<include>), which the one body of "
                          "an object has no use for; put the body's link in this file "
                          "instead") from None
    except xml.parsers.expat.ExpatError as e:
        raise ConfigError(f"{named} is not a model Drake can load: it is not well-formed XML "
                          f"({e})") from None
    return [mesh for mesh in meshes if mesh]
