"""The check of your own object's model file (object.file: an SDF or URDF path, or a
package:// URL) before anything simulates, each refusal one line naming object.file.

It is checked as every other file the user names: the file, each mesh file it names, and
each file a mesh names in turn (a glTF's buffers and images, an OBJ's material libraries
and their textures), resolved as Drake resolves them, must be a regular file that exists
and is at most a bounded size. The file declares no DTD (a model has no use for one, and
its entities could expand a small file into gigabytes, the "billion laughs", before Drake
reads a body) and includes no other model (<include>: one body needs none, and what it
names is another model file, unchecked).

Then Drake loads it as the station will, into a plant with a SceneGraph, so that its
geometry is made (mesh files read, convex hulls computed): what Drake cannot use, or warns
about, is refused here, not at station build. It must hold one model of one body, free (no
joint or weld to the world or anything: the hand must lift it), with collision geometry: a
body the hand cannot touch is nothing to grasp. That geometry must
fill the box object.size gives, where the object's frame puts it (rig/objects.py: frame at
the centre of the base, z up, y along the finger stroke), within SIZE_TOLERANCE_M on each
side, each of its shapes a solid (no flat or needle hull), each mesh scaled by positive
factors (a negative one mirrors it, turning its faces inside out): the grasp plan uses
object.size, not the model, to open, place and close the fingers."""

import contextlib
import json
import logging
import math
import pathlib
import re
import xml.parsers.expat

import numpy as np

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.files import file_problem, read_bounded
from tegrasp_drake.rig.objects import FINGER_CLEARANCE_M, MIN_SIZE_M
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
# How far [m] each side of the model's collision geometry may lie from the box object.size
# places in its frame: the grasp plan opens the fingers FINGER_CLEARANCE_M clear of the box
# object.size gives and sets its grasp height from it; a model wider by more is struck by an
# open pad, one narrower or off its frame by more is closed on where it is not.
SIZE_TOLERANCE_M = FINGER_CLEARANCE_M
# The least volume [m^3] of each collision shape: a cube of MIN_SIZE_M, the smallest extent
# the contact geometry resolves (rig/objects.py). A flat mesh's hull (volume 0) is no solid
# for the pads to squeeze, and Drake meets a non-finite pose at extents far under it.
MIN_SHAPE_VOLUME_M3 = MIN_SIZE_M ** 3
MODEL_SUFFIXES = (".sdf", ".urdf")  # the formats docs/user-guide.md names for object.file
_URL_SCHEMES = ("package://", "model://", "file://")  # what Drake's PackageMap resolves


def check_model_file(file: str, source: str, size) -> None:
    """ConfigError naming `source` and field object.file unless `file` (module docstring)
    is a model file with no DTD that Drake loads with its meshes, holding one model of one
    free body (no joint, no <static>) whose collision geometry fills the box of object.size
    `size` [m]: [width along the stroke, depth, height] (rig/objects.OBJECT_SIZES)."""
    if not file:
        raise ConfigError(f"{source}: field 'object.file' is required for shape 'file'")
    plant, scene_graph, parser = _plant_and_parser()
    path = _model_path(file, parser.package_map(), source)
    for mesh in _mesh_references(path, f"{source}: field 'object.file': '{file}'"):
        mesh_path = _check_mesh(mesh, path, file, parser.package_map(), source)
        _check_supporting_files(
            mesh_path, f"{source}: field 'object.file': '{file}' names the mesh '{mesh}', which")
    try:
        with _drake_warnings() as warnings:
            if file.startswith("package://"):
                instances = parser.AddModels(url=file)
            else:
                instances = parser.AddModels(file_name=file)
    except (RuntimeError, ValueError) as e:
        raise ConfigError(f"{source}: field 'object.file': '{file}' is not a model Drake "
                          f"can load: {drake_error_line(e)}") from None
    if warnings:
        raise ConfigError(
            f"{source}: field 'object.file': '{file}' is not a model Drake loads cleanly: it "
            f"warned ({len(warnings)} warning(s)), first: "
            f"{drake_error_line(warnings[0]).removeprefix('warning: ')}; fix the model")
    problem = one_body_problem(plant, instances) or joints_problem(plant, instances[0])
    if problem:
        raise ConfigError(f"{source}: field 'object.file': '{file}' {problem}")
    (body_index,) = plant.GetBodyIndices(instances[0])
    body = plant.get_body(body_index)
    if not plant.GetCollisionGeometriesForBody(body):
        raise ConfigError(
            f"{source}: field 'object.file': '{file}' has no collision geometry on its body "
            f"'{body.name()}', so the hand has nothing to grasp; give its link a <collision>")
    _check_geometry(plant, scene_graph.model_inspector(), body, size,
                    f"{source}: field 'object.file': '{file}'")
    _check_centre_of_mass(body, size, f"{source}: field 'object.file': '{file}'")


