import pytest
from pydrake.multibody.plant import CalcContactFrictionFromSurfaceProperties, CoulombFriction

from tegrasp_drake.rig import materials


def test_geometry_coefficients_are_the_rounded_fit_of_the_intended_pairs():
    fitted = materials.fit_geometry_friction()
    assert set(fitted) == set(materials.GEOMETRY_FRICTION)
    for name, value in materials.GEOMETRY_FRICTION.items():
        assert value == pytest.approx(fitted[name], rel=2e-3), name  # 3 significant digits


def test_pad_object_pairs_meet_their_intended_friction_within_2_percent():
    grasp_pairs = [p for p in materials.MATERIAL_PAIRS if p.weight == materials.GRASP_WEIGHT]
    assert {p.b for p in grasp_pairs} == {"cardboard", "plastic"}
    for pair in grasp_pairs:
        assert pair.combined() == pytest.approx(pair.intended_static, rel=0.02), pair


def test_pair_friction_is_the_value_drake_combines():
    for pair in materials.MATERIAL_PAIRS:
        a = materials.GEOMETRY_FRICTION[pair.a]
        b = materials.GEOMETRY_FRICTION[pair.b]
        drake = CalcContactFrictionFromSurfaceProperties(CoulombFriction(a, a),
                                                         CoulombFriction(b, b))
        assert pair.combined() == pytest.approx(drake.dynamic_friction()), pair
