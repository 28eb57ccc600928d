"""Adds the scenario's object to a plant: a primitive shape written as SDF, or a model file.
Primitive objects are rigid hydroelastic bodies with frame O at the centre of the base face,
z up, and the inertia of a uniform solid; a model file's body keeps its geometry and mass
distribution and takes the scenario's mass and friction."""

import itertools

import numpy as np
from pydrake.geometry import (AddContactMaterial, AddRigidHydroelasticProperties, Convex,
                              ProximityProperties)
from pydrake.math import RigidTransform
from pydrake.multibody.plant import CoulombFriction
from pydrake.multibody.tree import ModelInstanceIndex

from tegrasp_drake.modelgen.sdf_text import box_inertia, friction_text, inertial_text
from tegrasp_drake.rig.files import UserPathError
from tegrasp_drake.rig.object_file import drake_error_line, joints_problem, one_body_problem
from tegrasp_drake.rig.objects import DEFAULT_COLOR, ObjectConfig
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig

OBJECT_MODEL_NAME = "object"
OBJECT_BODY_NAME = "object"
# Edge length [m] of a primitive's rigid surface mesh (a cylinder's facets; a box is 24
# triangles whatever the hint): at 10 mm the thin cylinder slips at 0.87 of the Coulomb grip,
# outside the validation's 10 % (docs/sweeps.md, "Coarser contact geometry").
MESH_RESOLUTION_M = 0.005


def _geometry(config: ObjectConfig) -> str:
    if config.shape == "box":
        return "<box><size>{:g} {:g} {:g}</size></box>".format(*config.size)
    diameter, height = config.size
    return f"<cylinder><radius>{diameter / 2:g}</radius><length>{height:g}</length></cylinder>"


def _inertia(config: ObjectConfig) -> np.ndarray:
    if config.shape == "box":
        return box_inertia(config.mass, config.size)
    radius, height = config.size[0] / 2, config.size[1]
    side = config.mass * (3 * radius ** 2 + height ** 2) / 12
    return np.diag([side, side, config.mass * radius ** 2 / 2])


def object_sdf(config: ObjectConfig, *, mesh_resolution_m: float = MESH_RESOLUTION_M,
               collision: bool = True) -> str:
    """SDF text of a primitive (box or cylinder) object; mesh_resolution_m: its
    drake:mesh_resolution_hint [m]; without `collision`, its body and visual only."""
    half_height = config.height() / 2
    color = " ".join(f"{c:g}" for c in config.color or DEFAULT_COLOR)
    geometry = _geometry(config)
    collision_text = (
        f'<collision name="collision"><pose>0 0 {half_height:g} 0 0 0</pose>'
        f"<geometry>{geometry}</geometry><drake:proximity_properties><drake:rigid_hydroelastic/>"
        f"<drake:mesh_resolution_hint>{mesh_resolution_m:g}</drake:mesh_resolution_hint>"
        f"{friction_text(config.friction)}</drake:proximity_properties></collision>")
    return (
        '<?xml version="1.0"?><sdf version="1.9">'
        f'<model name="{OBJECT_MODEL_NAME}"><link name="{OBJECT_BODY_NAME}">'
        f"{inertial_text(config.mass, (0, 0, half_height), _inertia(config))}"
        f"{collision_text if collision else ''}"
        f'<visual name="visual"><pose>0 0 {half_height:g} 0 0 0</pose>'
        f"<geometry>{geometry}</geometry><material><diffuse>{color}</diffuse></material>"
        "</visual></link></model></sdf>")


def _corner_hull_collision(plant, instance, config: ObjectConfig) -> None:
    """The box's collision shape as its 8 corners' convex hull, with its Box's properties."""
    half = np.asarray(config.size, dtype=float) / 2
    corners = np.array([signs for signs in itertools.product((-1.0, 1.0), repeat=3)]).T
    properties = ProximityProperties()
    AddRigidHydroelasticProperties(MESH_RESOLUTION_M, properties)
    AddContactMaterial(properties=properties,
                       friction=CoulombFriction(config.friction, config.friction))
    plant.RegisterCollisionGeometry(
        object_body(plant, instance), RigidTransform([0.0, 0.0, config.height() / 2]),
        Convex(corners * half[:, None], "box_corner_hull"), "collision", properties)


