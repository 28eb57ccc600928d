"""Where a scenario's object stands: on its marker, where the robot expects it, moved by a
misplacement and yawed (the paper's grid of misplacements, Sec. IV-B)."""

import dataclasses
import math

from tegrasp_drake.modelgen.table_sdf import CENTER_XY as TABLE_CENTER_XY
from tegrasp_drake.modelgen.table_sdf import SIZE as TABLE_SIZE
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.rig.api_boundary import public_dataclass


@public_dataclass
@dataclasses.dataclass
class ObjectPlacementConfig:
    """The object's marker and its misplacement from it [m, world; deg]."""
    # The marker, where the robot expects the object (the grasp is planned for it).
    expected_xy: list[float] = bounded(default_factory=lambda: [0.72, 0.0], low=-0.9, high=0.9,
                                       unit="m", length=2,
                                       why="within the JACO2's 0.9 m reach, Kinova JACO2 "
                                           "specifications")
    # Misplacement from the marker: x normal to the palm, y along the stroke.
    offset: list[float] = bounded(default_factory=lambda: [0.0, 0.0], low=-0.2, high=0.2,
                                  unit="m", length=2,
                                  why="a misplacement near its marker, within the open hand's "
                                      "reach")
    yaw_deg: float = bounded(0.0, low=-180.0, high=180.0, unit="deg")

    def xy(self) -> tuple[float, float]:
        """Where the object's centre stands [m, world]: the marker moved by the offset."""
        return tuple(a + b for a, b in zip(self.expected_xy, self.offset))

    def problem(self, shape: str, size, spread_m: float = 0.0
                ) -> tuple[str, str, object] | None:
        """(field, must, value) when a `shape` of `size` [m] here, or up to spread_m [m] off
        it along each axis (a sweep's placement jitter), is off the table; else None."""
        x, y = self.xy()
        radius = footprint_radius(shape, size) + spread_m
        (cx, cy), (half_x, half_y) = TABLE_CENTER_XY, (TABLE_SIZE[0] / 2, TABLE_SIZE[1] / 2)
        if abs(x - cx) + radius <= half_x and abs(y - cy) + radius <= half_y:
            return None
        return ("offset", f"puts the object at ({x:.3f}, {y:.3f}) m (placement.expected_xy "
                f"{list(self.expected_xy)} + placement.offset"
                + (f", +-{spread_m * 1000:g} mm of placement jitter" if spread_m else "")
                + "), off the table top (x "
                f"{cx - half_x:g} to {cx + half_x:g} m, y {cy - half_y:g} to {cy + half_y:g} m); "
                "place it on the table", list(self.offset))


# How far a result's offset may lie from where its trial put the object [m]: a sweep's trial
# function sets it to its marker + jitter (scenario_from_trial_spec) and JSON carries a float
# exactly, so only a sum taken in another order differs, by ~1e-17 m; a nanometre is far below
# anything the simulation resolves and far above that rounding.
OFFSET_TOLERANCE_M = 1e-9


def result_offset_problem(offset, expected) -> str | None:
    """Why `offset` [m, x y] (a result's offset_m, a logged placement.offset) is not the
    offset `expected` [m, x y] its trial put the object at, within OFFSET_TOLERANCE_M, in
    words ("OFFSET m is not EXPECTED m"), or None."""
    if len(offset) == 2 and all(abs(a - b) <= OFFSET_TOLERANCE_M
                                for a, b in zip(offset, expected)):
        return None
    return f"{shorten(repr(offset))} m is not [{expected[0]!r}, {expected[1]!r}] m"


def footprint_radius(shape: str, size) -> float:
    """The radius [m] of the upright cylinder about an object's footprint at any yaw: a
    cylinder's own, a box's (or a file's bounding box's) half diagonal."""
    return size[0] / 2 if shape == "cylinder" else math.hypot(size[0], size[1]) / 2


def object_speed_bound_mps(hit_impulse_n_s: float) -> float:
    """The fastest [m/s] a scenario's object can move: as fast as the hand carrying or throwing
    it (rig/jaco_velocity_tracker.HAND_SPEED_BOUND_MPS) plus what a hit of hit_impulse_n_s
    [N s] (its force times its duration; 0: no hit) gives the lightest object a scenario
    allows (rig/objects.MIN_MASS_KG). Gravity adds to it while the object falls
    (object_position_bounds)."""
    from tegrasp_drake.rig.jaco_velocity_tracker import HAND_SPEED_BOUND_MPS
    from tegrasp_drake.rig.objects import MIN_MASS_KG
    return HAND_SPEED_BOUND_MPS + hit_impulse_n_s / MIN_MASS_KG


def object_sideways_speed_bound_mps(speed_mps: float, gravity_mps2: float) -> float:
    """The fastest [m/s] the object's origin can move sideways (world x, y), given its speed bound
    speed_mps (object_speed_bound_mps) and gravity_mps2 [m/s^2] along world z only. Gravity
    speeds a fall but turns it sideways only through a contact (a finger it pivots on, the table
    it tips over; the scene has no floor, and in free fall the sideways speed stays as it was):
    by energy, at most sqrt(speed^2 + 2 g h) with h the highest drop a contact can turn, from
    the JACO2's reach above the table (the highest the hand lifts it) to the table slab's
    underside."""
    from tegrasp_drake.rig.jaco_velocity_tracker import JACO2_REACH_M
    drop = JACO2_REACH_M + TABLE_SIZE[2]
    return math.sqrt(speed_mps ** 2 + 2.0 * gravity_mps2 * drop)


def object_position_bounds(duration_s: float, speed_mps: float,
                           gravity_mps2: float) -> tuple[tuple[float, float], tuple[float, float],
                                                          tuple[float, float]]:
    """(x, y, z) ranges [m, world] the object's origin stays in for duration_s [s] of a
    trial: it starts on the table top (ObjectPlacementConfig.problem refuses a placement off
    it) and moves at most speed_mps [m/s] (object_speed_bound_mps) sideways; up, the hand
    lifts it at most the JACO2's reach above the table (it holds it within the reach) and it
    moves at most speed_mps further; down, it may also fall (off the table's edge) under
    gravity_mps2 [m/s^2] the whole time."""
    from tegrasp_drake.rig.jaco_velocity_tracker import JACO2_REACH_M
    travel = speed_mps * duration_s
    (cx, cy), (half_x, half_y) = TABLE_CENTER_XY, (TABLE_SIZE[0] / 2, TABLE_SIZE[1] / 2)
    return ((cx - half_x - travel, cx + half_x + travel),
            (cy - half_y - travel, cy + half_y + travel),
            (-travel - gravity_mps2 * duration_s ** 2 / 2, JACO2_REACH_M + travel))

