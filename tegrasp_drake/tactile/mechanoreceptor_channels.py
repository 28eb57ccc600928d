"""The paper's Eq. 1 (SA_i, the sum of finger i's 12 taxel normal forces [N]) and Eq. 2 (RA_i, the
magnitude of its pad's vibration [m/s^2]) for both fingers, as one Diagram. RA is compiled
(SymbolicVectorSystem); SA is summed in Python in numpy's pairwise order, which a compiled
MatrixGain would change by a rounding, and costs nothing between 108 Hz taxel samples (cached)."""

import math

import numpy as np
from pydrake.symbolic import Variable, sqrt
from pydrake.systems.framework import DiagramBuilder, LeafSystem, System
from pydrake.systems.primitives import Multiplexer, SymbolicVectorSystem

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.api_boundary import public_api

_AXES = ports.PAD_ACCELERATION_AXES


def slowly_adapting(taxel_forces: np.ndarray) -> float:
    """Eq. 1: the sum of a pad's taxel normal forces [N]."""
    return float(np.add.reduce(taxel_forces))  # np.sum's own reduction, without its wrapper


def rapidly_adapting(acceleration: np.ndarray) -> float:
    """Eq. 2: the magnitude of a pad's vibration vector [m/s^2]."""
    a = np.asarray(acceleration, dtype=float)
    return math.sqrt(a.dot(a))  # what np.linalg.norm computes for a vector


class SlowlyAdapting(LeafSystem):
    """Eq. 1 of both fingers.

    .. pydrake_system::

        name: SlowlyAdapting
        input_ports:
        - left_taxel_forces
        - right_taxel_forces
        output_ports:
        - sa

    Each taxel's normal force (12) [N] per finger in; sa [left, right] [N] out.
    """

    def __init__(self):
        super().__init__()
        self._taxels = [self.DeclareVectorInputPort(f"{f}_taxel_forces", TAXELS_PER_PAD)
                        for f in FINGER_NAMES]
        self.DeclareVectorOutputPort("sa", len(FINGER_NAMES), self._calc,
                                     prerequisites_of_calc={p.ticket() for p in self._taxels})

    def _calc(self, context, output):
        output.SetFromVector([slowly_adapting(p.Eval(context)) for p in self._taxels])


def rapidly_adapting_system() -> SymbolicVectorSystem:
    """Eq. 2 of both fingers: [left xyz, right xyz] in, [RA_left, RA_right] out [m/s^2]."""
    axes = [[Variable(f"{finger}_{axis}") for axis in "xyz"] for finger in FINGER_NAMES]
    return SymbolicVectorSystem(input=[a for pad in axes for a in pad],
                                output=[sqrt(x * x + y * y + z * z) for x, y, z in axes])


@public_api
def MakeMechanoreceptorChannels():
    """The four channels SA_left, SA_right, RA_left, RA_right as a Diagram.

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

    Taxel forces (12) [N] and pad vibration (3) [m/s^2, pad frame] per finger in; sa
    [N], ra [m/s^2] ([left, right]) and channels (CHANNEL_NAMES order) out.
    """
    builder = DiagramBuilder()
    sa = builder.AddNamedSystem("slowly_adapting", SlowlyAdapting())
    accelerations = builder.AddNamedSystem("pad_accelerations",
                                           Multiplexer([_AXES] * len(FINGER_NAMES)))
    ra = builder.AddNamedSystem("rapidly_adapting", rapidly_adapting_system())
    builder.Connect(accelerations.get_output_port(), ra.get_input_port())
    channels = builder.AddNamedSystem("channels", Multiplexer([len(FINGER_NAMES)] * 2))
    builder.Connect(sa.get_output_port(), channels.get_input_port(0))
    builder.Connect(ra.get_output_port(), channels.get_input_port(1))
    for finger in FINGER_NAMES:
        builder.ExportInput(sa.GetInputPort(f"{finger}_taxel_forces"),
                            f"{finger}_taxel_forces")
    for k, finger in enumerate(FINGER_NAMES):
        builder.ExportInput(accelerations.get_input_port(k), f"{finger}_pad_acceleration")
    builder.ExportOutput(sa.get_output_port(), "sa")
    builder.ExportOutput(ra.get_output_port(), "ra")
    builder.ExportOutput(channels.get_output_port(), "channels")
    diagram = builder.Build()
    diagram.set_name("mechanoreceptor_channels")
    return diagram


@public_api
def AddMechanoreceptorChannels(builder: DiagramBuilder, station: System):
    """Adds Eq. 1-2 (MakeMechanoreceptorChannels) fed by the station's tactile ports."""
    channels = builder.AddNamedSystem("mechanoreceptor_channels", MakeMechanoreceptorChannels())
    for finger in FINGER_NAMES:
        builder.Connect(station.GetOutputPort(ports.taxel_forces(finger)),
                        channels.GetInputPort(f"{finger}_taxel_forces"))
        builder.Connect(station.GetOutputPort(ports.pad_acceleration(finger)),
                        channels.GetInputPort(f"{finger}_pad_acceleration"))
    return channels
