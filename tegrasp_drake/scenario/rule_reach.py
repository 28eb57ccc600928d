"""Which taxel_aware rules one finger alone can fire in a scenario's world: the largest push
one pad presses an upright free-standing object with before it tips or slides
(contact_geometry.one_pad_push, at the scenario's pad-centre height on its table) against the
pad's contact thresholds in force (control/noise_thresholds.py). `python -m
tegrasp_drake.scenario.rule_reach --check|--write docs/controller.md` compares or replaces the
table between `<!-- one-pad reach -->` and `<!-- end of one-pad reach -->` (docs/controller.md,
"Which rules one finger can fire")."""

import dataclasses
import sys

from pydrake.multibody.tree import UniformGravityFieldElement

from tegrasp_drake.control.taxel_aware.contact_geometry import OnePadPush, one_pad_push
from tegrasp_drake.modelgen import table_sdf
from tegrasp_drake.rig.generated_table import GeneratedTable
from tegrasp_drake.rig.materials import pair_friction
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS, ObjectConfig
from tegrasp_drake.scenario.scenario import LoadScenario, controller_in_force

GRAVITY_MPS2 = UniformGravityFieldElement.kDefaultStrength  # the plant's, Drake's default

# The heaviest object of the development grids: analysis/example_sweep.yaml's mug (masses
# up to 0.3 kg, object friction 0.3-0.8 across the grids), and its heaviest draw (mass x 1.1,
# the sweeps' mass_scale_bound).
HEAVIEST_GRID_OBJECT = ObjectConfig(name="mug", shape="cylinder", size=[0.040, 0.100],
                                    mass=0.30, friction=0.8)
MASS_SCALE_BOUND = 0.10

# What each rule needs one pad alone to press, by the count it reads: "taxel" a taxel above
# taxel_contact_n at the close's first touch (ContactEstimator), "pad" one pad's SA sum above
# contact_force_n while the other's is not (obs.contact); None: not one pad's push, with why.
RULE_COUNTS = {
    "one_sided": ("pad", "one pad's sum, the other's not, for re_reach.one_sided_contact_s"),
    "approach_contact": ("pad", "a pad's sum in the approach (the open fingers: one pad)"),
    "one_sided_at_width": ("pad", "one pad's sum alone, closed to the width"),
    "bracket_recentre": ("pad", "one pad's sum alone, the other's face remembered"),
    "beyond_pads": ("taxel", "the first touch on one pad's distal row alone"),
    "tipping_guard": ("taxel", "the first touch on one pad, the other still to close"),
    "off_centre": (None, "both pads at the Reach-Load event: the grip squeezes"),
    "reach_timeout_both_pads": (None, "both pads' sums: the grip squeezes"),
    "load_timeout_both_pads": (None, "both pads' sums: the grip squeezes"),
    "held_tilted": (None, "held in Hold: the grip squeezes"),
    "regrasp_after_place": (None, "after held_tilted"),
    "regrasp_set_down": (None, "holds back the Unload after held_tilted: lets nothing go"),
    "place_set_down": (None, "holds back the Unload of a held object: lets nothing go"),
    "grip_settling": (None, "both pads' sums: the grip squeezes"),
    "touch_unconfirmed": (None, "holds back while no pad's sum reads: nothing to press"),
    "touch_confirmed": (None, "a pad's sum just after the Reach-Load event: the close squeezes"),
    "caged": (None, "a first touch on the palm side, by one pad or both at once; both squeeze"),
    "reach_timeout_caged": (None, "after caged"),
    "load_timeout_caged": (None, "after caged"),
    "finger_strike": (None, "the wrist force of a finger's front or (linkage) its film's RA "
                      "onset, an impact: not quasi-static"),
    "closed_untouched": (None, "no taxel's touch in the close: fires on what no pad pressed"),
    "ra_onset_one_film": (None, "one film's RA onset, an impact the SA need not see"),
    "curled_fingertips": (None, "the fingertips curled past the object: both close on it"),
}


@dataclasses.dataclass(frozen=True)
class ObjectReach:
    """An object's one-pad push (OnePadPush [N]) and the masses [kg] at which its limit would
    reach the taxel and pad-sum counts (the same shape, friction and contact height)."""
    name: str
    mass_kg: float
    width_m: float
    table_friction: float
    push: OnePadPush
    mass_for_taxel_kg: float
    mass_for_pad_kg: float


