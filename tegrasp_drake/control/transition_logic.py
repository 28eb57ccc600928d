"""The grasp state machine's transition rule as a pure function (Sec. II-B, III-C, Fig. 6).

`next_mode(mode, observation, counters, config)` says which mode comes next and why, from a
summary of what the machine observes; it keeps no state and has no side effects, so it is
tested exhaustively. The LeafSystem (grasp_state_machine.py) builds the observation each
tick and carries out the motion of each mode.

  Reach    -> Load       the Reach-Load event                    (memorized/heuristic event)
  Reach    -> Re-Reach   one finger alone in contact, closed on nothing, or no event in time
                         (taxel_aware: also a finger striking the object during the approach,
                         from the joint torques: finger_strike.py; and the close's first
                         touch on one pad's distal row alone when the close would push
                         the object over: taxel_corrections.touched_beyond_pads)
  Re-Reach -> Reach      the gripper is open and re-centred      (corrective)
  Load     -> Lift       the Load-Lift event                     (memorized/heuristic event)
  Load     -> Lift       after a Lift-Load: both SA at the raised grip force, RA quiet,
                         relift_settle_s in Load (corrective; the memorized events describe
                         the ideal grasp, not a re-load)
  Load     -> Re-Reach   no Load-Lift event in time (first load only); taxel_aware: the
                         close's first touch, seen after the Reach-Load event, came on one
                         pad's distal row alone (taxel_corrections.touched_beyond_pads)
  Lift     -> Load       the object slips (Lift-Load)            (corrective; or the
                         memorized slip event: corrective_event)
  Lift     -> Hold       the lift motion ended                   (timer)
  Hold     -> Avoid      a hit: RA above the hit threshold       (threshold; or the
                         memorized hit event: corrective_event)
  Hold     -> Place      hold_s in Hold                          (timer)
  Avoid    -> Hold       the avoiding motion ended               (timer)
  Place    -> Unload     the Place-Unload event                  (memorized/heuristic event)
  Place    -> Unload     no event place_event_timeout_s after the arm stopped (timer)
  Unload   -> Done       the gripper is open and the arm retracted (timer)
  any      -> Failed     a device fault, the object lost (no pad contact, and not caged
                         behind the pads), or corrections used up
A corrective action whose retries are used up goes to Failed with the reason; those
decisions (take the action, or give up) are in corrective_actions.py.

The taxel_aware controller (issue #14) changes Reach, Load, Hold and Place with the
decisions of taxel_corrections.py: Re-Reach along both axes until centred, Load on
one-sided contact at the object's width (or at the extent between the faces that the two
fingers touched alone in turn) or with both pads on the object after the event timeout,
Lift after the Load timeout with both pads on, and a re-grasp of an object held tilted
(Hold -> Place -> Re-Reach -> Reach ...).
"""

import dataclasses

from tegrasp_drake.control.corrective_actions import (
    Counters, avoid_on_hit, avoid_on_hit_event, lift_load_on_slip_event, lift_load_or_fail,
    re_reach_or_fail, relift_after_lift_load)
from tegrasp_drake.control.finger_strike import finger_strike_response
from tegrasp_drake.control.grasp_modes import TERMINAL_MODES, Decision, Mode, Trigger
from tegrasp_drake.control.taxel_contact import GraspContact
from tegrasp_drake.control.taxel_corrections import (
    after_regrasp_place, approach_contact_response, beyond_pads_response, on_reach_event,
    on_reach_timeout, one_sided_response, regrasp_or_none)

TAXEL_AWARE = "taxel_aware"

HOLDING_MODES = (Mode.LIFT, Mode.HOLD, Mode.AVOID, Mode.PLACE)


