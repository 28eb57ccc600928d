"""The objects to grasp: the paper's three (Fig. 8a) and user-defined ones; frame O at the
centre of the base, z up. The paper gives no sizes: the built-in ones fit the 85 mm stroke
with the +-1.5 cm misplacement and 2.5 mm finger clearance; masses are those of plastic or
cardboard objects that size. `friction` is the geometry's own coefficient, not a pair's
(docs/model.md, "Friction by material pair"), written as both its static and dynamic
coefficient: Drake's discrete solvers use only the dynamic one, for sticking too."""

import dataclasses
import math
import re

from tegrasp_drake.rig.api_boundary import TextPattern, public_dataclass
from tegrasp_drake.rig import materials
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.robotiq.dimensions import PAD_CENTER_Z, PALM_Z
from tegrasp_drake.robotiq.units import STROKE_M
from tegrasp_drake.rig.ranges import bounded, number_problem, real_number
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.unset_fields import unset_when_empty

# The entries of an object's `size` [m] for each shape.
OBJECT_SIZES = {"box": ("x", "y", "z"), "cylinder": ("diameter", "height"),
                "file": ("width along the stroke", "depth", "height")}
OBJECT_SHAPES = tuple(OBJECT_SIZES)
FINGER_CLEARANCE_M = 0.0025  # smallest gap between an open pad and the object
MAX_WIDTH_M = STROKE_M - 2 * FINGER_CLEARANCE_M  # widest object the open fingers clear


def max_depth_m(width_m: float) -> float:
    """The deepest object [m] along the approach the hand takes at width_m [m] along the
    stroke. At the grasp the pads' centres close on the object's centre
    (control/scripted_grasp.grasp_frame_xy), so its near half lies between them and the palm:
    it must end FINGER_CLEARANCE_M short of the palm on either hand model, the prismatic
    pads' centres PAD_CENTER_Z from the mounting face, the linkage's 130.7 mm open and up to
    13.7 mm further as they close (robotiq/linkage.py), the palm at PALM_Z."""
    linkage_pad_z = float(linkage.PAD_CENTER_OPEN[1]) + linkage.pad_travel_at_opening(width_m)
    return 2 * (min(PAD_CENTER_Z, linkage_pad_z) - PALM_Z - FINGER_CLEARANCE_M)


# The smallest extent [m] the contact geometry resolves: a primitive's rigid mesh has 5 mm facets
# (simulation/object_model.py MESH_RESOLUTION_M), a pad's taxel is 20/3 x 24/4 mm
# (rig/taxel_layout.py); a smaller object touches one facet of one taxel, and at 0.1 mm Drake
# meets a non-finite pose.
MIN_SIZE_M = 0.005
# The lightest object [kg]: its weight, 0.1 N, is what a lift adds to the pads' load; the SA
# thresholds that tell the grasp's events apart are 0.3-1 N (controller contact_force_n), so a
# lighter object's lift is not felt. Near zero Drake's mass matrix is not positive-definite.
MIN_MASS_KG = 0.01
# An object's name names a folder (its events) and is part of file names (trial ids, logs):
# at most 64 characters, well under the 255-byte file-name limit with what is added to it (a
# sweep's trial record staged beside its target adds under 80).
OBJECT_NAME_PATTERN = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_-]{0,63}$")
OBJECT_NAME_WORDS = ("must be letters, digits, '_' or '-' (not first), at most 64 characters: "
                     "it names the folder of the object's events")
# An object's name as a public function's argument (Annotated[str, OBJECT_NAME]).
OBJECT_NAME = TextPattern(OBJECT_NAME_PATTERN, OBJECT_NAME_WORDS)
# The events folder's own subfolders (events/FORMAT.md): the ensemble's and the corrective
# events, and the prismatic hand's events. An object of one of these names would have its
# events written into them (and their index.json removed as a stale file of its own).
ENSEMBLE_EVENTS_FOLDER = "ensemble"
CORRECTIVE_EVENTS_FOLDER = "corrective"
PRISMATIC_HAND_EVENTS_FOLDER = "prismatic"
EVENTS_SUBFOLDERS = (ENSEMBLE_EVENTS_FOLDER, CORRECTIVE_EVENTS_FOLDER,
                     PRISMATIC_HAND_EVENTS_FOLDER)


def object_name_problem(name) -> str | None:
    """Why `name` cannot name an object (it names the folder of the object's events, and
    files of its trials), in words that follow "field 'object.name'"; None if it can."""
    if isinstance(name, str) and len(name) > 64:
        return f"must be at most 64 characters (it names a folder), got {len(name)}"
    if not isinstance(name, str) or not OBJECT_NAME_PATTERN.match(name):
        return f"{shorten(repr(name))} {OBJECT_NAME_WORDS}"
    if name in EVENTS_SUBFOLDERS:
        return (f"'{name}' is a folder of the events folder itself ({', '.join(EVENTS_SUBFOLDERS)}"
                "): give your object another name")
    return None


