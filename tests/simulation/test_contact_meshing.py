"""The scenario's contact geometry (simulation/contact_meshing.py): each setting changes the
meshes SceneGraph holds for contact, keeps the materials, and bad values are refused.
Whether the contact world still matches closed-form mechanics with them is in
simulation/test_validation_scenes.py."""


import numpy as np
import pytest
from pydrake.geometry import Box, Convex, HalfSpace, Mesh
from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, object_pose
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig, pad_refinement_for
from tegrasp_drake.simulation.object_model import object_body
from tegrasp_drake.simulation.station import AddStationPlant, pad_geometries
from tegrasp_drake.simulation.table_model import HALF_SPACE_SLAB_THICKNESS_M


def _station_plant(scenario):
    return AddStationPlant(DiagramBuilder(), plant_config=scenario.plant_config,
                           arm=scenario.arm, gripper=scenario.gripper, object=scenario.object,
                           X_WO=object_pose(scenario),
                           pad_modulus_pa=scenario.tactile.pad_modulus_pa,
                           random_seed=scenario.random_seed,
                           contact_geometry=scenario.contact_geometry)


def _object_geometry(parts):
    (geometry,) = parts.plant.GetCollisionGeometriesForBody(
        object_body(parts.plant, parts.object_instance))
    return geometry


def _table_geometry(parts):
    table = parts.plant.GetModelInstanceByName("table")
    (geometry,) = parts.plant.GetCollisionGeometriesForBody(
        parts.plant.GetBodyByName("top", table))
    return geometry


def _material(properties) -> tuple:
    friction = properties.GetProperty("material", "coulomb_friction")
    return (friction.static_friction(), friction.dynamic_friction(),
            properties.GetPropertyOrDefault("material", "hunt_crossley_dissipation", None),
            properties.GetPropertyOrDefault("material", "relaxation_time", None))


@pytest.fixture(scope="module")
def reference():
    return _station_plant(LoadScenario(name="box"))


@pytest.fixture(scope="module")
def coarse():
    return _station_plant(LoadScenario(name="box", overrides=[
        "contact_geometry.box_triangles=12", "contact_geometry.table=half_space"]))


def test_the_reference_box_is_drakes_24_triangle_box(reference):
    inspector = reference.scene_graph.model_inspector()
    geometry = _object_geometry(reference)
    assert isinstance(inspector.GetShape(geometry), Box)
    mesh = inspector.maybe_get_hydroelastic_mesh(geometry)
    assert (mesh.num_triangles(), mesh.num_vertices()) == (24, 14)


def test_twelve_box_triangles_are_the_corners_convex_hull(coarse):
    inspector = coarse.scene_graph.model_inspector()
    geometry = _object_geometry(coarse)
    assert isinstance(inspector.GetShape(geometry), Convex)
    mesh = inspector.maybe_get_hydroelastic_mesh(geometry)
    assert (mesh.num_triangles(), mesh.num_vertices()) == (12, 8)
    # The same solid: the corners of the 45 x 45 x 110 mm box on its base, in the body frame.
    X_BG = inspector.GetPoseInFrame(geometry)
    p_BV = np.array([X_BG.multiply(mesh.vertex(v)) for v in range(mesh.num_vertices())])
    np.testing.assert_allclose(p_BV.min(axis=0), [-0.0225, -0.0225, 0.0], atol=1e-12)
    np.testing.assert_allclose(p_BV.max(axis=0), [0.0225, 0.0225, 0.110], atol=1e-12)


def test_the_corner_hull_keeps_the_boxs_contact_material(reference, coarse):
    properties = [parts.scene_graph.model_inspector().GetProximityProperties(
        _object_geometry(parts)) for parts in (reference, coarse)]
    assert _material(properties[0]) == _material(properties[1])
    assert all(p.HasProperty("hydroelastic", "compliance_type") for p in properties)
    assert not any(p.HasProperty("hydroelastic", "hydroelastic_modulus") for p in properties)


def test_the_half_space_table_is_the_box_tables_material_as_deep(reference, coarse):
    inspectors = [parts.scene_graph.model_inspector() for parts in (reference, coarse)]
    geometries = [_table_geometry(parts) for parts in (reference, coarse)]
    assert isinstance(inspectors[0].GetShape(geometries[0]), Box)
    assert isinstance(inspectors[1].GetShape(geometries[1]), HalfSpace)
    box, half_space = (i.GetProximityProperties(g) for i, g in zip(inspectors, geometries))
    assert _material(box) == _material(half_space)
    assert (box.GetProperty("hydroelastic", "hydroelastic_modulus")
            == half_space.GetProperty("hydroelastic", "hydroelastic_modulus"))
    # Drake's box field reaches the modulus at the mid-plane, half the 50 mm top deep.
    assert HALF_SPACE_SLAB_THICKNESS_M == inspectors[0].GetShape(geometries[0]).height() / 2
    assert half_space.GetProperty("hydroelastic", "slab_thickness") == HALF_SPACE_SLAB_THICKNESS_M


