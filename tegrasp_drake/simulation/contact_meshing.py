"""How finely the contact world is meshed: the scenario's `contact_geometry` section.
Each hydroelastic contact-surface face is one SAP constraint, so coarser meshes make a trial
cheaper. The defaults are the reference geometry; each coarser choice is opt-in and kept only
where validation_scenes.py's closed-form checks hold. `pad_refinement` meshes the pads finer
against friction creep (docs/model.md, "Friction creep"). Costs: docs/sweeps.md, "Coarser
contact geometry"."""

import dataclasses
from tegrasp_drake.modelgen.pad_mesh import PAD_REFINEMENTS
from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.rig.api_boundary import public_dataclass

BOX_TRIANGLES = (24, 12)
TABLE_SHAPES = ("box", "half_space")


@public_dataclass
@dataclasses.dataclass
class ContactGeometryConfig:
    """How finely the contact world is meshed; the defaults are the reference geometry."""
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
