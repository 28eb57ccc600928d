"""The vocabulary of the taxel-aware rule table: what a rule sees (Situation), what it
decides (an action, carried by the Decision with a structured Reason), and a rule itself
(name, condition, action).

A rule's action says everything the state machine needs to carry it out: a ReReach holds
its shift, a Regrasp marks the Place as a re-grasp's. The state machine never works out
again which rule applies; the table (table.py) says it once, in order.
"""

import dataclasses
import enum
from collections.abc import Callable

from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift


class Reason(enum.StrEnum):
    """Which rule of the table decided a transition (its name in the table)."""
    DEVICE_FAULT = "device_fault"
    GRIPPER_FAULT = "gripper_fault"
    OBJECT_LOST = "object_lost"
    FINGER_STRIKE = "finger_strike"
    APPROACH_CONTACT = "approach_contact"
    BEYOND_PADS = "beyond_pads"
    TIPPING_GUARD = "tipping_guard"
    OFF_CENTRE = "off_centre"
    REACH_EVENT = "reach_event"
    ONE_SIDED_AT_WIDTH = "one_sided_at_width"
    BRACKETED_AT_EXTENT = "bracketed_at_extent"
    BRACKET_RECENTRE = "bracket_recentre"
    ONE_SIDED = "one_sided"
    CLOSED_ON_NOTHING = "closed_on_nothing"
    REACH_TIMEOUT_BOTH_PADS = "reach_timeout_both_pads"
    REACH_TIMEOUT_CAGED = "reach_timeout_caged"
    REACH_TIMEOUT = "reach_timeout"
    LOAD_LIFT_EVENT = "load_lift_event"
    RELIFT = "relift"
    LOAD_TIMEOUT_BOTH_PADS = "load_timeout_both_pads"
    LOAD_TIMEOUT_CAGED = "load_timeout_caged"
    LOAD_TIMEOUT = "load_timeout"
    CAGED_LIFT_ENDED = "caged_lift_ended"
    CAGED_NO_LIFT_LOAD = "caged_no_lift_load"
    LIFT = "lift"
    AVOID_HIT = "avoid_hit"
    HELD_TILTED = "held_tilted"
    HOLD_TIME = "hold_time"
    REGRASP_AFTER_PLACE = "regrasp_after_place"
    PLACE = "place"
    RE_CENTRED = "re_centred"
    AVOID_ENDED = "avoid_ended"
    RELEASED = "released"


# ---- actions ------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class ReReach:
    """Open, move the open gripper by `shift` [m, world], close again. `counted`: the
    Re-Reach counts toward the Re-Reach limits (a re-grasp's does not)."""
    shift: Shift
    counted: bool = True
    mode = Mode.RE_REACH


@dataclasses.dataclass(frozen=True)
class Load:
    """Squeeze at the grip force, without (or after) the Reach-Load event."""
    mode = Mode.LOAD


@dataclasses.dataclass(frozen=True)
class Lift:
    """Lift the object (the Load-Lift event, or a Load timeout with the object held)."""
    mode = Mode.LIFT


@dataclasses.dataclass(frozen=True)
class Regrasp:
    """Put the object down (Place) to open and grasp it again."""
    mode = Mode.PLACE


@dataclasses.dataclass(frozen=True)
class Failed:
    """Give up: the corrections are used up or switched off."""
    mode = Mode.FAILED


# ---- rules --------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class Situation:
    """What a rule reads: the mode, the tick's Observation (its `estimate`, the
    ContactEstimate), the corrections made so far, the controller's settings
    (GraspControllerConfig), the event detector's trigger and how long to hold [s]."""
    mode: Mode
    obs: object
    counters: Counters
    config: object
    event_trigger: Trigger
    hold_s: float

    @property
    def estimate(self):
        return self.obs.estimate

    @property
    def taxel(self):
        return self.config.taxel_aware


@dataclasses.dataclass(frozen=True)
class Rule:
    """One row of the table: when `condition(situation)` holds, `action(situation)` is the
    Decision (None: stay in the mode), and no row below is asked. `when` and `then` say
    the condition and the action in words (the table's documentation)."""
    code: Reason
    condition: Callable[[Situation], bool]
    action: Callable[[Situation], Decision | None]
    when: str = ""
    then: str = ""

    @property
    def name(self) -> str:
        return self.code.value


def decide(action, trigger: Trigger, reason: str) -> Decision:
    """The Decision carrying `action` (its mode), with the human-readable `reason`."""
    return Decision(action.mode, trigger, reason, action=action)


def re_reach_allowed(situation: Situation, limit: int | None = None) -> bool:
    """Re-Reach is on and fewer than `limit` (default taxel_aware.max_re_reaches)
    Re-Reaches are made."""
    limit = situation.taxel.max_re_reaches if limit is None else limit
    return situation.config.re_reach_enabled and situation.counters.re_reaches < limit


def re_reach_or_fail(situation: Situation, shift: Shift, reason: str, *,
                     limit: int | None = None) -> Decision:
    """ReReach by `shift` for `reason`, or Failed when Re-Reach is switched off or `limit`
    (default taxel_aware.max_re_reaches) Re-Reaches are made, as the paper's rule
    (corrective_actions.re_reach_or_fail) words it."""
    limit = situation.taxel.max_re_reaches if limit is None else limit
    re_reaches = situation.counters.re_reaches
    if not situation.config.re_reach_enabled:
        return decide(Failed(), Trigger.CORRECTIVE, f"{reason}; Re-Reach is switched off")
    if re_reaches >= limit:
        return decide(Failed(), Trigger.CORRECTIVE,
                      f"{reason}, after {re_reaches} Re-Reach attempts")
    return decide(ReReach(shift), Trigger.CORRECTIVE, reason)
