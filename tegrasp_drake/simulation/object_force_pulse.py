"""An external force pulse on the object: the scenario's "hit" (to exercise Avoid)."""

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.multibody.math import SpatialForce
from pydrake.multibody.plant import ExternallyAppliedSpatialForce
from pydrake.systems.framework import LeafSystem


@dataclasses.dataclass
class DisturbanceConfig:
    """An external hit on the object: a constant force pulse at its body origin."""
    hit_time_s: float = -1.0  # simulated time of the hit [s]; negative: no hit
    hit_force_n: list[float] = dataclasses.field(default_factory=lambda: [0.0, 20.0, 0.0])  # world
    hit_duration_s: float = 0.02


class ObjectForcePulse(LeafSystem):
    """A constant force `config.hit_force_n` [N, world frame] on the object's body origin
    during [hit_time_s, hit_time_s + hit_duration_s); nothing otherwise.

    .. pydrake_system::

        name: ObjectForcePulse
        output_ports:
        - applied_spatial_force

    Ports:
        applied_spatial_force: (abstract list of ExternallyAppliedSpatialForce) the pulse on
            the object's body origin during the hit, an empty list otherwise; for the
            plant's applied_spatial_force input.
    """

    def __init__(self, *, body_index, config: DisturbanceConfig):
        super().__init__()
        self._start = float(config.hit_time_s)
        self._end = self._start + float(config.hit_duration_s)
        force = ExternallyAppliedSpatialForce()
        force.body_index = body_index
        force.p_BoBq_B = np.zeros(3)
        force.F_Bq_W = SpatialForce(np.zeros(3), np.asarray(config.hit_force_n, dtype=float))
        self._force = force
        self.DeclareAbstractOutputPort(
            "applied_spatial_force",
            lambda: AbstractValue.Make([ExternallyAppliedSpatialForce()]), self._calc,
            prerequisites_of_calc={self.time_ticket()})

    def _calc(self, context, output):
        active = self._start <= context.get_time() < self._end
        output.set_value([self._force] if active else [])
