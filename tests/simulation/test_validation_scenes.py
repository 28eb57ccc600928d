"""The station's contact world against closed-form mechanics.

Every scene is the station's own gripper, table and materials with the scenario's default
plant settings (simulation/validation_scenes.py); thresholds come from the closed forms
below and the margins stated with them, not from the simulation's numbers.

Tipping or sliding. One pad pushes a standing cylinder (radius r) sideways at height h on a
table with pair friction mu_t. With a frictionless pad it tips over before it slides when
h > r / mu_t (moments about the far edge of its base at the onset of sliding). The pad's own
friction mu_p resists the tipping (the contact point rises along the pad) and presses the
object onto the table, which moves the boundary up to h = r (1 / mu_t + mu_p) when that
friction is fully engaged; the true boundary lies between the two. The pad's contact line
spans h +- PAD_WIDTH / 2, and once the cylinder leans the force acts at the line's lower end,
so the cases below keep the whole line clear of the band with 20 % margins: it slides when
h + w/2 < 0.8 r / mu_t and tips when h - w/2 > 1.2 r (1 / mu_t + mu_p). (Measured in this
scene: the thin cylinder slides at h = 35 mm and tips at 40 mm; bounds 33.2 and 41.8 mm.)

Slip. An upright object of mass m held by two pads with grip force F each slides down when
2 mu F < m g: it starts to fall at F = m g / (2 mu), mu the pad-object pair. The drop is
detected at 1 mm/s while the grip falls at 2.5 N/s, which makes the detected force a few
per cent low (measured 0.958 of the prediction).

No creep. An object held still, below the friction limits, must stay still. Gravity twists a
tilted, off-centre held cylinder in the pads' plane; under Drake's default stiction tolerance
(1e-4 m/s) the regularised friction let it turn steadily.

Each check runs on the reference geometry and on every coarser contact geometry a scenario
can select that changes its scene (simulation/contact_meshing.py): the table as a
half-space under the cylinder; the box as 12 triangles, with the closed forms above for the
box (half-width 22.5 mm, its own pair friction).
"""

import dataclasses

import pytest

from tegrasp_drake.scenario.scenario import Scenario
from tegrasp_drake.rig import materials
from tegrasp_drake.rig.tactile_fingertip import PAD_WIDTH
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig
from tegrasp_drake.simulation.validation_scenes import (GRAVITY, held_tilt_rate,
                                                        push_standing_object,
                                                        slip_onset_grip_force)

PLANT_CONFIG = Scenario().plant_config  # the scenario's default: what every trial runs on
THIN_CYLINDER = BUILTIN_OBJECTS["thin_cylinder"]
RADIUS = THIN_CYLINDER.width_along_stroke() / 2
MU_TABLE = materials.pair_friction(THIN_CYLINDER.friction, materials.TABLE_TOP)
MU_PAD = materials.pair_friction(THIN_CYLINDER.friction, materials.PAD_COVER)
TIPS_WITHOUT_PAD_FRICTION = RADIUS / MU_TABLE  # 33.2 mm
TIPS_WITH_PAD_FRICTION = RADIUS * (1.0 / MU_TABLE + MU_PAD)  # 41.8 mm

UPRIGHT_DEG = 2.0  # a cylinder that slid stays within this of vertical (measured 0.03)
TIPPED_DEG = 10.0  # one that tipped over leans past this within the push (measured 28)

# The contact geometries a scenario can select that change the cylinder's scenes, and the
# box's (the box setting leaves a cylinder as it is; the table appears in the push only).
CYLINDER_GEOMETRIES = pytest.mark.parametrize("geometry", [
    ContactGeometryConfig(), ContactGeometryConfig(table="half_space")],
    ids=["reference", "table_half_space"])
BOX_GEOMETRIES = pytest.mark.parametrize("geometry", [
    ContactGeometryConfig(), ContactGeometryConfig(box_triangles=12),
    ContactGeometryConfig(box_triangles=12, table="half_space")],
    ids=["reference", "box_12_triangles", "box_12_triangles_half_space"])
