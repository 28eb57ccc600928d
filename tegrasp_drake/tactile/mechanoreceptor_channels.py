"""MechanoreceptorChannels: the paper's Eq. 1 (SA) and Eq. 2 (RA) for both fingers.

SA_i = sum over finger i's 12 taxels of the normal force F_z,k [N]          (Eq. 1)
RA_i = sqrt(a_x^2 + a_y^2 + a_z^2) of finger i's pad vibration [m/s^2]      (Eq. 2)
"""

import math

import numpy as np
from pydrake.systems.framework import LeafSystem
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.framework import System

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.api_boundary import public_api


def slowly_adapting(taxel_forces: np.ndarray) -> float:
    """Eq. 1: the sum of a pad's taxel normal forces [N]."""
    return float(np.add.reduce(taxel_forces))  # np.sum's own reduction, without its wrapper


def rapidly_adapting(acceleration: np.ndarray) -> float:
    """Eq. 2: the magnitude of a pad's vibration vector [m/s^2]."""
    a = np.asarray(acceleration, dtype=float)
    return math.sqrt(a.dot(a))  # what np.linalg.norm computes for a vector


class MechanoreceptorChannels(LeafSystem):
    """The four channels SA_left, SA_right, RA_left, RA_right.

    .. pydrake_system::

        name: MechanoreceptorChannels
        input_ports:
        - left_taxel_forces
        - right_taxel_forces
        - left_pad_acceleration
        - right_pad_acceleration
        output_ports:
        - sa
        - ra
        - channels

    Ports:
        left_taxel_forces, right_taxel_forces: (12) each taxel's normal force F_z [N].
        left_pad_acceleration, right_pad_acceleration: (3) the pad's vibration [m/s^2],
            pad frame.
        sa: (2) [left, right] Eq. 1 [N].
        ra: (2) [left, right] Eq. 2 [m/s^2].
        channels: (4) [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2), in
            tegrasp_drake.rig.channels.CHANNEL_NAMES order.
    """

    def __init__(self):
        super().__init__()
        self._taxels = [self.DeclareVectorInputPort(f"{f}_taxel_forces", TAXELS_PER_PAD)
                        for f in FINGER_NAMES]
        self._accelerations = [self.DeclareVectorInputPort(f"{f}_pad_acceleration", 3)
                               for f in FINGER_NAMES]
        sa_tickets = {p.ticket() for p in self._taxels}
        ra_tickets = {p.ticket() for p in self._accelerations}
        self._sa_port = self.DeclareVectorOutputPort("sa", 2, self._calc_sa,
                                                     prerequisites_of_calc=sa_tickets)
        self.DeclareVectorOutputPort("ra", 2, self._calc_ra, prerequisites_of_calc=ra_tickets)
        self.DeclareVectorOutputPort("channels", 4, self._calc_channels,
                                     prerequisites_of_calc=sa_tickets | ra_tickets)

    def _sa(self, context):
        return [slowly_adapting(p.Eval(context)) for p in self._taxels]

    def _ra(self, context):
        return [rapidly_adapting(p.Eval(context)) for p in self._accelerations]

    def _calc_sa(self, context, output):
        output.SetFromVector(self._sa(context))

    def _calc_ra(self, context, output):
        output.SetFromVector(self._ra(context))

    def _calc_channels(self, context, output):
        # SA from the sa port's cache: the taxels change at their own rate (108 Hz), RA at
        # every film sample (1 kHz), when this port is evaluated.
        output.SetFromVector(self._sa_port.Eval(context).tolist() + self._ra(context))


@public_api
def AddMechanoreceptorChannels(builder: DiagramBuilder, station: System):
    """Adds Eq. 1-2 fed by the station's tactile ports; returns the system."""
    channels = builder.AddNamedSystem("mechanoreceptor_channels", MechanoreceptorChannels())
    for finger in FINGER_NAMES:
        builder.Connect(station.GetOutputPort(ports.taxel_forces(finger)),
                        channels.GetInputPort(f"{finger}_taxel_forces"))
        builder.Connect(station.GetOutputPort(ports.pad_acceleration(finger)),
                        channels.GetInputPort(f"{finger}_pad_acceleration"))
    return channels
