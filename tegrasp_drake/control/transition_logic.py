"""The paper's grasp state machine (Sec. II-B, III-C, Fig. 6b) as a rule table: the tick's
Observation and PAPER_TABLE, which other controllers' tables extend. Event transitions,
timed ones, the corrective actions (corrective_actions.py) and Failed. `python -m
tegrasp_drake.control.rule_docs` prints the table."""

import dataclasses
from collections.abc import Callable

from tegrasp_drake.control.corrective_actions import (
    avoid_on_hit, avoid_on_hit_event, lift_load_on_slip_event, lift_load_or_fail,
    relift_after_lift_load)
from tegrasp_drake.control.grasp_modes import HOLDING_MODES, Decision, Mode, Trigger, as_words
from tegrasp_drake.control.rule_actions import Failed, Lift, Load, decide
from tegrasp_drake.control.rule_engine import ReReachMove, Rule, RuleTable, Situation


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
    corrective_event_matched: bool = False
    gripper_fault: str = ""  # the 2F-85 fault's name, "" for none
    device_fault: str = ""  # a watchdog's message, "" for none
    # a re-grasp's Place, and the taxel_aware ContactEstimate (None for other controllers)
    regrasp_pending: bool = False
    estimate: object | None = None


def memorized_corrective_trigger(config, transition: str) -> bool:
    """Whether the corrective `transition` is triggered by its memorized event."""
    return transition in config.memorized_corrective.events


def placed(obs: Observation, config) -> bool:
    """In Place: the Place-Unload event, or its timeout."""
    return obs.event_matched or place_timed_out(obs, config)


def place_timed_out(obs: Observation, config) -> bool:
    """In Place: place.event_timeout_s [s] have passed since the arm stopped."""
    return obs.motion_done and obs.time_since_motion_done >= config.place.event_timeout_s


def touching_finger(s: Situation) -> str:
    """The finger in contact when one alone is ("left" or "right")."""
    return "left" if s.obs.contact[0] else "right"


def one_sided(s: Situation) -> bool:
    """One finger alone has touched for re_reach.one_sided_contact_s while closing."""
    return s.obs.one_sided_s >= s.config.re_reach.one_sided_contact_s


def reach_timed_out(s: Situation) -> bool:
    """No Reach-Load event re_reach.reach_event_timeout_s after closing."""
    return s.obs.closing_s >= s.config.re_reach.reach_event_timeout_s


def reach_timeout_reason(s: Situation) -> str:
    return f"no Reach-Load event {s.config.re_reach.reach_event_timeout_s:g} s after closing"


def load_timed_out(s: Situation) -> bool:
    """No Load-Lift event load_event_timeout_s in Load."""
    return s.obs.time_in_mode >= s.config.load_event_timeout_s


def load_timeout_reason(s: Situation) -> str:
    return f"no Load-Lift event within {s.config.load_event_timeout_s:g} s"


def _fault(s: Situation) -> Decision:
    return Decision(Mode.FAILED, Trigger.FAULT, as_words(s.obs.device_fault))


def _gripper_fault(s: Situation) -> Decision:
    return Decision(Mode.FAILED, Trigger.FAULT, as_words(f"gripper fault {s.obs.gripper_fault}"))


def _object_lost(s: Situation) -> bool:
    return (s.config.drop_check_enabled and s.mode in HOLDING_MODES
            and not any(s.obs.contact))


def _load_timeout(s: Situation) -> Decision:
    if s.counters.lift_loads:
        return decide(Failed(), Trigger.CORRECTIVE, f"{load_timeout_reason(s)} after Lift-Load")
    return s.re_reach_or_fail(load_timeout_reason(s), limit=s.config.re_reach.max_re_reaches)


def _relift(s: Situation) -> Decision | None:
    return relift_after_lift_load(grip_reached=s.obs.grip_reached, slip_quiet=s.obs.slip_quiet,
                                  time_in_load_s=s.obs.time_in_mode, counters=s.counters,
                                  config=s.config)


