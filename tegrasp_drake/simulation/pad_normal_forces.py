"""PadNormalForces: each finger's net contact force along its pad's outward normal, the
film's load on the linkage hand, whose finger joints turn (on the prismatic hand the finger
joint's generalized contact force is that force): the contact forces on the finger body
summed from the plant's contact results."""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ContactResults
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES


def collision_geometry_bodies(plant) -> dict:
    """{collision geometry id: the index (int) of the body it belongs to} of `plant`."""
    bodies = {}
    for i in range(plant.num_bodies()):
        for geometry in plant.GetCollisionGeometriesForBody(plant.get_body(BodyIndex(i))):
            bodies[geometry] = i
    return bodies


def bodies_contact_forces(contacts, geometry_body: dict, bodies) -> list[np.ndarray]:
    """The net contact force [N, world] on each body index in `bodies`, in one walk over the
    contacts; geometry_body maps collision geometry ids to body indices."""
    totals = [np.zeros(3) for _ in bodies]
    for i in range(contacts.num_hydroelastic_contacts()):
        info = contacts.hydroelastic_contact_info(i)
        surface = info.contact_surface()
        body_M = geometry_body.get(surface.id_M())
        body_N = geometry_body.get(surface.id_N())
        if body_M not in bodies and body_N not in bodies:
            continue
        force = info.F_Ac_W().translational()
        for total, body in zip(totals, bodies):
            if body_M == body:  # F_Ac_W acts on M's body
                total += force
            elif body_N == body:
                total -= force
    for i in range(contacts.num_point_pair_contacts()):
        info = contacts.point_pair_contact_info(i)
        body_A, body_B = int(info.bodyA_index()), int(info.bodyB_index())
        if body_A not in bodies and body_B not in bodies:
            continue
        force = info.contact_force()
        for total, body in zip(totals, bodies):
            if body_B == body:  # contact_force acts on body B
                total += force
            elif body_A == body:
                total -= force
    return totals


class PadNormalForces(LeafSystem):
    """Both fingers' contact forces along their pads' outward normals.

    .. pydrake_system::

        name: PadNormalForces
        input_ports:
        - contact_results
        - body_poses
        output_ports:
        - pad_normal_forces

    Ports:
        contact_results, body_poses: the plant's.
        pad_normal_forces: (2, N) each finger body's net contact force along its pad's
            outward normal (the pad frame's -z), positive pushing it open.
    """

    def __init__(self, *, plant, pads: dict):
        super().__init__()
        self._pads = [pads[finger] for finger in FINGER_NAMES]
        self._bodies = tuple(int(pad.body_index) for pad in self._pads)
        # Each pad frame's z axis in its body frame (a column of R_BP).
        self._z_BP = [pad.X_BP.rotation().matrix()[:, 2] for pad in self._pads]
        self._geometry_body = collision_geometry_bodies(plant)
        self._contacts = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._poses = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        self.DeclareVectorOutputPort(
            "pad_normal_forces", 2, self._calc,
            prerequisites_of_calc={self._contacts.ticket(), self._poses.ticket()})

    def _calc(self, context, output):
        poses = self._poses.Eval(context)
        totals = bodies_contact_forces(self._contacts.Eval(context), self._geometry_body,
                                       self._bodies)
        output.SetFromVector([
            float(total @ -(poses[body].rotation().matrix() @ z_BP))
            for total, body, z_BP in zip(totals, self._bodies, self._z_BP)])