def _added_model_file_body(parser, config: ObjectConfig) -> ModelInstanceIndex:
    """The model file's one body added to the parser's plant with the scenario's mass and
    friction, as a primitive's are: the file is parsed into a plant of its own, and its body
    made again in this one (a parsed body's mass cannot be changed before Finalize, only in
    a context) with its spatial inertia scaled to object.mass (the same centre of mass and
    mass distribution: its density scaled), its geometries at their poses with their
    properties, each collision geometry's Coulomb friction object.friction (static =
    dynamic). So the trial simulates the object its events, records and randomised mass and
    friction describe. A file that is not one model of one free body is refused."""
    from pydrake.geometry import GeometryInstance, IllustrationProperties, PerceptionProperties
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.tree import SpatialInertia
    from pydrake.systems.framework import DiagramBuilder
    scratch, scratch_graph = AddMultibodyPlantSceneGraph(DiagramBuilder(), time_step=0.0)
    scratch_parser = Parser(scratch)
    scratch_parser.package_map().AddMap(parser.package_map())
    instances = _added_model_file(scratch_parser, config.file)
    problem = (one_body_problem(scratch, instances) or joints_problem(scratch, instances[0]))
    if problem:
        raise UserPathError(f"field 'object.file': '{config.file}' {problem}")
    source = object_body(scratch, instances[0])
    inertia = source.default_spatial_inertia()
    plant = parser.plant()
    instance = plant.AddModelInstance(scratch.GetModelInstanceName(instances[0]))
    body = plant.AddRigidBody(source.name(), instance, SpatialInertia(
        config.mass, inertia.get_com(), inertia.get_unit_inertia()))
    inspector = scratch_graph.model_inspector()
    for geometry in scratch.GetCollisionGeometriesForBody(source):
        properties = ProximityProperties(inspector.GetProximityProperties(geometry))
        friction = CoulombFriction(config.friction, config.friction)
        if properties.HasProperty("material", "coulomb_friction"):
            properties.UpdateProperty("material", "coulomb_friction", friction)
        else:
            properties.AddProperty("material", "coulomb_friction", friction)
        plant.RegisterCollisionGeometry(body, inspector.GetPoseInFrame(geometry),
                                        inspector.GetShape(geometry),
                                        inspector.GetName(geometry).split("::")[-1],
                                        properties)
    for geometry in scratch.GetVisualGeometriesForBody(source):
        visual = GeometryInstance(inspector.GetPoseInFrame(geometry),
                                  inspector.GetShape(geometry),
                                  inspector.GetName(geometry).split("::")[-1])
        illustration = inspector.GetIllustrationProperties(geometry)
        perception = inspector.GetPerceptionProperties(geometry)
        if illustration is not None:
            visual.set_illustration_properties(IllustrationProperties(illustration))
        if perception is not None:
            visual.set_perception_properties(PerceptionProperties(perception))
        plant.RegisterVisualGeometry(body, visual)
    return instance


def _added_model_file(parser, file: str) -> list[ModelInstanceIndex]:
    """The model instances of the model file `file` (a path or package:// URL); UserPathError
    (one line, naming object.file, which the command line reports as a user's file) when
    Drake cannot load it: a file changed since the scenario's check (rig/object_file.py), or
    an object config that never went through it."""
    try:
        if file.startswith("package://"):
            return parser.AddModels(url=file)
        return parser.AddModels(file_name=file)
    except (RuntimeError, ValueError) as e:
        raise UserPathError(f"field 'object.file': '{file}' is not a model Drake can load: "
                            f"{drake_error_line(e)}") from None


def AddObject(parser, config: ObjectConfig,
              geometry: ContactGeometryConfig | None = None) -> ModelInstanceIndex:
    """Adds the object to the parser's plant, meshed as `geometry` says; returns its instance."""
    geometry = geometry or ContactGeometryConfig()
    corner_hull = config.shape == "box" and geometry.box_triangles == 12
    if config.shape == "file":
        instances = [_added_model_file_body(parser, config)]
    else:
        instances = parser.AddModelsFromString(object_sdf(config, collision=not corner_hull),
                                               "sdf")
    if corner_hull:
        _corner_hull_collision(parser.plant(), instances[0], config)
    return instances[0]


def object_body(plant, instance):
    """The object's single body."""
    bodies = plant.GetBodyIndices(instance)
    if len(bodies) != 1:
        raise ValueError(f"the object model must have exactly one body, it has {len(bodies)}")
    return plant.get_body(bodies[0])
