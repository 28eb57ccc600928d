"""Friction by material pair: the coefficient each geometry carries, and why.

Drake gives every collision geometry its own coefficients and combines the two of a contact
as mu = 2 mu_A mu_B / (mu_A + mu_B) (`CalcContactFrictionFromSurfaceProperties`), so a
geometry's value is not the friction of any pair. The discrete solvers (SAP, "lagged",
"similar") read only the combined *dynamic* coefficient, for sticking as well as sliding
(`GetCombinedDynamicCoulombFriction` in multibody/plant/contact_properties.h; measured too: a
pad mu_s 1.0 / mu_d 0.5 on an object mu_s 1.0 / mu_d 0.5 slipped at the grip the dynamic pair
predicts, not the static one). So every geometry gets one value, written as both mu_dynamic
and mu_static, and the value aims at the pair's *static* coefficient: holding, slipping and
tipping over are all decided at the onset of slip. Sliding friction is then about 20-25 %
too high.

Intended pair values (static / kinetic) are handbook ranges for these materials, reasoned
estimates rather than measurements: conductive fabric over a compliant elastomer on paper
or polymer 0.5-0.9; paper on wood 0.4-0.5; polymers on laminate or aluminium 0.3-0.4; paper
on paper 0.4-0.6; PP on PP 0.3-0.4. Materials: the pad cover is the paper's silver-plated
nylon conductive fabric over silicone elastomer; the box is cardboard; the cylinders are
rigid plastic (ABS/PP); the table top is melamine-faced wood; the finger and palm are
anodised aluminium.

Not every pair can be met. In reciprocals the rule is linear, 2 / mu_pair = 1/mu_A + 1/mu_B,
so two objects' pairs must differ by the same reciprocal step against every partner; the
intended values ask for 2/0.80 - 2/0.70 = -0.36 against the pad but -1.27 against the table.
The geometry values below are the weighted least-squares fit in reciprocals (weights:
pad-object 10, object-table 3, finger-object 1, object-object 0.3), rounded to 3 digits:
the grasp pairs (pad-object) land within 2 %, the others within about 10 % (the worst,
cardboard on cardboard, 10.4 % low). `MATERIAL_PAIRS` lists every pair with its intended
value; docs/model.md, "Friction by material pair", shows the table with the results.
"""

import dataclasses

import numpy as np

# Per-geometry coefficients (mu_dynamic = mu_static), from fit_geometry_friction() rounded.
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