def _lift_load(s: Situation) -> Decision | None:
    if memorized_corrective_trigger(s.config, "lift_load"):
        return lift_load_on_slip_event(s.obs.corrective_event_matched, s.counters, s.config)
    return lift_load_or_fail(s.obs.slip_s, s.counters, s.config)


def _avoid(s: Situation) -> Decision | None:
    if memorized_corrective_trigger(s.config, "hold_avoid"):
        return avoid_on_hit_event(s.obs.corrective_event_matched, s.obs.time_in_mode,
                                  s.counters, s.config)
    return avoid_on_hit(s.obs.hit, s.counters, s.config)


def _decides(decision: Callable[[Situation], Decision | None]) -> Callable[[Situation], bool]:
    """The condition of a rule whose action is a corrective decision (None: none)."""
    return lambda s: decision(s) is not None


def _when_done(mode: Mode, trigger: Trigger, reason: str):
    """The action of a rule that ends a motion: `mode` by `trigger`, for `reason`."""
    return lambda s: Decision(mode, trigger, reason)


def _done(s: Situation) -> bool:
    """The mode's motion (and gripper stage) has ended."""
    return s.obs.motion_done


def _event(s: Situation) -> bool:
    """The detector matches the mode's expected event."""
    return s.obs.event_matched


# Priorities: every mode's rules first (1-3), then each mode's by 100s, room between.
PAPER_RULES = (
    # Any mode: the devices, the object.
    Rule("device_fault", None, 1, lambda s: bool(s.obs.device_fault), _fault,
         when="a watchdog reports a device fault", then="Failed (fault), its message"),
    Rule("gripper_fault", None, 2, lambda s: bool(s.obs.gripper_fault), _gripper_fault,
         when="the gripper reports a fault", then="Failed (fault)"),
    Rule("object_lost", None, 3, _object_lost,
         lambda s: Decision(Mode.FAILED, Trigger.THRESHOLD, "object lost: no finger in contact"),
         when="holding (Lift, Hold, Avoid, Place), no pad's SA above contact_force_n "
         "(drop_check_enabled)", then="Failed"),
    # Reach.
    Rule("reach_event", (Mode.REACH,), 100, _event,
         lambda s: decide(Load(), s.event_trigger, "Reach-Load event"),
         when="the object's Reach-Load event (heuristic: each SA above "
         "heuristic.contact_force_n)", then="Load (event): close at the grip force"),
    Rule("one_sided", (Mode.REACH,), 200, one_sided,
         lambda s: s.re_reach_or_fail(f"only the {touching_finger(s)} finger touched"),
         when="one finger alone in contact for re_reach.one_sided_contact_s while closing",
         then="{re_reach}, else Failed"),
    Rule("closed_on_nothing", (Mode.REACH,), 300, lambda s: s.obs.closed_on_nothing,
         lambda s: s.re_reach_or_fail("the gripper closed on nothing"),
         when="the gripper closed to its request with no object (gOBJ 3)",
         then="{re_reach}, else Failed"),
    Rule("reach_timeout", (Mode.REACH,), 400, reach_timed_out,
         lambda s: s.re_reach_or_fail(reach_timeout_reason(s)),
         when="no Reach-Load event re_reach.reach_event_timeout_s after closing",
         then="{re_reach}, else Failed"),
    # Re-Reach.
    Rule("re_centred", (Mode.RE_REACH,), 100, _done,
         _when_done(Mode.REACH, Trigger.CORRECTIVE, "re-centred"),
         when="the gripper opened and moved", then="Reach (close again)"),
    # Load.
    Rule("load_lift_event", (Mode.LOAD,), 100, _event,
         lambda s: decide(Lift(), s.event_trigger, "Load-Lift event"),
         when="the Load-Lift event: the settled grip (heuristic: each SA above "
         "heuristic.grip_fraction of the grip force)", then="Lift (event)"),
    Rule("relift", (Mode.LOAD,), 200, _decides(_relift), _relift,
         when="after a Lift-Load: both SA at lift_load.grip_fraction of the raised grip "
         "force, the slip band quiet, lift_load.relift_settle_s in Load", then="Lift"),
    Rule("load_timeout", (Mode.LOAD,), 400, load_timed_out, _load_timeout,
         when="no Load-Lift event load_event_timeout_s in Load",
         then="Failed after a Lift-Load, else Re-Reach ({re_reach_shift}; at most "
         "re_reach.max_re_reaches), else Failed"),
    # Lift.
    Rule("lift_load", (Mode.LIFT,), 100, _decides(_lift_load), _lift_load,
         when="either slip band above lift_load.slip_vibration_mps2 for lift_load.slip_s "
         "(or the memorized slip event: memorized_corrective.events); lift_load.enabled",
         then="Load at lift_load.force_factor times the grip force (Lift-Load), Failed "
         "after lift_load.max_lift_loads"),
    Rule("lift_ended", (Mode.LIFT,), 200, _done,
         _when_done(Mode.HOLD, Trigger.TIMER, "lift motion ended"),
         when="the lift motion ended", then="Hold"),
    # Hold.
    Rule("avoid_hit", (Mode.HOLD,), 100, _decides(_avoid), _avoid,
         when="a hit: either a film's RA above avoid.hit_ra_mps2 over its mean of the "
         "avoid.hit_level_s before, from avoid.hit_refractory_s in Hold (or the memorized hit "
         "event: memorized_corrective.events); avoid.enabled, fewer "
         "than avoid.max_avoids Avoids made",
         then="Avoid: sense the hit's direction, move avoid.distance_m away"),
    Rule("hold_time", (Mode.HOLD,), 200, lambda s: s.obs.time_in_mode >= s.hold_s,
         lambda s: Decision(Mode.PLACE, Trigger.TIMER, f"held {s.hold_s:g} s"),
         when="hold_s in Hold (the grasp script's)", then="Place"),
    # Avoid.
    Rule("avoid_ended", (Mode.AVOID,), 100, _done,
         _when_done(Mode.HOLD, Trigger.TIMER, "avoiding motion ended"),
         when="the avoiding motion ended", then="Hold"),
    # Place.
    Rule("place_event", (Mode.PLACE,), 100, _event,
         lambda s: Decision(Mode.UNLOAD, s.event_trigger, "Place-Unload event"),
         when="the Place-Unload event: the table touch (heuristic: either RA above "
         "heuristic.place_ra_mps2)", then="Unload (event): open, retract"),
    Rule("place_timeout", (Mode.PLACE,), 200, lambda s: place_timed_out(s.obs, s.config),
         lambda s: Decision(Mode.UNLOAD, Trigger.TIMER,
                            "no Place-Unload event after the arm stopped"),
         when="no Place-Unload event place.event_timeout_s after the arm stopped",
         then="Unload: open, retract"),
    # Unload.
    Rule("released", (Mode.UNLOAD,), 100, _done,
         _when_done(Mode.DONE, Trigger.TIMER, "released and retracted"),
         when="the gripper opened and the arm retracted", then="Done"),
)

# The paper's Re-Reach: corrective_actions.re_reach_shift, worked out as the gripper opens.
PAPER_RE_REACH = ReReachMove(shift_label="the paper's shift along the stroke",
                             limit_label="re_reach.max_re_reaches",
                             limit=lambda s: s.config.re_reach.max_re_reaches)
PAPER_TABLE = RuleTable(name="paper", rules=PAPER_RULES, re_reach_move=PAPER_RE_REACH)


def rule_table() -> RuleTable:
    """The memorized and heuristic controllers' rule table (their registry entries')."""
    return PAPER_TABLE


def next_mode(mode: Mode, obs: Observation, counters, config, *, event_trigger: Trigger,
              hold_s: float) -> Decision | None:
    """The paper's transition out of `mode` this tick (PAPER_TABLE), or None to stay."""
    return PAPER_TABLE.next_mode(mode, obs, counters, config, event_trigger=event_trigger,
                                 hold_s=hold_s)
