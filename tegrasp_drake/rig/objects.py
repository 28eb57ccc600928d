"""The objects to grasp: the paper's three (Fig. 8a) and user-defined ones.

The paper does not give its objects' sizes; these are chosen to fit the 2F-85's 85 mm stroke
with the +-1.5 cm misplacement along the stroke and a finger clearance of 2.5 mm or more:
width along the stroke + 2 x 15 mm <= 85 mm - 2 x 2.5 mm. Masses are those of plastic or
cardboard objects of that size. Frame of an object O: origin at the centre of its base (the
face resting on the table), z up.

An object's `friction` is the coefficient of its own collision geometry, not of any pair:
Drake combines it with the other geometry's as 2 mu_A mu_B / (mu_A + mu_B)
(modelgen/materials.py). The built-in box is cardboard (0.448: pad 0.814, table 0.412),
the cylinders rigid plastic (0.374: pad 0.690, table 0.377). For a pair value P against the
pad, give the object P mu_pad / (2 mu_pad - P) with mu_pad = materials.PAD_COVER.
"""

import dataclasses
import math

from tegrasp_drake.modelgen import materials

# The entries of an object's `size` [m] for each shape.
OBJECT_SIZES = {"box": ("x", "y", "z"), "cylinder": ("diameter", "height"),
                "file": ("width along the stroke", "depth", "height")}
OBJECT_SHAPES = tuple(OBJECT_SIZES)


@dataclasses.dataclass
class ObjectConfig:
    """An object to grasp.

    Leave `shape` empty to take the built-in object called `name`. Otherwise:
    shape "box" with size [x, y, z] m; "cylinder" with size [diameter, height] m; or "file"
    with `file` an SDF/URDF path or package:// URL whose model has one body, and size
    [width along the stroke, depth, height] m for planning.
    """
    name: str = "box"
    shape: str = ""
    size: list[float] = dataclasses.field(default_factory=list)
    mass: float = 0.0  # kg
    # Coulomb coefficient of the object's geometry (static = dynamic), combined with the
    # pad's and the table's by Drake's pair rule (see the module docstring).
    friction: float = 0.0
    file: str = ""
    color: list[float] = dataclasses.field(default_factory=lambda: [0.9, 0.5, 0.1, 1.0])

    def width_along_stroke(self) -> float:
        """Extent along the finger stroke [m] (y of the object when placed on its marker)."""
        return self.size[0] if self.shape == "cylinder" else self.size[1]

    def height(self) -> float:
        return self.size[1] if self.shape == "cylinder" else self.size[2]


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


def object_problem(config: ObjectConfig, *, shapes=OBJECT_SHAPES,
                   friction_given: bool = True) -> tuple[str, str] | None:
    """The first field of a user-defined object (its shape given) that cannot make an
    object, and what is wrong, in words that follow "field 'x'"; None when all can.

    `shapes` narrows the shapes allowed; with `friction_given` False the friction is not
    checked (left for later). A model file is not looked for.
    """
    if config.shape not in shapes:
        return "shape", f"names an unknown shape {config.shape!r} (known: {', '.join(shapes)})"
    sizes = OBJECT_SIZES[config.shape]
    if len(config.size) != len(sizes) or not all(_is_positive(v) for v in config.size):
        return "size", (f"must hold {len(sizes)} positive sizes [{', '.join(sizes)}] in "
                        f"metres for a {config.shape}, got {list(config.size)}")
    if not _is_positive(config.mass):
        return "mass", f"must be positive [kg], got {config.mass!r}"
    if friction_given and not _is_positive(config.friction):
        return "friction", f"must be positive, got {config.friction!r}"
    return None


def _is_positive(value) -> bool:
    """A finite number above zero."""
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and 0.0 < value < math.inf)