BOX = BUILTIN_OBJECTS["box"]
BOX_TIPS_WITHOUT_PAD_FRICTION = (BOX.width_along_stroke() / 2
                                 / materials.pair_friction(BOX.friction, materials.TABLE_TOP))
BOX_MU_PAD = materials.pair_friction(BOX.friction, materials.PAD_COVER)


# Each object under each contact geometry that changes its push scene, with the height at
# which it tips over when the pad's friction is left out (the cylinder 33.2, the box 54.6 mm).
PUSHED_LOW = pytest.mark.parametrize("obj, tips_without_pad_friction, geometry", [
    *[(THIN_CYLINDER, TIPS_WITHOUT_PAD_FRICTION, g) for g in CYLINDER_GEOMETRIES.args[1]],
    *[(BOX, BOX_TIPS_WITHOUT_PAD_FRICTION, g) for g in BOX_GEOMETRIES.args[1]]],
    ids=[f"cylinder-{i}" for i in CYLINDER_GEOMETRIES.kwargs["ids"]]
        + [f"box-{i}" for i in BOX_GEOMETRIES.kwargs["ids"]])


@PUSHED_LOW
def test_an_object_pushed_low_slides_upright(obj, tips_without_pad_friction, geometry):
    height = 0.015  # m, pad centre above the table
    assert height + PAD_WIDTH / 2 < 0.8 * tips_without_pad_friction
    result = push_standing_object(obj, push_height=height, plant_config=PLANT_CONFIG,
                                  contact_geometry=geometry)
    assert result.tilt_deg < UPRIGHT_DEG
    assert result.slide_m > 0.015  # of the pad's 20 mm push


@CYLINDER_GEOMETRIES
def test_a_cylinder_pushed_high_tips_over(geometry):
    height = 0.062  # m
    assert height - PAD_WIDTH / 2 > 1.2 * TIPS_WITH_PAD_FRICTION
    result = push_standing_object(THIN_CYLINDER, push_height=height, plant_config=PLANT_CONFIG,
                                  contact_geometry=geometry)
    assert result.tilt_deg > TIPPED_DEG


def test_a_held_object_slips_at_the_coulomb_grip_force():
    # No table in this scene: the cylinder's only geometry setting-free check.
    heavy = dataclasses.replace(THIN_CYLINDER, mass=0.5)  # kg; slips at a grip of 3.6 N
    predicted = heavy.mass * GRAVITY / (2.0 * MU_PAD)
    result = slip_onset_grip_force(heavy, plant_config=PLANT_CONFIG,
                                   initial_force=2.0 * predicted)
    assert result.onset_force_n is not None, "the object never slipped"
    assert 0.9 <= result.onset_force_n / predicted <= 1.1


def test_a_tilted_object_held_below_the_friction_limit_does_not_creep():
    # The thin cylinder tilted 30 deg in the pads' plane, its centre of mass 45 mm from the
    # pads' centre along its axis, gripped with 10 N: gravity's twist m g d sin(30 deg) =
    # 0.013 N m is 17 % of the pads' torsional friction 2 mu F L / 4 (L = 23 mm, the contact
    # line across the 20 mm pad at 30 deg). With Drake's default stiction tolerance 1e-4 m/s
    # this scene turned at 0.127 deg/s; with the scenario's 1e-6 at 0.017 deg/s.
    rate = held_tilt_rate(THIN_CYLINDER, tilt_deg=30.0, com_offset=0.045, grip_force=10.0,
                          plant_config=PLANT_CONFIG)
    assert abs(rate) < 0.05  # deg/s



@BOX_GEOMETRIES
def test_a_held_box_slips_at_the_coulomb_grip_force(geometry):
    heavy = dataclasses.replace(BOX, mass=0.8)  # kg; slips at a grip of 4.8 N
    predicted = heavy.mass * GRAVITY / (2.0 * BOX_MU_PAD)
    result = slip_onset_grip_force(heavy, plant_config=PLANT_CONFIG,
                                   initial_force=2.0 * predicted, contact_geometry=geometry)
    assert result.onset_force_n is not None, "the box never slipped"
    assert 0.9 <= result.onset_force_n / predicted <= 1.1
