"""The actions a rule decides (rule_engine.py), carried by its Decision and only carried
out by the state machine; Drake-free."""

import dataclasses

from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger


@dataclasses.dataclass(frozen=True)
class ReReach:
    """Open, move by `shift` [m, world; a contact_geometry.Shift; None: the paper's shift
    along the stroke], close again; `counted` toward the limits (a re-grasp's is not)."""
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
    """ReReach by `shift`, or Failed when Re-Reach is off or `limit` Re-Reaches are made."""
    limit = re_reach_limit(situation, limit)
    re_reaches = situation.counters.re_reaches
    if not situation.config.re_reach.enabled:
        return decide(Failed(), Trigger.CORRECTIVE, f"{reason}; Re-Reach is switched off")
    if re_reaches >= limit:
        return decide(Failed(), Trigger.CORRECTIVE,
                      f"{reason}, after {re_reaches} Re-Reach attempts")
    return decide(ReReach(shift), Trigger.CORRECTIVE, reason)