@dataclasses.dataclass(frozen=True)
class Observation:
    """What the machine sees in one tick. Durations in seconds."""
    time_in_mode: float = 0.0
    event_matched: bool = False  # the detector reports the expected event now
    motion_done: bool = False  # the mode's arm motion (and gripper stage) has finished
    time_since_motion_done: float = 0.0
    closing_s: float = -1.0  # time since the gripper was told to close; -1 if not closing
    contact: tuple = (False, False)  # (left, right) SA above the contact force
    one_sided_s: float = 0.0  # how long exactly one finger has been in contact
    closed_on_nothing: bool = False  # at the closed request with no object (gOBJ 3)
    grip_reached: bool = False  # both SA at grip_fraction of the requested grip force
    slip_quiet: bool = True  # both slip-band vibrations below the slip threshold
    slip_s: float = 0.0  # how long either RA has been above the slip threshold
    hit: bool = False  # either RA above the hit threshold (after the refractory time)
    # The corrective EventMatcher matches the mode's memorized corrective event (slip in
    # Lift, a hit in Hold); read for the events in controller.memorized_corrective_events.
    corrective_event_matched: bool = False
    gripper_fault: str = ""  # the 2F-85 fault's name, "" for none
    device_fault: str = ""  # a watchdog's message, "" for none
    # The taxel_aware controller's: the gripper's opening and the object's width along the
    # stroke [m], the contact's shape on the pads (None: not read), how long the object
    # has sat tilted in Hold [s], and whether the Place is a re-grasp's.
    opening_m: float = 0.0
    object_width_m: float = 0.0
    contact_shape: GraspContact | None = None
    tilted_s: float = 0.0
    regrasp_pending: bool = False
    approach_contact_s: float = 0.0  # a pad in contact while the approach moves [s]
    # The finger-strike sense (taxel_aware, finger_strike.py): how long the force on the
    # wrist has exceeded the strike threshold during the approach [s], that force [N], and
    # the struck finger ("left", "right", "" unknown).
    strike_s: float = 0.0
    strike_force_n: float = 0.0
    strike_finger: str = ""
    # The close pushed the object far enough that opening would let it fall over
    # (taxel_corrections.release_topples).
    topples_if_released: bool = False
    # The closed fingers hold the object behind the pads, against the palm
    # (taxel_corrections.caged_behind_pads): no pad touches it, so no event comes.
    caged_behind_pads: bool = False
    # The close's first touch came on one pad's distal row alone and the close would push
    # the object past its tipping limit (taxel_corrections.touched_beyond_pads), and which
    # pad that was ("left", "right").
    touched_beyond_pads: bool = False
    first_touch_finger: str = ""
    # One finger touches alone while closing, and the other touched at an earlier close:
    # the object's extent between the two faces [m] (taxel_corrections.bracketed_object;
    # 0: no such pair).
    bracketed_width_m: float = 0.0


def _taxel_aware(config) -> bool:
    return getattr(config, "name", "") == TAXEL_AWARE


def _reach_taxel_aware(obs: Observation, counters: Counters, config, event_trigger: Trigger):
    strike = config.taxel_aware.finger_strike
    if strike.enabled and obs.strike_s >= strike.sustain_s:
        return finger_strike_response(finger=obs.strike_finger or None,
                                      force_n=obs.strike_force_n,
                                      re_reaches=counters.re_reaches, config=config)
    if obs.approach_contact_s >= config.one_sided_contact_s:
        return approach_contact_response(contact=obs.contact, re_reaches=counters.re_reaches,
                                         config=config)
    if obs.touched_beyond_pads:
        beyond = beyond_pads_response(finger=obs.first_touch_finger,
                                      re_reaches=counters.re_reaches, config=config)
        if beyond is not None:
            return beyond
    if obs.event_matched:
        centre_first = (on_reach_event(obs.contact_shape, re_reaches=counters.re_reaches,
                                       config=config,
                                       topples_if_released=obs.topples_if_released)
                        if obs.contact_shape is not None else None)
        return centre_first or Decision(Mode.LOAD, event_trigger, "Reach-Load event")
    if obs.one_sided_s >= config.one_sided_contact_s:
        return one_sided_response(finger="left" if obs.contact[0] else "right",
                                  opening_m=obs.opening_m, object_width_m=obs.object_width_m,
                                  re_reaches=counters.re_reaches, config=config,
                                  bracketed_width_m=obs.bracketed_width_m)
    if obs.closed_on_nothing:
        return on_reach_timeout(both_touch=False, re_reaches=counters.re_reaches,
                                config=config, reason="the gripper closed on nothing")
    if obs.closing_s >= config.reach_event_timeout_s:
        return on_reach_timeout(
            both_touch=all(obs.contact), re_reaches=counters.re_reaches, config=config,
            reason=f"no Reach-Load event {config.reach_event_timeout_s:g} s after closing",
            caged=obs.caged_behind_pads)
    return None


