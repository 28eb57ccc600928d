"""Friction by material pair: the coefficient each geometry carries, and why
(docs/model.md, "Friction by material pair").

Drake combines two geometries' coefficients as mu = 2 mu_A mu_B / (mu_A + mu_B), and its
discrete solvers use only the combined dynamic one, for sticking too. So each geometry gets
one value (as mu_dynamic and mu_static), fitted by weighted least squares in reciprocals so
that the pairs meet their intended *static* coefficients (handbook ranges, MATERIAL_PAIRS):
holding, slipping and tipping are decided at the onset of slip.
"""

import dataclasses

import numpy as np

# Per-geometry coefficients (mu_dynamic = mu_static): fit_geometry_friction() to 3 digits.
PAD_COVER = 4.42  # not a physical coefficient: the pad's share of its pairs (0.69-0.81)
CARDBOARD = 0.448  # the built-in box
PLASTIC = 0.374  # the built-in cylinders
TABLE_TOP = 0.381
ALUMINIUM = 0.381  # the finger behind the pad, and the palm
GEOMETRY_FRICTION = {"pad cover": PAD_COVER, "cardboard": CARDBOARD, "plastic": PLASTIC,
                     "table": TABLE_TOP, "aluminium": ALUMINIUM}


def pair_friction(mu_a: float, mu_b: float) -> float:
    """The coefficient Drake uses for a contact of two geometries with mu_a and mu_b."""
    return 2.0 * mu_a * mu_b / (mu_a + mu_b)


@dataclasses.dataclass(frozen=True)
class MaterialPair:
    """One contact pair of materials, its intended friction and its weight in the fit."""
    a: str
    b: str
    intended_static: float
    intended_kinetic: float
    weight: float

    def combined(self, friction=GEOMETRY_FRICTION) -> float:
        """The pair's coefficient in the simulation (the geometries' values combined)."""
        return pair_friction(friction[self.a], friction[self.b])


GRASP_WEIGHT = 10.0  # pad-object pairs: the grasp's own friction, met within 2 %
MATERIAL_PAIRS = (
    MaterialPair("pad cover", "cardboard", 0.80, 0.60, GRASP_WEIGHT),
    MaterialPair("pad cover", "plastic", 0.70, 0.50, GRASP_WEIGHT),
    MaterialPair("cardboard", "table", 0.45, 0.35, 3.0),
    MaterialPair("plastic", "table", 0.35, 0.30, 3.0),
    MaterialPair("aluminium", "cardboard", 0.45, 0.35, 1.0),
    MaterialPair("aluminium", "plastic", 0.35, 0.30, 1.0),
    MaterialPair("cardboard", "cardboard", 0.50, 0.40, 0.3),
    MaterialPair("plastic", "plastic", 0.35, 0.30, 0.3),
    MaterialPair("cardboard", "plastic", 0.40, 0.32, 0.3),
)


def fit_geometry_friction(pairs=MATERIAL_PAIRS) -> dict:
    """Per-geometry coefficients whose combined pairs best meet the intended static values:
    weighted least squares on 2 / mu_pair = 1/mu_a + 1/mu_b (linear in the reciprocals)."""
    names = sorted({name for pair in pairs for name in (pair.a, pair.b)})
    design = np.zeros((len(pairs), len(names)))
    for row, pair in enumerate(pairs):
        design[row, names.index(pair.a)] += 1.0
        design[row, names.index(pair.b)] += 1.0
    weights = np.array([pair.weight for pair in pairs])
    target = np.array([2.0 / pair.intended_static for pair in pairs])
    reciprocals, *_ = np.linalg.lstsq(design * weights[:, None], target * weights, rcond=None)
    return dict(zip(names, 1.0 / reciprocals))