@public_dataclass
@dataclasses.dataclass
class ObjectConfig:
    """An object to grasp: with `shape` empty the built-in object `name` (None keeps its
    values); else your own "box", "cylinder" or "file" (a one-body SDF/URDF) with the sizes
    of OBJECT_SIZES [m], mass and friction, its events stored under `name`."""
    name: str = "box"
    shape: str = unset_when_empty("the built-in object named by 'name'")
    size: list[float] = unset_when_empty("the built-in object's sizes", bounded(
        default_factory=list, low=MIN_SIZE_M, high=0.5, unit="m",
        why="an object the 2F-85 lifts from the table: at least the contact meshes' 5 mm "
            "facets (a pad's taxel is 6-7 mm), at most 0.5 m in any extent"))
    mass: float | None = bounded(None, low=MIN_MASS_KG, high=5.0, unit="kg",
                                 why="lighter, its weight is under a third of the pads' "
                                     "smallest event threshold, 0.3 N; at most the 2F-85's "
                                     "rated payload, Robotiq 2F-85 manual")
    # Coulomb coefficient of the object's geometry (static = dynamic; module docstring)
    # Low end: with the pads' 4.42, Drake's pair 2 mu_pad mu / (mu_pad + mu) of 0.005 is 0.01,
    # wet ice; the slip recordings (recording/corrective_events.py) use 0.008 to make a box slip.
    friction: float | None = bounded(None, low=0.005, high=2.0,
                                     why="dry Coulomb coefficients of solids stay below about "
                                         "1.5, rubber on rubber; at least 0.005, a pad pair of "
                                         "0.01, wet ice")
    file: str = unset_when_empty("no model file (a built-in or primitive shape)")
    # [r, g, b, a] in [0, 1]; empty: the built-in object's colour, or DEFAULT_COLOR
    color: list[float] = unset_when_empty("the built-in object's colour, or the default", bounded(
        default_factory=list, low=0.0, high=1.0, why="RGBA components"))

    def width_along_stroke(self) -> float:
        """Extent along the finger stroke [m] (y of the object when placed on its marker)."""
        return self.size[0] if self.shape in ("cylinder", "file") else self.size[1]

    def depth_along_approach(self) -> float:
        """Extent along the approach [m] (x of the object when placed on its marker)."""
        return self.size[1] if self.shape == "file" else self.size[0]

    def height(self) -> float:
        return self.size[1] if self.shape == "cylinder" else self.size[2]


DEFAULT_COLOR = [0.9, 0.5, 0.1, 1.0]  # your own object's, unless it gives one

BUILTIN_OBJECTS = {
    "box": ObjectConfig(name="box", shape="box", size=[0.045, 0.045, 0.110], mass=0.15,
                        friction=materials.CARDBOARD, color=[0.85, 0.55, 0.2, 1.0]),
    "thick_cylinder": ObjectConfig(name="thick_cylinder", shape="cylinder",
                                   size=[0.050, 0.110], mass=0.20,
                                   friction=materials.PLASTIC,
                                   color=[0.2, 0.6, 0.3, 1.0]),
    "thin_cylinder": ObjectConfig(name="thin_cylinder", shape="cylinder", size=[0.025, 0.120],
                                  mass=0.06, friction=materials.PLASTIC,
                                  color=[0.3, 0.4, 0.85, 1.0]),
}


def object_problem(config: ObjectConfig, *, shapes=OBJECT_SHAPES) -> tuple[str, str] | None:
    """(field, what is wrong) of the first field of a user-defined object that cannot make
    one, in words that follow "field 'x'"; None when all can (a model file is not sought)."""
    problem = object_name_problem(config.name)
    if problem:
        return "name", problem
    if config.shape not in shapes:
        return "shape", f"names an unknown shape {config.shape!r} (known: {', '.join(shapes)})"
    sizes = OBJECT_SIZES[config.shape]
    for k, value in enumerate(config.size):  # finite before positive: NaN is said as such
        problem = number_problem(value)
        if problem is not None:
            return f"size[{k}]", problem
    if len(config.size) != len(sizes) or not all(_is_positive(v) for v in config.size):
        return "size", (f"must hold {len(sizes)} positive sizes [{', '.join(sizes)}] in "
                        f"metres for a {config.shape}, got {list(config.size)}")
    problem = object_fit_problem(config)
    if problem:
        return "size", problem
    for name, words in (("mass", "the object's mass [kg]"),
                        ("friction", "its Coulomb friction coefficient, e.g. 0.5 (a "
                                     "frictionless object cannot be held from the side)")):
        value = getattr(config, name)
        if value is None:
            return name, f"is missing: give {words}"
        problem = number_problem(value)
        if problem is not None:
            return name, problem
        if not _is_positive(value):
            return name, f"must be positive ({words}), got {value!r}"
    return None


