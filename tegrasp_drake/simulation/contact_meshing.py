"""How finely the contact world is meshed: the scenario's `contact_geometry` section.
Each hydroelastic contact-surface face is one SAP constraint, so coarser meshes make a trial
cheaper. The object and table defaults are the reference geometry; each coarser choice is
opt-in and kept only where validation_scenes.py's closed-form checks hold. The linkage pads
are meshed finer by default, against SAP's friction creep (docs/model.md, "Friction creep").
Costs: docs/sweeps.md, "Coarser contact geometry".
"""

import dataclasses
from tegrasp_drake.modelgen.pad_mesh import PAD_REFINEMENTS
from tegrasp_drake.rig.ranges import bounded, chosen
from tegrasp_drake.rig.api_boundary import public_dataclass

BOX_TRIANGLES = (24, 12)
TABLE_SHAPES = ("box", "half_space")


@public_dataclass
@dataclasses.dataclass
class ContactGeometryConfig:
    """How finely the contact world is meshed; the defaults are the reference geometry."""
    # 24 (Drake's Box) or 12 (the convex hull of the corners)
    box_triangles: int = chosen(24, names=BOX_TRIANGLES, why="Drake's box mesh, or its "
                                                           "corners' convex hull")
    table: str = chosen("box", names=TABLE_SHAPES, why="the compliant table box, or a "
                                                       "compliant half-space at its top")
    # 0 (Drake's mesh of the pad box), 1 or 2 (that mesh split as many times into eight);
    # None: by the hand and the object (pad_refinement_for)
    pad_refinement: int | None = bounded(None, low=min(PAD_REFINEMENTS),
                                         high=max(PAD_REFINEMENTS),
                                         why="Drake's medial-axis mesh of the pad, split up "
                                             "to twice")


# The linkage pads' refinement by the object's shape when the scenario leaves it unset: the
# coarsest at which the paper grid's Holds showed no friction creep (the paper's 9 markers,
# development seed 600; docs/model.md, "Friction creep"). A box's flat face loads the pads far
# inside their friction cone and holds at one split (about 390 faces a pad in Hold); a
# cylinder's line can leave both fingers off their pins, held by friction near the cone, and
# needs two (about 700 faces a pad). A mesh from a file is taken as curved.
PAD_REFINEMENT_BY_SHAPE = {"box": 1, "cylinder": 2, "file": 2}


def pad_refinement_for(config: ContactGeometryConfig, hand_model: str,
                       object_shape: str) -> int:
    """The pads' refinement: the scenario's if set, else 0 on the prismatic hand and the
    object shape's level (PAD_REFINEMENT_BY_SHAPE) on the linkage hand."""
    if config.pad_refinement is not None:
        return config.pad_refinement
    return PAD_REFINEMENT_BY_SHAPE[object_shape] if hand_model == "linkage" else 0

