"""The corrective actions of Sec. III-C (Re-Reach, Lift-Load, Avoid) as pure functions: the
decisions the rules call and the moves the state machine makes (docs/controller.md, "Corrective
actions"). Frames: world W; G approaches along +x, the stroke along y, the left finger on +y."""

import dataclasses
import math

import numpy as np
from pydrake.math import RotationMatrix

from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger
from tegrasp_drake.rig.arm_kinematics import R_WG_SIDE_GRASP

# The corrective action each transition starts (trial results name them).
CORRECTIVE_ACTIONS = {(Mode.REACH, Mode.RE_REACH): "re_reach",
                      (Mode.LOAD, Mode.RE_REACH): "re_reach",
                      (Mode.LIFT, Mode.LOAD): "lift_load",
                      (Mode.HOLD, Mode.AVOID): "avoid"}
# The pads' frames in G: each pad's z axis points at the other finger.
R_G_PAD = (RotationMatrix.MakeXRotation(math.pi / 2),  # left pad
           RotationMatrix.MakeXRotation(-math.pi / 2))  # right pad


@dataclasses.dataclass(frozen=True)
class Counters:
    """How many Re-Reach, Lift-Load and Avoid corrections the grasp has made."""
    re_reaches: int = 0
    lift_loads: int = 0
    avoids: int = 0
    regrasps: int = 0  # the taxel_aware controller's re-grasps of a tilted object


# The taxel_aware actions these transitions start when a corrective trigger takes them.
CORRECTIVE_ONLY_ACTIONS = {(Mode.HOLD, Mode.PLACE): "regrasp",
                           (Mode.REACH, Mode.LOAD): "load_without_event"}


def corrective_action_of(from_mode: Mode, to_mode: Mode,
                         trigger: Trigger | None = None) -> str | None:
    """The corrective action from_mode -> to_mode starts (taxel_aware's by `trigger`), or None."""
    action = CORRECTIVE_ACTIONS.get((from_mode, to_mode))
    if action is None and trigger == Trigger.CORRECTIVE:
        action = CORRECTIVE_ONLY_ACTIONS.get((from_mode, to_mode))
    return action


# ---- Re-Reach -------------------------------------------------------------------------


def re_reach_shift(sa_n, opening_m: float, object_width_m: float,
                   contact_force_n: float) -> float:
    """The shift [m, world y] that centres the gripper on the object: toward the finger
    touching alone by (opening_m - object_width_m) / 2, never negative; 0 unless one touches."""
    contact = np.asarray(sa_n)[:2] > contact_force_n
    if contact[0] == contact[1]:
        return 0.0
    half_gap = (opening_m - object_width_m) / 2.0
    sign = 1.0 if contact[0] else -1.0
    return sign * max(half_gap, 0.0)


def re_reach_target(p_WG, shift_m: float) -> np.ndarray:
    """p_WG [m, world] shifted by shift_m along world y."""
    return p_WG + np.array([0.0, shift_m, 0.0])


def approach_retreat_target(p_WG, retreat_m: float, *, start_xyz, grasp_xyz) -> np.ndarray:
    """p_WG [m, world] moved back along the Reach's path (grasp_xyz to start_xyz) by retreat_m
    [m], never past the start pose along it: the Reach's own motion reversed, which takes a
    finger off whatever that motion pressed it into, an object's top as well as a face in
    front (docs/controller.md, "Finger strike"), and keeps the arm on the segment it can reach."""
    toward_start = np.subtract(start_xyz, grasp_xyz, dtype=float)
    u = toward_start / np.linalg.norm(toward_start)
    room_m = float(np.dot(np.subtract(start_xyz, p_WG, dtype=float), u))
    return np.asarray(p_WG, dtype=float) + min(retreat_m, max(room_m, 0.0)) * u


# ---- Lift-Load ------------------------------------------------------------------------


def _lift_load_for_slip(counters: Counters, config: GraspControllerConfig, trigger: Trigger,
                        reason: str) -> Decision:
    if counters.lift_loads >= config.lift_load.max_lift_loads:
        return Decision(Mode.FAILED, trigger,
                        f"the object still slips after {counters.lift_loads} Lift-Load "
                        "corrections")
    return Decision(Mode.LOAD, trigger, reason)


def lift_load_or_fail(slip_s: float, counters: Counters,
                      config: GraspControllerConfig) -> Decision | None:
    """In Lift: Load after slip_s [s] of slip (Failed once max_lift_loads are used), else None."""
    if not (config.lift_load.enabled and slip_s >= config.lift_load.slip_s):
        return None
    return _lift_load_for_slip(counters, config, Trigger.CORRECTIVE,
                               "slip during Lift (Lift-Load)")


def lift_load_on_slip_event(slip_event: bool, counters: Counters,
                            config: GraspControllerConfig) -> Decision | None:
    """In Lift: Load on the memorized slip event (Failed after max_lift_loads), else None."""
    if not (config.lift_load.enabled and slip_event):
        return None
    return _lift_load_for_slip(counters, config, Trigger.CORRECTIVE_EVENT,
                               "memorized slip event during Lift (Lift-Load)")


def lift_load_grip_force(grip_force_n: float, config: GraspControllerConfig) -> float:
    """The grip force [N] after a slip: force_factor times grip_force_n, capped."""
    return min(grip_force_n * config.lift_load.force_factor, config.lift_load.max_grip_force_n)


