"""Ground-truth judgement of a trial from its TrialLog: lift, hold, placement, release, and
the times of the physical events that mark the transitions (noise-free simulation truth):

  first_contact        either pad's true normal force on the object first exceeds
                       CONTACT_FORCE_N
  grip_force_reached   both pads reach GRIP_FRACTION of the grip force (or of the grip's
                       plateau, grip_plateau_n): the grip has settled, the earliest lift
  lift_start           the scripted ideal grasp's start of Lift (None in closed loop)
  table_touch          the object's lowest point back within TOUCH_HEIGHT_M of the table
                       after lift-off (a tilted object touches with an edge)

A pad's force counts as on the object only while the fingers stand apart (object_sa): fingers
that closed on nothing press their pads on each other, which the taxels feel as they would
an object."""

import dataclasses

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.math import RotationMatrix

from tegrasp_drake.rig.objects import MIN_SIZE_M
from tegrasp_drake.robotiq import units as ru

CONTACT_FORCE_N = 0.2
GRIP_FRACTION = 0.9
TOUCH_HEIGHT_M = 0.0005
LIFTED_HEIGHT_M = 0.02  # above its resting height, the object counts as lifted
RELEASED_FORCE_N = 0.5
# [s] over which the held grip is measured (docs/controller.md, "The grip a trial holds")
SETTLE_WINDOW_S = 0.2
# [m] Fingers closer than this hold nothing between their pads: half the thinnest object a
# scenario takes (rig/objects.MIN_SIZE_M, 5 mm), ten gPO bytes (0.37 mm each) from closed,
# and far above the pads' squeeze of a held object (25 N on a 20 x 24 mm, 4 mm, 2 MPa pad:
# 0.1 mm). The pads themselves meet at a zero opening (the gPO's closed byte).
PADS_MEET_OPENING_M = MIN_SIZE_M / 2


@dataclasses.dataclass
class GraspOutcome:
    lift_height_m: float
    hold_time_s: float
    final_tilt_deg: float
    placement_error_m: float
    released: bool
    events: dict  # name -> time [s] or None

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def tilt_deg(object_state_row: np.ndarray) -> float:
    """Angle [deg] between the object's z axis and world z."""
    q = object_state_row[:4]
    R = RotationMatrix(Quaternion(q / np.linalg.norm(q)))
    return float(np.degrees(np.arccos(np.clip(R.matrix()[2, 2], -1.0, 1.0))))


def lowest_point_heights(object_state: np.ndarray, object_config=None) -> np.ndarray:
    """Height [m] of the object's lowest point at each logged state (N, 13), for a box or
    cylinder whose origin is the centre of its base; the origin's height otherwise."""
    z = object_state[:, 6].copy()
    if object_config is None or object_config.shape not in ("box", "cylinder"):
        return z
    lowest = np.empty_like(z)
    for k, row in enumerate(object_state):
        q = row[:4] / np.linalg.norm(row[:4])
        R = RotationMatrix(Quaternion(q)).matrix()
        if object_config.shape == "box":
            sx, sy, sz = object_config.size
            corners = np.array([[x, y, h] for x in (-sx / 2, sx / 2) for y in (-sy / 2, sy / 2)
                                for h in (0.0, sz)])
            lowest[k] = z[k] + (corners @ R.T)[:, 2].min()
        else:
            radius, height = object_config.size[0] / 2, object_config.size[1]
            axis_z = R[2, 2]  # the world z of the cylinder's axis
            rim = radius * np.sqrt(max(0.0, 1.0 - axis_z ** 2))
            lowest[k] = z[k] + min(0.0, height * axis_z) - rim
    return lowest


def _first(times: np.ndarray, mask: np.ndarray):
    index = np.flatnonzero(mask)
    return float(times[index[0]]) if index.size else None


def longest_run_s(times: np.ndarray, mask: np.ndarray) -> float:
    """Longest contiguous time [s] during which mask holds."""
    best, start = 0.0, None
    for t, m in zip(times, mask):
        if m and start is None:
            start = t
        if not m and start is not None:
            best, start = max(best, t - start), None
    if start is not None:
        best = max(best, times[-1] - start)
    return float(best)


def true_sa(log) -> np.ndarray:
    """(N, 2) the noise-free 12-taxel sums [N] of the left and right pads at log.t_sa."""
    return log.true_taxels.reshape(len(log.true_taxels), 2, -1).sum(axis=2)


def pads_apart(log) -> np.ndarray:
    """(N,) at each taxel frame (log.t_sa): the fingers' opening in the latest gripper status
    (gPO, log.t_slow) is at least PADS_MEET_OPENING_M, so what the pads press is between
    them; before the first status, apart (the fingers start open)."""
    index = np.searchsorted(log.t_slow, log.t_sa, side="right") - 1
    opening = ru.opening_from_position_byte(log.gripper_status[:, ru.STATUS_PO])
    return np.where(index >= 0, opening[np.maximum(index, 0)] >= PADS_MEET_OPENING_M, True)


