"""An external force pulse on the object: the scenario's "hit" (to exercise Avoid)."""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.multibody.math import SpatialForce
from pydrake.multibody.plant import ExternallyAppliedSpatialForce
from pydrake.systems.framework import LeafSystem


class ObjectForcePulse(LeafSystem):
    """A constant force [N, world frame] on the object's body origin during
    [start_s, start_s + duration_s); nothing otherwise.

    Output: applied_spatial_force (list of ExternallyAppliedSpatialForce), for the plant's
    applied_spatial_force input.
    """

    def __init__(self, *, body_index, start_s: float, duration_s: float, force_W):
        super().__init__()
        self._start, self._end = float(start_s), float(start_s) + float(duration_s)
        force = ExternallyAppliedSpatialForce()
        force.body_index = body_index
        force.p_BoBq_B = np.zeros(3)
        force.F_Bq_W = SpatialForce(np.zeros(3), np.asarray(force_W, dtype=float))
        self._force = force
        self.DeclareAbstractOutputPort(
            "applied_spatial_force",
            lambda: AbstractValue.Make([ExternallyAppliedSpatialForce()]), self._calc,
            prerequisites_of_calc={self.time_ticket()})

    def _calc(self, context, output):
        active = self._start <= context.get_time() < self._end
        output.set_value([self._force] if active else [])
