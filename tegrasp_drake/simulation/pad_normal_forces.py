"""PadNormalForces: each finger's net contact force along its pad's outward normal.

The PVDF film (pad_vibration_sensor.py) is loaded by the pad's normal contact force. On the
prismatic hand the finger joint moves along the pad normal, so its generalized contact force
is that force; a linkage finger's joints turn, so this system sums the contact forces on the
finger body (the follower: pad and backing) from the plant's contact results and projects
them on the pad's outward normal.
"""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ContactResults
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES


def pad_contact_force(contacts, geometry_body: dict, finger_body: int,
                      n_out_W: np.ndarray) -> float:
    """The net contact force on body `finger_body` [N] along n_out_W (world), positive
    pushing the pad open. geometry_body maps collision geometry ids to body indices."""
    total = np.zeros(3)
    for i in range(contacts.num_hydroelastic_contacts()):
        info = contacts.hydroelastic_contact_info(i)
        surface = info.contact_surface()
        if geometry_body.get(surface.id_M()) == finger_body:  # F_Ac_W acts on M's body
            total += info.F_Ac_W().translational()
        elif geometry_body.get(surface.id_N()) == finger_body:
            total -= info.F_Ac_W().translational()
    for i in range(contacts.num_point_pair_contacts()):
        info = contacts.point_pair_contact_info(i)
        if int(info.bodyB_index()) == finger_body:  # contact_force acts on body B
            total += info.contact_force()
        elif int(info.bodyA_index()) == finger_body:
            total -= info.contact_force()
    return float(total @ n_out_W)


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
        pad_normal_forces: (2, N) left, right: the net contact force on each finger body
            along its pad's outward normal (the pad frame's -z), positive pushing it open.
    """

    def __init__(self, *, plant, pads: dict):
        super().__init__()
        self._pads = [pads[finger] for finger in FINGER_NAMES]
        self._geometry_body = {}
        for i in range(plant.num_bodies()):
            body = plant.get_body(BodyIndex(i))
            for geometry in plant.GetCollisionGeometriesForBody(body):
                self._geometry_body[geometry] = i
        self._contacts = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._poses = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        self.DeclareVectorOutputPort(
            "pad_normal_forces", 2, self._calc,
            prerequisites_of_calc={self._contacts.ticket(), self._poses.ticket()})

    def _calc(self, context, output):
        contacts = self._contacts.Eval(context)
        poses = self._poses.Eval(context)
        forces = []
        for pad in self._pads:
            X_WB = poses[int(pad.body_index)]
            n_out_W = -(X_WB.rotation().matrix() @ pad.X_BP.rotation().matrix()[:, 2])
            forces.append(pad_contact_force(contacts, self._geometry_body,
                                            int(pad.body_index), n_out_W))
        output.SetFromVector(forces)
