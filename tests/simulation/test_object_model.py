"""The scenario's object as a plant body (simulation/object_model.py): a primitive's SDF
gives the mass, centre of mass and inertia of a uniform solid, its frame at the centre of
the base face, a rigid hydroelastic collision shape with the object's friction; a model
file must hold one model of one body."""

import numpy as np
import pytest
from pydrake.geometry import Box, Cylinder
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.parsing import Parser
from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.simulation.object_model import MESH_RESOLUTION_M, AddObject, object_body

BOX = ObjectConfig(name="crate", shape="box", size=[0.04, 0.05, 0.12], mass=0.3, friction=0.4)
CYLINDER = ObjectConfig(name="can", shape="cylinder", size=[0.06, 0.10], mass=0.2,
                        friction=0.7)


def _added(config: ObjectConfig):
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    instance = AddObject(Parser(plant), config)
    plant.Finalize()
    return plant, scene_graph, instance


@pytest.mark.parametrize("config, height, inertia", [
    # Uniform box: m/12 (y^2 + z^2), m/12 (x^2 + z^2), m/12 (x^2 + y^2).
    (BOX, 0.12, 0.3 / 12 * np.array([0.05 ** 2 + 0.12 ** 2, 0.04 ** 2 + 0.12 ** 2,
                                     0.04 ** 2 + 0.05 ** 2])),
    # Uniform cylinder about its centre: m (3 r^2 + h^2) / 12 across, m r^2 / 2 along.
    (CYLINDER, 0.10, np.array([0.2 * (3 * 0.03 ** 2 + 0.1 ** 2) / 12] * 2
                              + [0.2 * 0.03 ** 2 / 2])),
], ids=["box", "cylinder"])
def test_primitive_has_the_mass_properties_of_a_uniform_solid_on_its_base(config, height,
                                                                         inertia):
    plant, _, instance = _added(config)
    body = object_body(plant, instance)
    M_BBo = body.default_spatial_inertia()
    assert M_BBo.get_mass() == pytest.approx(config.mass, rel=1e-12)
    np.testing.assert_allclose(M_BBo.get_com(), [0.0, 0.0, height / 2], rtol=0, atol=1e-12)
    I_BBcm = M_BBo.Shift(M_BBo.get_com()).CalcRotationalInertia().CopyToFullMatrix3()
    # The SDF writes 9 significant digits: a relative error of at most 5e-9.
    np.testing.assert_allclose(I_BBcm, np.diag(inertia), rtol=1e-8, atol=1e-15)


@pytest.mark.parametrize("config, shape", [(BOX, Box), (CYLINDER, Cylinder)],
                         ids=["box", "cylinder"])
def test_primitive_collides_as_a_rigid_hydroelastic_shape_with_its_friction(config, shape):
    plant, scene_graph, instance = _added(config)
    (geometry,) = plant.GetCollisionGeometriesForBody(object_body(plant, instance))
    inspector = scene_graph.model_inspector()
    assert isinstance(inspector.GetShape(geometry), shape)
    np.testing.assert_allclose(inspector.GetPoseInFrame(geometry).translation(),
                               [0.0, 0.0, config.height() / 2], rtol=0, atol=1e-12)
    properties = inspector.GetProximityProperties(geometry)
    # Hydroelastic and rigid: a compliance type, but no modulus (a compliant one has one).
    assert properties.HasProperty("hydroelastic", "compliance_type")
    assert not properties.HasProperty("hydroelastic", "hydroelastic_modulus")
    assert properties.GetProperty("hydroelastic", "resolution_hint") == MESH_RESOLUTION_M
    friction = properties.GetProperty("material", "coulomb_friction")
    assert (friction.static_friction(), friction.dynamic_friction()) == (config.friction,
                                                                         config.friction)


def _file_object(tmp_path, sdf: str) -> ObjectConfig:
    path = tmp_path / "object.sdf"
    path.write_text(sdf)
    return ObjectConfig(name="mine", shape="file", file=str(path), size=[0.04, 0.04, 0.1],
                        mass=0.1, friction=0.5)


LINK = '<link name="{}"><inertial><mass>0.1</mass></inertial></link>'


