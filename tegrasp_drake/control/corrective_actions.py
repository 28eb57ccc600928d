"""The corrective actions (Sec. III-C): Re-Reach, Lift-Load and Avoid, each as a decision
(take it, or give up) and an action (where to move, how hard to grip), in pure functions.

The rules of the rule tables (transition_logic.py) call the decisions (Re-Reach's is
rule_actions.re_reach_or_fail, shared by every table); the GraspStateMachine
(grasp_state_machine.py) calls the actions when it enters the mode. The thresholds and
distances come from the GraspControllerConfig's sections (controller_config.py).

Frames: world W; the grasp frame G at the side-grasp orientation (arm_kinematics.py)
approaches along world +x with the finger stroke along world y, the left finger on the +y
side; each pad's frame has its z axis, the pad normal, pointing at the other finger.

  Re-Reach   one finger alone touched (or none, or no event in time): open, shift along
             world y toward the touching finger by half the gap between the opening and
             the object's width, and reach again (at most re_reach.max_re_reaches times)
  Lift-Load  the object slips during Lift: back to Load at lift_load.force_factor times
             the grip force, and lift again once both SA reach it (at most
             lift_load.max_lift_loads)
  Avoid      a hit in Hold: stop, sense which way the hit pushed, move avoid.distance_m
             that way

Lift-Load's and Avoid's triggers are the heuristic thresholds (lift_load_or_fail,
avoid_on_hit) or, for the events named in controller.memorized_corrective.events, the
memorized corrective events matched by Eq. 3 (lift_load_on_slip_event, avoid_on_hit_event).
"""

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
# The pads' frames in the grasp frame G (the fingers are parallel to the gripper base, which
# is G's orientation): each pad's z axis, its normal, points at the other finger.
R_G_PAD = (RotationMatrix.MakeXRotation(math.pi / 2),  # left pad
           RotationMatrix.MakeXRotation(-math.pi / 2))  # right pad


@dataclasses.dataclass(frozen=True)
class Counters:
    """How many Re-Reach and Lift-Load corrections the grasp has made."""
    re_reaches: int = 0
    lift_loads: int = 0
    regrasps: int = 0  # the taxel_aware controller's re-grasps of a tilted object


# Taken by a corrective trigger, these transitions start the taxel_aware controller's
# actions (control/taxel_aware); by their usual trigger they start none.
CORRECTIVE_ONLY_ACTIONS = {(Mode.HOLD, Mode.PLACE): "regrasp",
                           (Mode.REACH, Mode.LOAD): "load_without_event"}


def corrective_action_of(from_mode: Mode, to_mode: Mode,
                         trigger: Trigger | None = None) -> str | None:
    """The corrective action ("re_reach", "lift_load", "avoid"; with a corrective
    `trigger` also "regrasp", "load_without_event") that the transition from_mode ->
    to_mode starts; None for any other transition (a corrective Load -> Lift, after a
    Lift-Load's re-load or the taxel_aware Load timeout, is no action of its own)."""
    action = CORRECTIVE_ACTIONS.get((from_mode, to_mode))
    if action is None and trigger == Trigger.CORRECTIVE:
        action = CORRECTIVE_ONLY_ACTIONS.get((from_mode, to_mode))
    return action


# ---- Re-Reach -------------------------------------------------------------------------


def re_reach_shift(sa_n, opening_m: float, object_width_m: float,
                   contact_force_n: float) -> float:
    """The shift [m, along world y] that centres the gripper on the object: the finger
    still touching it marks its near face, half the object's width from its centre.

    sa_n: (left, right) SA [N] (more entries are ignored); a finger touches above
    contact_force_n [N]. opening_m: the gripper's opening [m] where it stopped;
    object_width_m: the object's width along the stroke [m]. Toward the touching finger
    (the left finger is on +y) by (opening - width) / 2, never negative; 0 when both or
    neither finger touch.
    """
    contact = np.asarray(sa_n)[:2] > contact_force_n
    if contact[0] == contact[1]:
        return 0.0
    half_gap = (opening_m - object_width_m) / 2.0
    sign = 1.0 if contact[0] else -1.0
    return sign * max(half_gap, 0.0)


def re_reach_target(p_WG, shift_m: float) -> np.ndarray:
    """Where the open gripper moves to [m, world]: the grasp frame origin p_WG shifted by
    shift_m along world y (re_reach_shift)."""
    return p_WG + np.array([0.0, shift_m, 0.0])


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
    """In Lift: back to Load when the object has slipped for lift_load.slip_s [s]
    (slip-band vibration above lift_load.slip_vibration_mps2) and Lift-Load is on; Failed
    once lift_load.max_lift_loads are used up; None to go on lifting."""
    if not (config.lift_load.enabled and slip_s >= config.lift_load.slip_s):
        return None
    return _lift_load_for_slip(counters, config, Trigger.CORRECTIVE,
                               "slip during Lift (Lift-Load)")


def lift_load_on_slip_event(slip_event: bool, counters: Counters,
                            config: GraspControllerConfig) -> Decision | None:
    """In Lift, with memorized corrective triggers: back to Load when the memorized slip
    event (lift_load) matches and Lift-Load is on; Failed once lift_load.max_lift_loads
    are used up; None to go on lifting."""
    if not (config.lift_load.enabled and slip_event):
        return None
    return _lift_load_for_slip(counters, config, Trigger.CORRECTIVE_EVENT,
                               "memorized slip event during Lift (Lift-Load)")