@dataclasses.dataclass(frozen=True)
class RuleReach:
    """The scenario's counts [N] and each object's ObjectReach."""
    taxel_contact_n: float
    contact_force_n: float
    contact_height_m: float
    objects: tuple

    def reaches(self, count: str) -> tuple:
        """The names of the objects whose one-pad limit exceeds the count ("taxel" or "pad")."""
        threshold = self.taxel_contact_n if count == "taxel" else self.contact_force_n
        return tuple(o.name for o in self.objects if o.push.limit_n > threshold)


def _object_reach(obj: ObjectConfig, *, contact_height_m: float, taxel_n: float,
                  pad_n: float, name: str) -> ObjectReach:
    mu = pair_friction(obj.friction, table_sdf.FRICTION)
    weight = obj.mass * GRAVITY_MPS2
    push = one_pad_push(weight_n=weight, object_width_m=obj.width_along_stroke(),
                        contact_height_m=contact_height_m, table_friction=mu)
    per_kg = push.limit_n / obj.mass  # both limits grow with the mass
    return ObjectReach(name=name, mass_kg=obj.mass, width_m=obj.width_along_stroke(),
                       table_friction=mu, push=push, mass_for_taxel_kg=taxel_n / per_kg,
                       mass_for_pad_kg=pad_n / per_kg)


def grid_objects() -> tuple:
    """(name, ObjectConfig): the built-in objects, the development grids' heaviest object and
    its heaviest draw."""
    heaviest = HEAVIEST_GRID_OBJECT
    drawn = dataclasses.replace(heaviest, mass=heaviest.mass * (1.0 + MASS_SCALE_BOUND))
    return (*BUILTIN_OBJECTS.items(), (heaviest.name, heaviest),
            (f"{heaviest.name}, mass x {1.0 + MASS_SCALE_BOUND:g}", drawn))


def rule_reach(scenario=None, objects=None) -> RuleReach:
    """RuleReach of `scenario` (default: the default world run by taxel_aware) for `objects`
    ((name, ObjectConfig) pairs, default grid_objects()): the contact height is the pad
    centre's, grasp.grasp_height [m above the table]; the counts those in force."""
    scenario = scenario or LoadScenario(controller="taxel_aware")
    config = controller_in_force(scenario)
    height = scenario.grasp.grasp_height
    return RuleReach(
        taxel_contact_n=config.taxel_contact_n, contact_force_n=config.contact_force_n,
        contact_height_m=height,
        objects=tuple(_object_reach(obj, contact_height_m=height, name=name,
                                    taxel_n=config.taxel_contact_n,
                                    pad_n=config.contact_force_n)
                      for name, obj in (objects or grid_objects())))


def reach_markdown(reach: RuleReach | None = None) -> str:
    """The docs' two tables: each object's one-pad limit; each rule's count and the objects
    that reach it."""
    reach = reach or rule_reach()
    lines = [f"Pad centre {1000 * reach.contact_height_m:.0f} mm above the table; a taxel "
             f"counts above {reach.taxel_contact_n:.2f} N, a pad above "
             f"{reach.contact_force_n:.2f} N.", "",
             "| object | mass | width | table friction | tips at | slides at | one pad presses "
             "at most | mass to reach a taxel | mass to reach a pad |",
             "|---|---|---|---|---|---|---|---|---|"]
    for o in reach.objects:
        lines.append(f"| {o.name} | {o.mass_kg:.3g} kg | {1000 * o.width_m:.0f} mm | "
                     f"{o.table_friction:.2f} | {o.push.tips_n:.2f} N | {o.push.slides_n:.2f} N | "
                     f"{o.push.limit_n:.2f} N | {o.mass_for_taxel_kg:.2f} kg | "
                     f"{o.mass_for_pad_kg:.2f} kg |")
    lines += ["", "| rule | one pad must press | count | objects that reach it |",
              "|---|---|---|---|"]
    for rule, (count, why) in RULE_COUNTS.items():
        if count is None:
            lines.append(f"| `{rule}` | {why} | - | not bounded by one pad's push |")
            continue
        threshold = reach.taxel_contact_n if count == "taxel" else reach.contact_force_n
        names = ", ".join(reach.reaches(count)) or "none"
        lines.append(f"| `{rule}` | {why} | {count} > {threshold:.2f} N | {names} |")
    return "\n".join(lines) + "\n"


REACH_TABLE = GeneratedTable(name="the one-pad reach section", marker="one-pad reach",
                             markdown=lambda: reach_markdown())
documented_table = REACH_TABLE.documented


def main(argv=None) -> int:
    """`--check PAGE` or `--write PAGE` (GeneratedTable.main)."""
    return REACH_TABLE.main(argv, description=__doc__.split("\n\n")[0])


if __name__ == "__main__":
    sys.exit(main())