def _check_centre_of_mass(body, size, named: str) -> None:
    """ConfigError, `named` first, unless the body's centre of mass (its <inertial> pose)
    lies within the box of object.size `size` that its collision geometry fills
    (_check_geometry), within SIZE_TOLERANCE_M: a solid's centre of mass lies within its
    convex hull, so one outside is a typo in the pose (metres for millimetres), which would
    make the simulated object topple or swing in the hand as no real one does."""
    width, depth, height = size
    low = np.array([-depth / 2, -width / 2, 0.0]) - SIZE_TOLERANCE_M
    high = np.array([depth / 2, width / 2, height]) + SIZE_TOLERANCE_M
    com = np.asarray(body.default_spatial_inertia().get_com())
    if not (np.all(com >= low) and np.all(com <= high)):
        box = ", ".join(f"{axis} {_numbers([a * 1000, b * 1000])}"
                        for axis, a, b in zip("xyz", low, high))
        raise ConfigError(
            f"{named} puts its body's centre of mass at {_numbers(com * 1000)} mm (its "
            f"<inertial> pose, body frame), outside the object's box, {box} mm: a solid's "
            "centre of mass lies within it; fix the <inertial> <pose>")


def one_body_problem(plant, instances) -> str | None:
    """What is wrong, in words after the file's name, with the model instances `instances`
    that a model file added to `plant` as the object, unless they are one model of one body;
    else None. The station places, senses and lifts the object as one body."""
    bodies = [plant.get_body(b).name() for i in instances for b in plant.GetBodyIndices(i)]
    if len(instances) == 1 and len(bodies) == 1:
        return None
    return (f"must hold one model with one body (the object), it holds {len(instances)} "
            f"model(s) with bodies {bodies}")


def joints_problem(plant, instance) -> str | None:
    """What is wrong, in words after the file's name, with the model instance `instance` of
    `plant` (not yet finalized) as the object, if it has any joint; else None. Its body must
    be free, as the station places it and the hand lifts it. Drake makes a joint, before the
    plant is finalized, for each <joint> of an SDF or URDF model (to the world or anything)
    and a weld to the world for the link of an SDF <static>true</static> model; a free body
    has none until Finalize gives it its floating joint."""
    joints = [plant.get_joint(j) for j in plant.GetJointIndices(instance)]
    if not joints:
        return None
    listed = ", ".join(f"'{j.name()}' ({j.type_name()}, '{j.parent_body().name()}' to "
                       f"'{j.child_body().name()}')" for j in joints)
    return (f"joins its body to another by the joint(s) {listed}: the object must be one "
            f"free body the hand can lift; remove its <joint> elements (and any "
            f"<static>true</static>, which welds it to the world)")


def drake_error_line(error: Exception) -> str:
    """The first line of a Drake parse error (its text, else its type's name)."""
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


class _Collected(logging.Handler):
    """The messages of the log records it is handed."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


@contextlib.contextmanager
def _drake_warnings():
    """The messages Drake logs (pydrake hands its log to the Python logger "drake") at
    WARNING or above while the block runs, kept from the terminal: a warning about the
    model (an OBJ face naming a vertex it does not have, which Drake drops) is a refusal,
    in one line."""
    logger = logging.getLogger("drake")
    collected, propagate = _Collected(), logger.propagate
    logger.addHandler(collected)
    logger.propagate = False
    try:
        yield collected.messages
    finally:
        logger.removeHandler(collected)
        logger.propagate = propagate


def _plant_and_parser():
    """A plant registered with a SceneGraph (so that the parser makes its geometry, as in
    the station), the SceneGraph, and a parser resolving package://tegrasp/."""
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder
    plant, scene_graph = AddMultibodyPlantSceneGraph(DiagramBuilder(), time_step=0.0)
    return plant, scene_graph, paths.make_parser(plant)


