"""What a rule of a rule table (rule_engine.py) decides: an action, carried by its
Decision, which the state machine only carries out. A ReReach holds its shift (or none:
the paper's), a Regrasp marks the Place as a re-grasp's.

Imports no Drake (the controller registry, read at the command line's start, imports the
modules that define rule tables).
"""

import dataclasses

from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger


@dataclasses.dataclass(frozen=True)
class ReReach:
    """Open, move the open gripper by `shift` [m, world; a taxel_aware contact_geometry
    Shift], close again. shift None: the paper's shift along the stroke, which the state
    machine works out from the SA and the opening where the gripper stopped
    (corrective_actions.re_reach_shift). `counted`: the Re-Reach counts toward the Re-Reach
    limits (a re-grasp's does not)."""
    shift: object | None = None
    counted: bool = True
    mode = Mode.RE_REACH


@dataclasses.dataclass(frozen=True)
class Load:
    """Squeeze at the grip force, on the Reach-Load event or without it."""
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


def decide(action, trigger: Trigger, reason: str) -> Decision:
    """The Decision carrying `action` (its mode), with the human-readable `reason`."""
    return Decision(action.mode, trigger, reason, action=action)


def re_reach_limit(situation, limit: int | None = None) -> int:
    """`limit`, or by default the most Re-Reaches the situation's table allows."""
    return situation.re_reach_move.limit(situation) if limit is None else limit


def re_reach_allowed(situation, limit: int | None = None) -> bool:
    """Re-Reach is on and fewer than `limit` (default: the table's) Re-Reaches are made."""
    return (situation.config.re_reach.enabled
            and situation.counters.re_reaches < re_reach_limit(situation, limit))


def re_reach_or_fail(situation, shift, reason: str, *, limit: int | None = None) -> Decision:
    """ReReach by `shift` (None: the paper's) for `reason`, or Failed when Re-Reach is
    switched off (config.re_reach.enabled) or `limit` (default: the table's) Re-Reaches are
    made."""
    limit = re_reach_limit(situation, limit)
    re_reaches = situation.counters.re_reaches
    if not situation.config.re_reach.enabled:
        return decide(Failed(), Trigger.CORRECTIVE, f"{reason}; Re-Reach is switched off")
    if re_reaches >= limit:
        return decide(Failed(), Trigger.CORRECTIVE,
                      f"{reason}, after {re_reaches} Re-Reach attempts")
    return decide(ReReach(shift), Trigger.CORRECTIVE, reason)