def lift_load_grip_force(grip_force_n: float, config: GraspControllerConfig) -> float:
    """The grip force [N] of the Load after a slip: grip_force_n times
    lift_load.force_factor, at most lift_load.max_grip_force_n (the 2F-85's largest)."""
    return min(grip_force_n * config.lift_load.force_factor, config.lift_load.max_grip_force_n)


def relift_after_lift_load(*, grip_reached: bool, slip_quiet: bool, time_in_load_s: float,
                           counters: Counters,
                           config: GraspControllerConfig) -> Decision | None:
    """In Load after a Lift-Load: lift again once both SA reach the raised grip force
    (grip_reached), the slip band is quiet (the slip has stopped) and
    lift_load.relift_settle_s [s] have passed in Load; None otherwise, and always in the
    first Load (it waits for its memorized event: those describe the ideal grasp, not a
    re-load)."""
    if (counters.lift_loads and grip_reached and slip_quiet
            and time_in_load_s >= config.lift_load.relift_settle_s):
        return Decision(Mode.LIFT, Trigger.CORRECTIVE, "raised grip force reached (Lift-Load)")
    return None


# ---- Avoid ----------------------------------------------------------------------------


def is_hit(ra_mps2: float, time_in_hold_s: float, config: GraspControllerConfig) -> bool:
    """In Hold: the larger RA [m/s^2] above avoid.hit_ra_mps2, avoid.hit_refractory_s [s] or
    more after entering Hold (the stop of the lift rings briefly)."""
    avoid = config.avoid
    return time_in_hold_s >= avoid.hit_refractory_s and ra_mps2 > avoid.hit_ra_mps2


def avoid_on_hit(hit: bool, config: GraspControllerConfig) -> Decision | None:
    """In Hold: Avoid a hit (is_hit) when Avoid is on; None otherwise."""
    if config.avoid.enabled and hit:
        return Decision(Mode.AVOID, Trigger.THRESHOLD, "hit: RA above the hit threshold")
    return None


def avoid_on_hit_event(hit_event: bool, time_in_hold_s: float,
                       config: GraspControllerConfig) -> Decision | None:
    """In Hold, with memorized corrective triggers: Avoid when the memorized hit event
    (hold_avoid) matches memorized_corrective.hit_armed_s [s] or more after entering Hold
    (the stop of the lift or of an Avoid rings briefly, and stays in the matcher's window)
    and Avoid is on; None otherwise."""
    if (config.avoid.enabled and hit_event
            and time_in_hold_s >= config.memorized_corrective.hit_armed_s):
        return Decision(Mode.AVOID, Trigger.CORRECTIVE_EVENT, "memorized hit event in Hold")
    return None


def hit_baseline_history(history: tuple, sa_n, baseline_s: float,
                         period_s: float) -> tuple:
    """The Hold ticks' (left, right) SA [N] kept for a memorized hit's baseline: `history`
    with sa_n appended, the last round(baseline_s / period_s) + 1 ticks; its first entry
    is the SA baseline_s [s] ago (or the oldest since Hold began)."""
    keep = max(1, round(baseline_s / period_s)) + 1
    return (history + (tuple(float(x) for x in sa_n[:2]),))[-keep:]


def pad_accelerations_in_world(pad_acceleration: np.ndarray) -> np.ndarray:
    """(2, 3) the left and right pad accelerations [m/s^2] rotated from the pad frames into
    world, for the side grasp."""
    a = np.asarray(pad_acceleration).reshape(2, 3)
    return np.array([(R_WG_SIDE_GRASP @ R_G_PAD[k]).matrix() @ a[k] for k in range(2)])


def avoid_direction(delta_sa, acceleration_sum_W, sa_asymmetry_n: float) -> np.ndarray:
    """Unit world direction to move away from a hit.

    delta_sa: the (left, right) SA change [N] since just before the hit; the pad the object
    was pushed into gains: along the stroke (world y, the left finger on +y) when the gain
    differs by more than sa_asymmetry_n. Otherwise the horizontal part of
    acceleration_sum_W (the pads' accelerations in world, summed over the sensing time: the
    common motion of object and gripper); straight up when that is negligible too.
    """
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
    """The Avoid move from p_WG [m, world] after sensing for avoid.sense_s [s].

    sa_gain_sum_n: the (left, right) SA gain over the last Hold tick [N], summed over the
    sensing ticks (update_period_s apart); acceleration_sum_W: the pads' world
    accelerations [m/s^2] summed over those ticks. Moves avoid.distance_m [m] along
    avoid_direction of the mean gain.
    """
    ticks = max(1, round(config.avoid.sense_s / config.update_period_s))
    delta_sa = np.asarray(sa_gain_sum_n) / ticks
    direction = avoid_direction(delta_sa, acceleration_sum_W, config.avoid.sa_asymmetry_n)
    return AvoidMove(delta_sa_n=delta_sa, direction_W=direction,
                     p_end_W=p_WG + config.avoid.distance_m * direction)
