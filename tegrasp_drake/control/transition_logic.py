"""The grasp state machine's transition rule as a pure function (Sec. II-B, III-C, Fig. 6).

`next_mode(mode, observation, counters, config)` says which mode comes next and why, from a
summary of what the machine observes; it keeps no state and has no side effects, so it is
tested exhaustively. The LeafSystem (grasp_state_machine.py) builds the observation each
tick and carries out the motion of each mode.

  Reach    -> Load       the Reach-Load event                    (memorized/heuristic event)
  Reach    -> Re-Reach   one finger alone in contact, closed on nothing, or no event in time
  Re-Reach -> Reach      the gripper is open and re-centred      (corrective)
  Load     -> Lift       the Load-Lift event                     (memorized/heuristic event)
  Load     -> Lift       after a Lift-Load: both SA at the raised grip force, RA quiet,
                         relift_settle_s in Load (corrective; the memorized events describe
                         the ideal grasp, not a re-load)
  Load     -> Re-Reach   no Load-Lift event in time (first load only)
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
  any      -> Failed     a device fault, the object lost (no pad contact), or corrections
                         used up
A corrective action whose retries are used up goes to Failed with the reason; those
decisions (take the action, or give up) are in corrective_actions.py.

The taxel_aware controller keeps these rules and adds its own, as a rule table
(control/taxel_aware/table.py) over the same Observation and its ContactEstimate.
"""

import dataclasses

from tegrasp_drake.control.corrective_actions import (
    Counters, avoid_on_hit, avoid_on_hit_event, lift_load_on_slip_event, lift_load_or_fail,
    re_reach_or_fail, relift_after_lift_load)
from tegrasp_drake.control.grasp_modes import (HOLDING_MODES, TERMINAL_MODES, Decision, Mode,
                                               Trigger)


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
    # Whether the Place is a re-grasp's (taxel_aware), and what the taxel_aware
    # controller's ContactEstimator sensed this tick (taxel_aware/estimator.py; None for
    # the other controllers).
    regrasp_pending: bool = False
    estimate: object | None = None


def _reach(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
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
    if obs.event_matched:
        return Decision(Mode.LIFT, event_trigger, "Load-Lift event")
    relift = relift_after_lift_load(grip_reached=obs.grip_reached, slip_quiet=obs.slip_quiet,
                                    time_in_load_s=obs.time_in_mode, counters=counters,
                                    config=config)
    if relift is not None:
        return relift
    if obs.time_in_mode >= config.load_event_timeout_s:
        reason = f"no Load-Lift event within {config.load_event_timeout_s:g} s"
        if counters.lift_loads:
            return Decision(Mode.FAILED, Trigger.CORRECTIVE, f"{reason} after Lift-Load")
        return re_reach_or_fail(counters, config, reason)
    return None


def memorized_corrective_trigger(config, transition: str) -> bool:
    """True when the corrective `transition` (lift_load, hold_avoid) is triggered by its
    memorized corrective event (controller.memorized_corrective_events)."""
    return transition in getattr(config, "memorized_corrective_events", ())


def _lift(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if memorized_corrective_trigger(config, "lift_load"):
        lift_load = lift_load_on_slip_event(obs.corrective_event_matched, counters, config)
    else:
        lift_load = lift_load_or_fail(obs.slip_s, counters, config)
    if lift_load is not None:
        return lift_load
    if obs.motion_done:
        return Decision(Mode.HOLD, Trigger.TIMER, "lift motion ended")
    return None


def hold_avoid(obs: Observation, counters: Counters, config, event_trigger: Trigger,
               hold_s: float) -> Decision | None:
    """In Hold: Avoid a hit, from the heuristic threshold or the memorized hit event."""
    if memorized_corrective_trigger(config, "hold_avoid"):
        return avoid_on_hit_event(obs.corrective_event_matched, obs.time_in_mode, config)
    return avoid_on_hit(obs.hit, config)


def hold_time(obs: Observation, counters: Counters, config, event_trigger: Trigger,
              hold_s: float) -> Decision | None:
    """In Hold: Place after hold_s [s]."""
    if obs.time_in_mode >= hold_s:
        return Decision(Mode.PLACE, Trigger.TIMER, f"held {hold_s:g} s")
    return None


def _hold(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    return (hold_avoid(obs, counters, config, event_trigger, hold_s)
            or hold_time(obs, counters, config, event_trigger, hold_s))


def _avoid(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.motion_done:
        return Decision(Mode.HOLD, Trigger.TIMER, "avoiding motion ended")
    return None


def _place(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.event_matched:
        return Decision(Mode.UNLOAD, event_trigger, "Place-Unload event")
    if placed(obs, config):
        return Decision(Mode.UNLOAD, Trigger.TIMER, "no Place-Unload event after the arm stopped")
    return None


def placed(obs: Observation, config) -> bool:
    """In Place: the object stands on the table (the Place-Unload event, or
    place_event_timeout_s [s] after the arm stopped)."""
    return obs.event_matched or (obs.motion_done and obs.time_since_motion_done
                                 >= config.place_event_timeout_s)


def _re_reach(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.motion_done:
        return Decision(Mode.REACH, Trigger.CORRECTIVE, "re-centred")
    return None


def _unload(obs: Observation, counters: Counters, config, event_trigger: Trigger, hold_s: float):
    if obs.motion_done:
        return Decision(Mode.DONE, Trigger.TIMER, "released and retracted")
    return None


PAPER_RULES = {Mode.REACH: _reach, Mode.RE_REACH: _re_reach, Mode.LOAD: _load,
               Mode.LIFT: _lift, Mode.HOLD: _hold, Mode.AVOID: _avoid, Mode.PLACE: _place,
               Mode.UNLOAD: _unload}


def device_failure(obs: Observation) -> Decision | None:
    """Failed on a device fault (a watchdog's, or the gripper's)."""
    if obs.device_fault:
        return Decision(Mode.FAILED, Trigger.FAULT, obs.device_fault)
    if obs.gripper_fault:
        return Decision(Mode.FAILED, Trigger.FAULT, f"gripper fault {obs.gripper_fault}")
    return None


def object_lost(mode: Mode, obs: Observation, config) -> Decision | None:
    """Failed when, holding the object, no finger touches it."""
    if config.drop_check_enabled and mode in HOLDING_MODES and not any(obs.contact):
        return Decision(Mode.FAILED, Trigger.THRESHOLD, "object lost: no finger in contact")
    return None


def next_mode(mode: Mode, obs: Observation, counters: Counters, config, *,
              event_trigger: Trigger, hold_s: float) -> Decision | None:
    """The transition out of `mode` this tick, or None to stay.

    config: a GraspControllerConfig; event_trigger: the trigger name of this controller's
    event detector (memorized or heuristic); hold_s: how long to hold [s] (the paper: 3 s).
    """
    if mode in TERMINAL_MODES:
        return None
    return (device_failure(obs) or object_lost(mode, obs, config)
            or PAPER_RULES[mode](obs, counters, config, event_trigger, hold_s))