def _refused_at_build(config: ObjectConfig) -> str:
    """The one-line refusal AddObject gives `config`, checked to be the loader's words."""
    from tegrasp_drake.rig.files import UserPathError
    with pytest.raises(UserPathError) as refused:
        _added(config)
    text = str(refused.value)
    assert "\n" not in text and f"field 'object.file': '{config.file}'" in text, text
    assert "must hold one model with one body (the object)" in text, text
    return text


# The loader (rig/object_file.check_model_file) refuses such files first; AddObject, reached
# with an object config that never went through it, refuses them in the same words.
def test_a_model_file_with_two_models_is_refused(tmp_path):
    config = _file_object(tmp_path, '<?xml version="1.0"?><sdf version="1.9"><world name="w">'
                          f'<model name="a">{LINK.format("a")}</model>'
                          f'<model name="b">{LINK.format("b")}</model></world></sdf>')
    assert "it holds 2 model(s) with bodies ['a', 'b']" in _refused_at_build(config)


def test_a_model_with_two_bodies_is_refused(tmp_path):
    config = _file_object(tmp_path, '<?xml version="1.0"?><sdf version="1.9"><model name="a">'
                          f'{LINK.format("one")}{LINK.format("two")}</model></sdf>')
    assert "it holds 1 model(s) with bodies ['one', 'two']" in _refused_at_build(config)


# A model file's body takes the scenario's mass and friction, as a primitive's does: the
# trial simulates the object its events, records and randomised mass describe.
FILE_BOX = ('<?xml version="1.0"?><sdf version="1.9"><model name="mine"><link name="body">'
            '<inertial><pose>0 0 0.05 0 0 0</pose><mass>0.15</mass><inertia><ixx>1.4e-4</ixx>'
            '<iyy>1.5e-4</iyy><izz>4e-5</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>'
            '</inertial><collision name="c"><pose>0 0 0.05 0 0 0</pose>'
            f'{"<geometry><box><size>0.04 0.04 0.1</size></box></geometry>"}'
            '<drake:proximity_properties><drake:rigid_hydroelastic/><drake:mu_dynamic>0.9'
            '</drake:mu_dynamic><drake:mu_static>0.9</drake:mu_static>'
            '</drake:proximity_properties></collision><visual name="v">'
            '<pose>0 0 0.05 0 0 0</pose><geometry><box><size>0.04 0.04 0.1</size></box>'
            '</geometry></visual></link></model></sdf>')


def test_a_model_files_body_takes_the_scenarios_mass_with_the_files_distribution(tmp_path):
    import dataclasses
    config = dataclasses.replace(_file_object(tmp_path, FILE_BOX), mass=0.3)
    plant, _, instance = _added(config)
    M_BBo = object_body(plant, instance).default_spatial_inertia()
    assert M_BBo.get_mass() == pytest.approx(0.3, rel=1e-12)
    np.testing.assert_allclose(M_BBo.get_com(), [0.0, 0.0, 0.05], rtol=0, atol=1e-12)
    I_BBcm = M_BBo.Shift(M_BBo.get_com()).CalcRotationalInertia().CopyToFullMatrix3()
    # the file's inertia about its centre of mass, scaled by 0.3 / 0.15
    np.testing.assert_allclose(I_BBcm, 2.0 * np.diag([1.4e-4, 1.5e-4, 4e-5]), rtol=1e-9)


def test_a_model_files_collision_takes_the_scenarios_friction_and_keeps_its_shape(tmp_path):
    import dataclasses
    config = dataclasses.replace(_file_object(tmp_path, FILE_BOX), friction=0.01)
    plant, scene_graph, instance = _added(config)
    body = object_body(plant, instance)
    (geometry,) = plant.GetCollisionGeometriesForBody(body)
    inspector = scene_graph.model_inspector()
    assert isinstance(inspector.GetShape(geometry), Box)
    np.testing.assert_allclose(inspector.GetPoseInFrame(geometry).translation(),
                               [0.0, 0.0, 0.05], rtol=0, atol=1e-12)
    properties = inspector.GetProximityProperties(geometry)
    assert properties.HasProperty("hydroelastic", "compliance_type")
    friction = properties.GetProperty("material", "coulomb_friction")
    assert (friction.static_friction(), friction.dynamic_friction()) == (0.01, 0.01)
    assert len(plant.GetVisualGeometriesForBody(body)) == 1
    assert plant.GetModelInstanceName(instance) == "mine" and body.name() == "body"