def _reach(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if _taxel_aware(config):
        return _reach_taxel_aware(obs, counters, config, event_trigger)
    if obs.event_matched:
        return Decision(Mode.LOAD, event_trigger, "Reach-Load event")
    if obs.one_sided_s >= config.one_sided_contact_s:
        finger = "left" if obs.contact[0] else "right"
        return re_reach_or_fail(counters, config, f"only the {finger} finger touched")
    if obs.closed_on_nothing:
        return re_reach_or_fail(counters, config, "the gripper closed on nothing")
    if obs.closing_s >= config.reach_event_timeout_s:
        return re_reach_or_fail(
            counters, config, f"no Reach-Load event {config.reach_event_timeout_s:g} s after "
            "closing")
    return None


def _load(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if _taxel_aware(config) and obs.touched_beyond_pads:  # the event came before the taxels
        beyond = beyond_pads_response(finger=obs.first_touch_finger,
                                      re_reaches=counters.re_reaches, config=config)
        if beyond is not None:
            return beyond
    if obs.event_matched:
        return Decision(Mode.LIFT, event_trigger, "Load-Lift event")
    relift = relift_after_lift_load(grip_reached=obs.grip_reached, slip_quiet=obs.slip_quiet,
                                    time_in_load_s=obs.time_in_mode, counters=counters,
                                    config=config)
    if relift is not None:
        return relift
    if obs.time_in_mode >= config.load_event_timeout_s:
        reason = f"no Load-Lift event within {config.load_event_timeout_s:g} s"
        if _taxel_aware(config) and all(obs.contact):
            return Decision(Mode.LIFT, Trigger.CORRECTIVE, f"{reason}, both pads hold the "
                            "object: lift")
        if _taxel_aware(config) and obs.caged_behind_pads:
            return Decision(Mode.LIFT, Trigger.CORRECTIVE, f"{reason}, the fingers hold the "
                            "object behind the pads: lift")
        if counters.lift_loads:
            return Decision(Mode.FAILED, Trigger.CORRECTIVE, f"{reason} after Lift-Load")
        return re_reach_or_fail(counters, config, reason)
    return None


def memorized_corrective_trigger(config, transition: str) -> bool:
    """True when the corrective `transition` (lift_load, hold_avoid) is triggered by its
    memorized corrective event (controller.memorized_corrective_events)."""
    return transition in getattr(config, "memorized_corrective_events", ())


def _lift(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.caged_behind_pads:  # no pad touches it: squeezing harder cannot stop a slip
        return Decision(Mode.HOLD, Trigger.TIMER, "lift motion ended") if obs.motion_done \
            else None
    if memorized_corrective_trigger(config, "lift_load"):
        lift_load = lift_load_on_slip_event(obs.corrective_event_matched, counters, config)
    else:
        lift_load = lift_load_or_fail(obs.slip_s, counters, config)
    if lift_load is not None:
        return lift_load
    if obs.motion_done:
        return Decision(Mode.HOLD, Trigger.TIMER, "lift motion ended")
    return None


def _hold(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if memorized_corrective_trigger(config, "hold_avoid"):
        avoid = avoid_on_hit_event(obs.corrective_event_matched, obs.time_in_mode, config)
    else:
        avoid = avoid_on_hit(obs.hit, config)
    # A caged object touches no pad: the pads' RA reads it rattling against the fingers'
    # links, not a hit passed through a grasp contact (caged_behind_pads).
    if avoid is not None and not obs.caged_behind_pads:
        return avoid
    if _taxel_aware(config):
        regrasp = regrasp_or_none(tilted_s=obs.tilted_s, regrasps=counters.regrasps,
                                  taxel_config=config.taxel_aware)
        if regrasp is not None:
            return regrasp
    if obs.time_in_mode >= hold_s:
        return Decision(Mode.PLACE, Trigger.TIMER, f"held {hold_s:g} s")
    return None


def _avoid(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.motion_done:
        return Decision(Mode.HOLD, Trigger.TIMER, "avoiding motion ended")
    return None


def _place(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    placed = obs.event_matched or (obs.motion_done and obs.time_since_motion_done
                                   >= config.place_event_timeout_s)
    if placed:
        regrasp = after_regrasp_place(regrasp_pending=obs.regrasp_pending)
        if regrasp is not None:
            return regrasp
    if obs.event_matched:
        return Decision(Mode.UNLOAD, event_trigger, "Place-Unload event")
    if placed:
        return Decision(Mode.UNLOAD, Trigger.TIMER, "no Place-Unload event after the arm stopped")
    return None


def _re_reach(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.motion_done:
        return Decision(Mode.REACH, Trigger.CORRECTIVE, "re-centred")
    return None


def _unload(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.motion_done:
        return Decision(Mode.DONE, Trigger.TIMER, "released and retracted")
    return None


_RULES = {Mode.REACH: _reach, Mode.RE_REACH: _re_reach, Mode.LOAD: _load, Mode.LIFT: _lift,
          Mode.HOLD: _hold, Mode.AVOID: _avoid, Mode.PLACE: _place, Mode.UNLOAD: _unload}


def next_mode(mode: Mode, obs: Observation, counters: Counters, config, *,
              event_trigger: Trigger, hold_s: float) -> Decision | None:
    """The transition out of `mode` this tick, or None to stay.

    config: a GraspControllerConfig; event_trigger: the trigger name of this controller's
    event detector (memorized or heuristic); hold_s: how long to hold [s] (the paper: 3 s).
    """
    if mode in TERMINAL_MODES:
        return None
    if obs.device_fault:
        return Decision(Mode.FAILED, Trigger.FAULT, obs.device_fault)
    if obs.gripper_fault:
        return Decision(Mode.FAILED, Trigger.FAULT, f"gripper fault {obs.gripper_fault}")
    # A caged object (taxel_aware) touches no pad; it is lost when the fingers close to
    # their request, which ends caged_behind_pads.
    if (config.drop_check_enabled and mode in HOLDING_MODES and not any(obs.contact)
            and not obs.caged_behind_pads):
        return Decision(Mode.FAILED, Trigger.THRESHOLD, "object lost: no finger in contact")
    return _RULES[mode](obs, counters, config, event_trigger, hold_s)
