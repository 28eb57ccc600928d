"""Adds the table (models/table) to a plant, its top at the world's z = 0, as the compliant
box of the model file or a compliant half-space with its material (`contact_geometry.table`)."""

from pydrake.geometry import (AddCompliantHydroelasticPropertiesForHalfSpace,
                              AddContactMaterial, HalfSpace, ProximityProperties)
from pydrake.math import RigidTransform
from pydrake.multibody.plant import CoulombFriction
from pydrake.multibody.tree import ModelInstanceIndex

from tegrasp_drake.modelgen import table_sdf
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig

TABLE_URL = "package://tegrasp/table/table.sdf"
# The half-space's slab: Drake's box field reaches the modulus at its mid-plane, half its
# thickness deep, so a slab that deep gives the top the same pressure per depth.
HALF_SPACE_SLAB_THICKNESS_M = table_sdf.SIZE[2] / 2
# Drake 1.51 aborts (mesh_half_space_intersection.cc) clipping a rigid triangle with two
# vertices exactly on a soft half-space's plane, as an object's base at z = 0 starts: the
# plane sits this far above the top [m] (0.4 Pa more at rest).
HALF_SPACE_LIFT_M = 1e-9


def _half_space_properties() -> ProximityProperties:
    """The table box's contact material on a compliant half-space."""
    properties = ProximityProperties()
    AddCompliantHydroelasticPropertiesForHalfSpace(HALF_SPACE_SLAB_THICKNESS_M,
                                                   table_sdf.MODULUS, properties)
    AddContactMaterial(properties=properties, dissipation=table_sdf.DISSIPATION,
                       friction=CoulombFriction(table_sdf.FRICTION, table_sdf.FRICTION))
    properties.AddProperty("material", "relaxation_time", table_sdf.RELAXATION_TIME_S)
    return properties


def AddTable(parser, geometry: ContactGeometryConfig | None = None) -> ModelInstanceIndex:
    """Adds the table, welded, shaped as `geometry.table` says; returns its model instance."""
    plant = parser.plant()
    if geometry is None or geometry.table == "box":
        (table,) = parser.AddModels(url=TABLE_URL)
    else:
        (table,) = parser.AddModelsFromString(table_sdf.table_sdf(collision=False), "sdf")
    top = plant.GetFrameByName("top", table)
    plant.WeldFrames(plant.world_frame(), top)
    if geometry is not None and geometry.table == "half_space":
        # HalfSpace: the plane z = 0 of its frame, solid below: the table's top surface.
        plant.RegisterCollisionGeometry(top.body(), RigidTransform([0.0, 0.0, HALF_SPACE_LIFT_M]),
                                        HalfSpace(), "top", _half_space_properties())
    return table
