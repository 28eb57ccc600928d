"""A constant force on one body over a time interval: the scenario's hit on the object (to
exercise Avoid) and the gripper bench's push on a pad."""

import dataclasses
import math

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.multibody.math import SpatialForce
from pydrake.multibody.plant import ExternallyAppliedSpatialForce
from pydrake.systems.framework import LeafSystem
from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.rig.api_boundary import public_dataclass


@public_dataclass
@dataclasses.dataclass
class DisturbanceConfig:
    """An external hit on the object: a constant force pulse at its body origin."""
    # simulated time of the hit [s]; negative: no hit
    hit_time_s: float = bounded(-1.0, low=-1e6, high=600.0, unit="s", why="negative: no hit")
    # in world
    hit_force_n: list[float] = bounded(default_factory=lambda: [0.0, 20.0, 0.0], low=-100.0,
                                       high=100.0, unit="N", length=3, why="five times the paper's 20 N hit")
    hit_duration_s: float = bounded(0.02, low=0.0, low_open=True, high=1.0, unit="s",
                                    why="a hit, not a push", below="must be positive [s]")


class BodyForcePulse(LeafSystem):
    """A constant force `f_W` [N, world frame] at the point Q of body B (`p_BQ` [m], B's
    frame) during [start_s, end_s) [s]; nothing otherwise (end_s = inf: from start_s on).

    .. pydrake_system::

        name: BodyForcePulse
        output_ports:
        - applied_spatial_force

    Ports:
        applied_spatial_force: (list of ExternallyAppliedSpatialForce) the force during the
            interval, else empty; for the plant's applied_spatial_force input.
    """

    def __init__(self, *, body_index, p_BQ, f_W, start_s: float, end_s: float = math.inf):
        super().__init__()
        self._start, self._end = float(start_s), float(end_s)
        force = ExternallyAppliedSpatialForce()
        force.body_index = body_index
        force.p_BoBq_B = np.asarray(p_BQ, dtype=float)
        force.F_Bq_W = SpatialForce(np.zeros(3), np.asarray(f_W, dtype=float))
        self._force = force
        self.DeclareAbstractOutputPort(
            "applied_spatial_force",
            lambda: AbstractValue.Make([ExternallyAppliedSpatialForce()]), self._calc,
            prerequisites_of_calc={self.time_ticket()})

    @classmethod
    def object_hit(cls, *, body_index, config: DisturbanceConfig) -> "BodyForcePulse":
        """The scenario's hit (`config`) on the object's body origin."""
        return cls(body_index=body_index, p_BQ=np.zeros(3), f_W=config.hit_force_n,
                   start_s=config.hit_time_s,
                   end_s=config.hit_time_s + config.hit_duration_s)

    def _calc(self, context, output):
        active = self._start <= context.get_time() < self._end
        output.set_value([self._force] if active else [])