def object_sa(log) -> np.ndarray:
    """(N, 2) true_sa where the pads press something between them, 0 where the fingers have
    closed on each other (pads_apart): the pads' force on the object [N]."""
    return np.where(pads_apart(log)[:, None], true_sa(log), 0.0)


def first_contact_time(log, after: float = 0.0):
    """First time >= after [s] that either pad's force on the object exceeds CONTACT_FORCE_N."""
    return _first(log.t_sa, (object_sa(log).max(axis=1) > CONTACT_FORCE_N) & (log.t_sa >= after))


def grip_plateau_n(log, after: float = 0.0) -> float:
    """The level [N] the weaker pad's force on the object settles at after `after` [s]: its
    maximum (the squeeze rises monotonically to it and the lift only redistributes it). 0
    without samples."""
    weaker = object_sa(log).min(axis=1)[log.t_sa >= after]
    return float(weaker.max()) if weaker.size else 0.0


def grip_force_time(log, grip_force: float, after: float = 0.0):
    """First time >= after [s] that both pads' force on the object reaches GRIP_FRACTION of the
    grip force, else of grip_plateau_n (thin objects); None when it never rises above
    CONTACT_FORCE_N."""
    weaker = object_sa(log).min(axis=1)
    level = grip_force
    if not np.any((weaker >= GRIP_FRACTION * grip_force) & (log.t_sa >= after)):
        level = grip_plateau_n(log, after)
        if level <= CONTACT_FORCE_N:
            return None
    return _first(log.t_sa, (weaker >= GRIP_FRACTION * level) & (log.t_sa >= after))


def settled_grip_n(log, grip_force: float, after: float = 0.0) -> float:
    """The grip [N] the weaker pad holds: its median force on the object over SETTLE_WINDOW_S
    after the grip force is reached (grip_force_time, after `after` [s]); 0 if never."""
    start = grip_force_time(log, grip_force, after)
    if start is None:
        return 0.0
    weaker = object_sa(log).min(axis=1)
    window = (log.t_sa >= start) & (log.t_sa <= start + SETTLE_WINDOW_S)
    return float(np.median(weaker[window]))


def grip_fraction_at(log, t: float, grip_force: float, after: float = 0.0) -> float | None:
    """The weaker pad's force on the object at t [s] (latest taxel frame) as a fraction of
    settled_grip_n; None before the first frame or when the pads never grip."""
    index = int(np.searchsorted(log.t_sa, t, side="right")) - 1
    settled = settled_grip_n(log, grip_force, after)
    if index < 0 or settled <= CONTACT_FORCE_N:
        return None
    return float(object_sa(log)[index].min() / settled)


def scripted_lift_start(log) -> float | None:
    """When the scripted ideal grasp starts its Lift [s] (`phase_starts`), else None."""
    return (log.meta.get("phase_starts") or {}).get("lift")


def table_touch_time(log, object_config=None, after: float = 0.0):
    """First time > after [s] that the object's lowest point is within TOUCH_HEIGHT_M of rest."""
    low = lowest_point_heights(log.object_state, object_config)
    return _first(log.t_slow, (low - low[0] < TOUCH_HEIGHT_M) & (log.t_slow > after))


def release_height_m(log, t: float, object_config=None) -> float:
    """Height [m] of the object's lowest point above where it rested at the start (the table
    top: every trial starts with the object standing on it) in the last logged state at or
    before `t` [s]: for the start of Unload, the height the gripper let it go from."""
    low = lowest_point_heights(log.object_state, object_config)
    k = max(int(np.searchsorted(log.t_slow, t, side="right")) - 1, 0)
    return float(low[k] - low[0])


def physical_events(log, grip_force: float, object_config=None) -> dict:
    lift_index = np.flatnonzero(lifted_mask(log, object_config))
    return {"first_contact": first_contact_time(log),
            "grip_force_reached": grip_force_time(log, grip_force),
            "lift_start": scripted_lift_start(log),
            "table_touch": (table_touch_time(log, object_config, after=log.t_slow[lift_index[0]])
                            if lift_index.size else None)}


def lifted_mask(log, object_config=None) -> np.ndarray:
    """At each logged state: the object's lowest point is more than LIFTED_HEIGHT_M above where it
    rested (not the origin: a 45 mm box knocked on its side raises its origin 22.5 mm)."""
    low = lowest_point_heights(log.object_state, object_config)
    return low - low[0] > LIFTED_HEIGHT_M


def judge_grasp(log, *, target_xy, grip_force: float, object_config=None) -> GraspOutcome:
    """Evaluates a trial against the ground truth (object_config: for the object's lowest point)."""
    z = log.object_state[:, 6]
    lifted = lifted_mask(log, object_config)
    final = log.object_state[-1]
    final_sa = log.true_taxels[-1].reshape(2, 12).sum(axis=1)
    return GraspOutcome(
        lift_height_m=float(z.max() - z[0]),
        hold_time_s=longest_run_s(log.t_slow, lifted),
        final_tilt_deg=tilt_deg(final),
        placement_error_m=float(np.linalg.norm(final[4:6] - np.asarray(target_xy))),
        released=bool(final_sa.max() < RELEASED_FORCE_N),
        events=physical_events(log, grip_force, object_config))
