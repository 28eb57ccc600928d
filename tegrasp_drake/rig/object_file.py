"""The check of your own object's model file (object.file: an SDF or URDF path, or a
package:// URL) before anything simulates. It is checked as every other file the user
names: the file, and each mesh file it names, must be a regular file that exists and is at
most a bounded size, and the file declares no DTD (a model has no use for one, and its
entities could expand a small file into gigabytes, the "billion laughs", before Drake reads
a body). Then Drake loads it as the station will, into a plant with a SceneGraph, so that
its geometry is made (mesh files read, convex hulls computed) and what Drake cannot use is
refused here, in one line naming object.file, not at station build. It must hold one model
of one body, with collision geometry: a body the hand cannot touch is nothing to grasp."""

import pathlib
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
        _check_mesh(mesh, path, file, parser.package_map(), source)
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


def _check_mesh(uri: str, model: pathlib.Path, file: str, package_map, source: str) -> None:
    """ConfigError unless the mesh `uri` that `model` names resolves to a regular file of at
    most MAX_MESH_FILE_BYTES."""
    named = f"{source}: field 'object.file': '{file}' names the mesh '{uri}', which"
    _check_regular_file(_resolved(uri, package_map, model.parent, f"{named} cannot be found"),
                        MAX_MESH_FILE_BYTES, named)


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


def _mesh_references(path: pathlib.Path, named: str) -> list[str]:
    """The mesh files an SDF (<mesh><uri>) or URDF (<mesh filename=...>) file names, in the
    order given. ConfigError, `named` first, for a file that is not well-formed XML, or that
    declares a DTD (<!DOCTYPE ...>), refused as the parser meets it: before any entity."""
    meshes, elements, text = [], [], []

    def start(name, attributes):
        elements.append(name.rpartition(":")[2])
        text.clear()
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
    except xml.parsers.expat.ExpatError as e:
        raise ConfigError(f"{named} is not a model Drake can load: it is not well-formed XML "
                          f"({e})") from None
    return [mesh for mesh in meshes if mesh]