def test_a_cylinder_is_meshed_the_same_whatever_the_box_setting():
    meshes = []
    for triangles in (24, 12):
        parts = _station_plant(LoadScenario(name="thin_cylinder", overrides=[
            f"contact_geometry.box_triangles={triangles}"]))
        mesh = parts.scene_graph.model_inspector().maybe_get_hydroelastic_mesh(
            _object_geometry(parts))
        meshes.append((mesh.num_triangles(), mesh.num_vertices()))
    assert meshes[0] == meshes[1] == (64, 34)  # 16 facets round, 5 mm


@pytest.mark.parametrize("refinement, shape, tetrahedra",
                         [(0, Box, 44), (1, Mesh, 44 * 8), (2, Mesh, 44 * 64)])
def test_the_pads_are_drakes_box_mesh_or_that_mesh_split(reference, refinement, shape,
                                                          tetrahedra):
    parts = _station_plant(LoadScenario(name="box", overrides=[
        f"contact_geometry.pad_refinement={refinement}"]))
    inspector = parts.scene_graph.model_inspector()
    reference_pads = pad_geometries(reference.plant, reference.scene_graph, reference.gripper)
    for finger, pad in pad_geometries(parts.plant, parts.scene_graph, parts.gripper).items():
        assert isinstance(inspector.GetShape(pad.geometry_id), shape)
        assert inspector.maybe_get_hydroelastic_mesh(pad.geometry_id).num_elements() == tetrahedra
        properties = inspector.GetProximityProperties(pad.geometry_id)
        reference_properties = reference.scene_graph.model_inspector().GetProximityProperties(
            reference_pads[finger].geometry_id)
        assert _material(properties) == _material(reference_properties)
        assert (properties.GetProperty("hydroelastic", "hydroelastic_modulus")
                == reference_properties.GetProperty("hydroelastic", "hydroelastic_modulus"))
        # The same place on the finger: only the collision shape differs.
        assert inspector.GetPoseInFrame(pad.geometry_id).IsExactlyEqualTo(
            reference.scene_graph.model_inspector().GetPoseInFrame(
                reference_pads[finger].geometry_id))


@pytest.mark.parametrize("name, model, tetrahedra", [
    ("box", "linkage", 44 * 8), ("thick_cylinder", "linkage", 44 * 64),
    ("thin_cylinder", "linkage", 44 * 64), ("box", "prismatic", None)])
def test_unset_the_pads_are_split_by_the_objects_shape(name, model, tetrahedra):
    scenario = LoadScenario(name=name, overrides=[f"gripper.model={model}"])
    assert scenario.contact_geometry.pad_refinement is None
    assert scenario.plant_config.contact_surface_representation == "triangle"
    parts = _station_plant(scenario)
    inspector = parts.scene_graph.model_inspector()
    pads = pad_geometries(parts.plant, parts.scene_graph, parts.gripper).values()
    for pad in pads:
        mesh = inspector.maybe_get_hydroelastic_mesh(pad.geometry_id)
        if tetrahedra is None:  # the prismatic hand's pads: Drake's own box
            assert isinstance(inspector.GetShape(pad.geometry_id), Box)
        else:
            assert mesh.num_elements() == tetrahedra


def test_a_set_refinement_wins_over_the_shapes():
    assert pad_refinement_for(ContactGeometryConfig(pad_refinement=0), "linkage", "cylinder") == 0
    assert pad_refinement_for(ContactGeometryConfig(pad_refinement=2), "linkage", "box") == 2
    assert pad_refinement_for(ContactGeometryConfig(), "prismatic", "cylinder") == 0


def test_the_refined_pads_are_the_linkage_hands_only():
    with pytest.raises(ConfigError) as error:
        LoadScenario(overrides=["gripper.model=prismatic", "contact_geometry.pad_refinement=1"])
    assert "'contact_geometry.pad_refinement'" in str(error.value)
    assert "\n" not in str(error.value)


def test_no_preset_meshes_coarser_than_the_reference_the_sweep_grade_one_included():
    # The 12-triangle box lost a judged marker (docs/sweeps.md): it stays a setting only.
    reference = ContactGeometryConfig(box_triangles=24, table="box")
    assert LoadScenario().contact_geometry == reference
    scenario = LoadScenario(name="sweep_grade")
    assert scenario.contact_geometry == reference
    assert scenario.vibration.pad_force_source == "joint_forces"


@pytest.mark.parametrize("assignment, field", [
    ("contact_geometry.box_triangles=6", "contact_geometry.box_triangles"),
    ("contact_geometry.table=plane", "contact_geometry.table"),
    ("contact_geometry.pad_refinement=3", "contact_geometry.pad_refinement"),
    ("contact_geometry.cylinder_facet_m=0.01", "contact_geometry.cylinder_facet_m"),
])
def test_a_bad_contact_geometry_is_refused_in_one_line_naming_the_field(assignment, field):
    with pytest.raises(ConfigError) as error:
        LoadScenario(overrides=[assignment])
    assert f"'{field}'" in str(error.value)
    assert "\n" not in str(error.value)