def _check_geometry(plant, inspector, body, size, named: str) -> None:
    """ConfigError, `named` first, unless each mesh of `body` (collision or visual) has a
    positive scale, each collision shape is a solid of at least MIN_SHAPE_VOLUME_M3, and
    their bounding box in the body's frame is the box of object.size `size` (module
    docstring) within SIZE_TOLERANCE_M on each side."""
    from pydrake.geometry import Convex, Mesh
    for geometry in (plant.GetCollisionGeometriesForBody(body)
                     + plant.GetVisualGeometriesForBody(body)):
        shape = inspector.GetShape(geometry)
        if isinstance(shape, (Mesh, Convex)) and not np.all(shape.scale3() > 0):
            raise ConfigError(
                f"{named} scales its mesh '{shape.source().description()}' by "
                f"{_numbers(shape.scale3())}: each factor must be positive (a negative one "
                f"mirrors the mesh, turning its faces inside out); mirror the mesh file instead")
    low, high = np.full(3, np.inf), np.full(3, -np.inf)
    for geometry in plant.GetCollisionGeometriesForBody(body):
        shape = inspector.GetShape(geometry)
        support, volume = _support_and_volume(shape, named)
        if not volume >= MIN_SHAPE_VOLUME_M3:  # also NaN
            raise ConfigError(
                f"{named} has the collision shape '{inspector.GetName(geometry)}' of volume "
                f"{volume:.3g} m^3, less than a {MIN_SIZE_M * 1000:g} mm cube's: it is flat "
                f"or a needle, no solid for the fingers to squeeze; give a closed solid")
        X_BG = inspector.GetPoseInFrame(geometry)
        R_BG, p_BG = X_BG.rotation().matrix(), X_BG.translation()
        for axis in range(3):  # the body axis in G: row `axis` of R_BG
            low[axis] = min(low[axis], p_BG[axis] - support(-R_BG[axis]))
            high[axis] = max(high[axis], p_BG[axis] + support(R_BG[axis]))
    width, depth, height = size
    want_low, want_high = (np.array([-depth / 2, -width / 2, 0.0]),
                           np.array([depth / 2, width / 2, height]))
    if not (np.all(np.abs(low - want_low) <= SIZE_TOLERANCE_M)
            and np.all(np.abs(high - want_high) <= SIZE_TOLERANCE_M)):
        spans = ", ".join(f"{axis} {_numbers([a * 1000, b * 1000])}"
                          for axis, a, b in zip("xyz", low, high))
        wanted = ", ".join(f"{axis} {_numbers([a * 1000, b * 1000])}"
                           for axis, a, b in zip("xyz", want_low, want_high))
        raise ConfigError(
            f"{named} has collision geometry spanning {spans} mm in its body's frame, but "
            f"object.size {_numbers(size)} m puts the object at {wanted} mm (frame at the "
            f"centre of its base, z up, y along the stroke), each side within "
            f"{SIZE_TOLERANCE_M * 1000:g} mm: the grasp plan uses object.size; give the "
            f"model's size, or place and scale its geometry so")


def _support_and_volume(shape, named: str):
    """(h, volume [m^3]) of a collision shape: h(d) is how far [m] it reaches along the unit
    vector d of its own frame G (its support function), volume its solid's (a mesh's: its
    convex hull's, the shape Drake's point contact uses)."""
    from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Mesh, Sphere
    if isinstance(shape, Box):
        half = np.array([shape.width(), shape.depth(), shape.height()]) / 2
        return (lambda d: float(np.abs(d) @ half)), float(np.prod(2 * half))
    if isinstance(shape, Sphere):
        r = shape.radius()
        return (lambda d: r), 4 / 3 * math.pi * r ** 3
    if isinstance(shape, Cylinder):
        r, half = shape.radius(), shape.length() / 2
        return (lambda d: r * math.hypot(d[0], d[1]) + half * abs(d[2])), \
            math.pi * r ** 2 * 2 * half
    if isinstance(shape, Capsule):
        r, half = shape.radius(), shape.length() / 2
        return (lambda d: r + half * abs(d[2])), \
            math.pi * r ** 2 * 2 * half + 4 / 3 * math.pi * r ** 3
    if isinstance(shape, Ellipsoid):
        axes = np.array([shape.a(), shape.b(), shape.c()])
        return (lambda d: float(np.linalg.norm(axes * d))), 4 / 3 * math.pi * np.prod(axes)
    if isinstance(shape, (Mesh, Convex)):
        hull = shape.GetConvexHull()
        vertices = np.array([hull.vertex(i) for i in range(hull.num_vertices())])
        return (lambda d: float(np.max(vertices @ d))), _hull_volume(hull, vertices)
    raise ConfigError(f"{named} has a collision shape {type(shape).__name__}, which is no "
                      f"bounded solid to grasp; give a box, sphere, cylinder, capsule, "
                      f"ellipsoid or mesh")


def _hull_volume(hull, vertices) -> float:
    """The volume [m^3] a closed polygon mesh `hull` (its `vertices`) bounds: the sum over
    its faces, fanned into triangles, of the signed volumes of the tetrahedra they make with
    the origin (divergence theorem); a flat hull's faces, both sides of one polygon, sum to
    zero."""
    volume = 0.0
    for face in range(hull.num_elements()):
        polygon = hull.element(face)
        corners = vertices[[polygon.vertex(j) for j in range(polygon.num_vertices())]]
        for j in range(1, len(corners) - 1):
            volume += float(np.dot(corners[0], np.cross(corners[j], corners[j + 1]))) / 6
    return abs(volume)


def _numbers(values) -> str:
    """`values` as [a, b, ...] with up to 4 significant digits."""
    return "[" + ", ".join(f"{float(v):.4g}" for v in values) + "]"


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
        document = json.loads(read_bounded(mesh, MAX_MESH_FILE_BYTES))
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
    for line in read_bounded(path, MAX_SUPPORTING_FILE_BYTES).decode(
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
    problem = file_problem(path)
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
        parser.Parse(read_bounded(path, MAX_MODEL_FILE_BYTES), True)
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