def relift_after_lift_load(*, grip_reached: bool, slip_quiet: bool, time_in_load_s: float,
                           counters: Counters,
                           config: GraspControllerConfig) -> Decision | None:
    """In Load after a Lift-Load: Lift once the raised grip is reached, the slip band is
    quiet and relift_settle_s [s] have passed; None otherwise and in the first Load."""
    if (counters.lift_loads and grip_reached and slip_quiet
            and time_in_load_s >= config.lift_load.relift_settle_s):
        return Decision(Mode.LIFT, Trigger.CORRECTIVE, "raised grip force reached (Lift-Load)")
    return None


# ---- Avoid ----------------------------------------------------------------------------


def is_hit(ra_mps2, time_in_hold_s: float, config: GraspControllerConfig,
           level_mps2=0.0) -> bool:
    """In Hold: a film's RA [m/s^2] (one value or one per film) above hit_ra_mps2 over its
    level_mps2 (ra_level of the Hold's ticks before; 0: the number alone), from
    hit_refractory_s [s] in Hold on."""
    avoid = config.avoid
    rise = np.asarray(ra_mps2, dtype=float) - np.asarray(level_mps2, dtype=float)
    return time_in_hold_s >= avoid.hit_refractory_s and bool(np.any(rise > avoid.hit_ra_mps2))


def ra_history(history: tuple, ra_mps2, level_s: float, period_s: float) -> tuple:
    """`history` of the films' RA [m/s^2] at the Hold's ticks plus this tick's ra_mps2, kept
    to level_s [s] of ticks of period_s [s]; () when level_s is 0 (no level)."""
    keep = round(level_s / period_s)
    if keep <= 0:
        return ()
    return (history + (tuple(float(x) for x in ra_mps2),))[-keep:]


def ra_level(history: tuple, films: int = 2) -> tuple:
    """Each film's RA level [m/s^2]: its mean over `history` (ra_history); 0 with none."""
    if not history:
        return (0.0,) * films
    return tuple(float(x) for x in np.mean(np.asarray(history, dtype=float), axis=0))


def avoiding(counters: Counters, config: GraspControllerConfig) -> bool:
    """Whether a hit in Hold is avoided: Avoid is on and fewer than avoid.max_avoids made."""
    return config.avoid.enabled and counters.avoids < config.avoid.max_avoids


def avoid_on_hit(hit: bool, counters: Counters,
                 config: GraspControllerConfig) -> Decision | None:
    """In Hold: Avoid a hit (is_hit) while `avoiding`; None otherwise."""
    if hit and avoiding(counters, config):
        return Decision(Mode.AVOID, Trigger.THRESHOLD, "hit: RA above the hit threshold")
    return None


def avoid_on_hit_event(hit_event: bool, time_in_hold_s: float, counters: Counters,
                       config: GraspControllerConfig) -> Decision | None:
    """In Hold: Avoid on the memorized hit event from hit_armed_s [s] in Hold on while
    `avoiding`, else None."""
    if (avoiding(counters, config) and hit_event
            and time_in_hold_s >= config.memorized_corrective.hit_armed_s):
        return Decision(Mode.AVOID, Trigger.CORRECTIVE_EVENT, "memorized hit event in Hold")
    return None


def hit_baseline_history(history: tuple, sa_n, baseline_s: float,
                         period_s: float) -> tuple:
    """`history` of (left, right) SA [N] plus sa_n, kept to baseline_s [s]; first: the baseline."""
    keep = max(1, round(baseline_s / period_s)) + 1
    return (history + (tuple(float(x) for x in sa_n[:2]),))[-keep:]


def pad_accelerations_in_world(pad_acceleration: np.ndarray) -> np.ndarray:
    """(2, 3) the pads' accelerations [m/s^2] in world, for the side grasp."""
    a = np.asarray(pad_acceleration).reshape(2, 3)
    return np.array([(R_WG_SIDE_GRASP @ R_G_PAD[k]).matrix() @ a[k] for k in range(2)])


def avoid_direction(delta_sa, acceleration_sum_W, sa_asymmetry_n: float) -> np.ndarray:
    """Unit world direction away from a hit: along the stroke toward the pad whose SA gained more
    (delta_sa, (left, right) [N]) when the gains differ by more than sa_asymmetry_n; else the
    horizontal part of acceleration_sum_W (the pads' common motion); else straight up."""
    difference = float(delta_sa[0] - delta_sa[1])
    if abs(difference) > sa_asymmetry_n:
        return np.array([0.0, math.copysign(1.0, difference), 0.0])
    a = np.asarray(acceleration_sum_W, dtype=float)
    horizontal = np.array([a[0], a[1], 0.0])
    norm = np.linalg.norm(horizontal)
    return horizontal / norm if norm > 1e-6 else np.array([0.0, 0.0, 1.0])


@dataclasses.dataclass(frozen=True)
class AvoidMove:
    """Where Avoid moves the grasp frame origin, and the sensing it is based on."""
    delta_sa_n: np.ndarray  # (left, right) mean SA gain over the sensing time [N]
    direction_W: np.ndarray  # unit direction, world (avoid_direction)
    p_end_W: np.ndarray  # the end of the move [m, world]


def avoid_move(p_WG, sa_gain_sum_n, acceleration_sum_W,
               config: GraspControllerConfig) -> AvoidMove:
    """The Avoid move from p_WG [m, world]: avoid.distance_m along avoid_direction of the mean SA
    gain (sa_gain_sum_n [N] and acceleration_sum_W [m/s^2], summed over the sensing ticks)."""
    ticks = max(1, round(config.avoid.sense_s / config.update_period_s))
    delta_sa = np.asarray(sa_gain_sum_n) / ticks
    direction = avoid_direction(delta_sa, acceleration_sum_W, config.avoid.sa_asymmetry_n)
    return AvoidMove(delta_sa_n=delta_sa, direction_W=direction,
                     p_end_W=p_WG + config.avoid.distance_m * direction)