def object_fit_problem(config: ObjectConfig, *, yaw_bound_deg: float = 0.0) -> str | None:
    """Why an object of valid sizes does not fit the open 2F-85 grasped at its centre, standing
    square or yawed up to yaw_bound_deg [deg] (a sweep's placement jitter): its width along the
    stroke within MAX_WIDTH_M, its near half FINGER_CLEARANCE_M short of the palm
    (max_depth_m); in words that follow "field 'size'". None if it fits. The jitter's shift
    off the marker is left out: it moves the object as a marker's misplacement does (which
    the controllers are there to meet), and widens and deepens nothing; a yaw turns a box's
    footprint, which does."""
    width, depth = jittered_extents(config, yaw_bound_deg)
    nominal_width = config.width_along_stroke()
    at = (f" yawed {yaw_bound_deg:g} deg (the placement jitter's far end)"
          if yaw_bound_deg > 0 else "")
    if width > MAX_WIDTH_M:
        return (f"makes the object {width * 1000:.1f} mm wide along the finger stroke{at}, "
                f"more than the {MAX_WIDTH_M * 1000:.1f} mm the 85 mm stroke leaves with "
                f"{FINGER_CLEARANCE_M * 1000:.1f} mm clearance per finger")
    deepest = min(max_depth_m(nominal_width), max_depth_m(width))
    if depth > deepest:
        return (f"makes the object {depth * 1000:.1f} mm deep along the approach{at}, more "
                f"than the {deepest * 1000:.1f} mm the 2F-85 takes at a "
                f"{nominal_width * 1000:.1f} mm width: grasped at its centre, its near half "
                f"must end {FINGER_CLEARANCE_M * 1000:.1f} mm short of the palm")
    return None


def jittered_extents(config: ObjectConfig, yaw_bound_deg: float) -> tuple[float, float]:
    """(width along the stroke, depth along the approach) [m] of the object's footprint at
    its widest, and at its deepest, for a yaw up to yaw_bound_deg [deg] either way: a
    cylinder's are its diameter; a rectangle w x d yawed by t spans w cos t + d sin t, which
    grows until t = atan(d / w)."""
    width, depth = config.width_along_stroke(), config.depth_along_approach()
    if config.shape == "cylinder" or yaw_bound_deg <= 0:
        return width, depth
    bound = math.radians(min(yaw_bound_deg, 90.0))

    def span(along: float, across: float) -> float:
        t = min(bound, math.atan2(across, along))
        return along * math.cos(t) + across * math.sin(t)
    return span(width, depth), span(depth, width)


DESCRIPTION_FIELDS = ("shape", "size", "mass", "friction", "file")


def object_description(config: ObjectConfig) -> dict:
    """What the physics sees of a resolved object: {shape, size, mass, friction, file} (memorized
    events carry it, so they are used only for the object they felt)."""
    return {"shape": config.shape, "size": [float(v) for v in config.size],
            "mass": float(config.mass), "friction": float(config.friction),
            "file": config.file}


def description_problem(description: dict) -> str | None:
    """What is wrong with an object description's values (object_description's form), in
    words naming the field, else None: its shape one of OBJECT_SHAPES with that shape's
    number of sizes, and size, mass and friction in ObjectConfig's declared ranges, as a
    scenario's object must be (an event felt on no object a scenario can hold is no
    recording's; a differing field that `event_object_may_differ` lets through must still
    be an object's)."""
    from tegrasp_drake.rig.ranges import field_range
    shape, size = description.get("shape"), description.get("size")
    if shape not in OBJECT_SHAPES:
        return (f"field 'object_description.shape' is {shorten(repr(shape))}; it must be one "
                f"of {', '.join(OBJECT_SHAPES)}")
    if not isinstance(size, (list, tuple)) or len(size) != len(OBJECT_SIZES[shape]):
        return (f"field 'object_description.size' must hold the {len(OBJECT_SIZES[shape])} "
                f"sizes of a {shape} ({', '.join(OBJECT_SIZES[shape])}) [m]")
    for name, values in (("size", size), ("mass", [description.get("mass")]),
                         ("friction", [description.get("friction")])):
        allowed = field_range(ObjectConfig, name)
        for k, value in enumerate(values):
            where = f"{name}[{k}]" if name == "size" else name
            problem = number_problem(value)
            if problem:
                return f"field 'object_description.{where}' {problem}"
            if not allowed.contains(real_number(value)):
                return (f"field 'object_description.{where}' is "
                        f"{number_text(real_number(value))}: it "
                        f"{allowed.words(real_number(value))}")
    return None


def description_differences(recorded: dict, current: dict, *, rtol: float = 1e-9,
                            labels: tuple[str, str] = ("recorded", "now")) -> list[str]:
    """The fields in which two object descriptions differ, in words naming both values and
    their `labels` ("mass 0.15 (recorded) != 0.12 (now)")."""
    differences = []
    for name in DESCRIPTION_FIELDS:
        a, b = recorded.get(name), current.get(name)
        if name in ("size", "mass", "friction") and a is not None and b is not None:
            a_list, b_list = (a, b) if name == "size" else ([a], [b])
            same = len(a_list) == len(b_list) and all(
                math.isclose(x, y, rel_tol=rtol, abs_tol=1e-12) for x, y in zip(a_list, b_list))
        else:
            same = a == b
        if not same:
            differences.append(f"{name} {a!r} ({labels[0]}) != {b!r} ({labels[1]})")
    return differences


def _is_positive(value) -> bool:
    """A finite number above zero (a NumPy scalar as the number it holds)."""
    return number_problem(value) is None and real_number(value) > 0
