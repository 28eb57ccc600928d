"""How finely the contact world is meshed: the scenario's `contact_geometry` section.

Each hydroelastic contact-surface face is one SAP contact constraint and a share of
SceneGraph's surface query (docs/sweeps.md, "What a trial costs"), so coarser meshes make a
trial cheaper. The defaults are the reference geometry, the one every committed result
ran on; each coarser choice is opt-in, and kept only where the closed-form checks of the
contact world still hold (tests/simulation/test_validation_scenes.py).

- `box_triangles`: the surface mesh of a rigid primitive box object. 24 (Drake's Box: two
  triangles from each face's centre to each edge, 14 vertices, whatever the resolution
  hint) or 12 (the convex hull of its 8 corners: two triangles per face, the same solid).
  A flat face is flat either way; the pressure on a face is linear in both, so the force
  on a face pressed evenly is the same; only how a contact patch is cut into faces differs.
- `table`: the table top's compliant shape under the object. `box` (the reference: the
  1.2 x 1.0 x 0.05 m compliant box of models/table) or `half_space` (a compliant half-space
  at the table's top, z = 0, with the same modulus, dissipation, relaxation time and
  friction, and a slab thickness of half the box's thickness: Drake's box field rises from
  0 at the surface to the modulus at the box's mid-plane, 25 mm deep, as the slab's does
  at its thickness, so the top's stiffness per depth is the same). The box's tetrahedra are
  up to its full size; the half-space cuts the object's bottom triangles only along the
  surface. It passes the validation but gains nothing in contact (the free step is about
  20 % cheaper, the step in contact no cheaper: docs/sweeps.md).

- `pad_refinement`: the pads' compliant boxes as Drake meshes them (0, the reference: 44
  tetrahedra from the box's medial axis, whatever the resolution hint) or that mesh split 1
  or 2 times into eight (modelgen/pad_mesh.py: the same pressure field, value for value).
  This one is finer, not coarser: it multiplies the faces of the pads' contact surfaces by
  about 4 a level, which slows the regularised friction's creep of a pad held by friction
  alone and costs CPU time in contact in proportion (docs/model.md, "Friction creep"). The
  linkage hand only.

Cylinders keep their 5 mm facets (object_model.MESH_RESOLUTION_M: 16 round the 25 mm thin
cylinder, 32 round the 50 mm thick one): at 10 mm the thin cylinder is an octagon and
slips at 0.87 of the Coulomb grip force instead of 0.96, outside the validation's 10 %.
"""

import dataclasses
from tegrasp_drake.modelgen.pad_mesh import PAD_REFINEMENTS
from tegrasp_drake.rig.ranges import bounded

BOX_TRIANGLES = (24, 12)
TABLE_SHAPES = ("box", "half_space")


@dataclasses.dataclass
class ContactGeometryConfig:
    """How finely the contact world is meshed (module docstring); the defaults are the
    reference geometry."""
    # 24 (Drake's Box) or 12 (the convex hull of the corners)
    box_triangles: int = bounded(24, low=12, high=24, why="12 or 24")
    table: str = "box"  # "box" or "half_space"
    # 0 (Drake's mesh of the pad box), 1 or 2 (that mesh split as many times into eight)
    pad_refinement: int = bounded(0, low=min(PAD_REFINEMENTS), high=max(PAD_REFINEMENTS),
                                  why="Drake's medial-axis mesh of the pad, split up to twice")


def contact_geometry_problem(config: ContactGeometryConfig) -> tuple[str, str] | None:
    """The first field of `config` that is not a choice the contact world offers, and what
    is wrong, in words that follow "field 'contact_geometry.x'"; None when all are."""
    if config.box_triangles not in BOX_TRIANGLES:
        return "box_triangles", (f"must be 24 (Drake's box mesh) or 12 (its corners' convex "
                                 f"hull), got {config.box_triangles!r}")
    if config.table not in TABLE_SHAPES:
        return "table", (f"must be one of {', '.join(TABLE_SHAPES)} (the compliant table "
                         f"box, or a compliant half-space at its top), got {config.table!r}")
    return None
