"""The states of the grasping algorithm (Sec. II-B, Fig. 6b), what can trigger a change, and
the record of each change (the state machine's timeline)."""

import dataclasses
import enum

from tegrasp_drake.rig.api_boundary import check_field_types, public_dataclass
from tegrasp_drake.rig.ranges import bounded, check_ranges
from tegrasp_drake.rig.echo import given, shorten, shown
from tegrasp_drake.rig.files import one_line


class Mode(enum.IntEnum):
    """The state machine's modes; the value is what the `mode` output port carries."""
    REACH = 0
    RE_REACH = 1
    LOAD = 2
    LIFT = 3
    HOLD = 4
    AVOID = 5
    PLACE = 6
    UNLOAD = 7
    DONE = 8
    FAILED = 9

    @property
    def label(self) -> str:
        """The paper's name: Reach, Re-Reach, Load, ..."""
        return "Re-Reach" if self is Mode.RE_REACH else self.name.capitalize()

    @staticmethod
    def from_label(label: str) -> "Mode":
        """The mode named `label` (Mode.label); ValueError for an unknown name."""
        for mode in Mode:
            if mode.label == label:
                return mode
        raise ValueError(f"unknown mode {shown(label)}; known: "
                         f"{', '.join(m.label for m in Mode)}")


TERMINAL_MODES = (Mode.DONE, Mode.FAILED)
# The modes in which the fingers hold the object (the drop check's).
HOLDING_MODES = (Mode.LIFT, Mode.HOLD, Mode.AVOID, Mode.PLACE)


# The most characters of a rule's name, and so of the `code` a timeline entry may carry: a
# rule's name is a few words joined by underscores (the longest today, reach_timeout_both_pads,
# has 23); the bound refuses a crafted code before it is looked up or quoted back.
CODE_MAX_LENGTH = 40


class Trigger(enum.StrEnum):
    """What made a transition (the `trigger` of each timeline entry)."""
    MEMORIZED_EVENT = "memorized_event"  # the EventMatcher matched the expected memorized event
    HEURISTIC_EVENT = "heuristic_event"  # the heuristic controller's threshold detector fired
    THRESHOLD = "threshold"  # a hand-set threshold on the live signals (hit, lost object)
    TIMER = "timer"  # a planned motion or a timed phase ended
    CORRECTIVE = "corrective"  # a corrective action (Re-Reach, Lift-Load) started or ended
    FAULT = "fault"  # a device fault
    CORRECTIVE_EVENT = "corrective_event"  # a memorized corrective event matched

    @property
    def is_event(self) -> bool:
        """True for an event detector's trigger (memorized or heuristic)."""
        return self in (Trigger.MEMORIZED_EVENT, Trigger.HEURISTIC_EVENT)


def detects(trigger: Trigger):
    """Marks an event detector's builder with the trigger its detections fire (the builder's
    `trigger`): what a controller with that detector can put on a transition
    (controller_registry.ControllerEntry.triggers) and the state machine's event trigger."""
    def mark(builder):
        builder.trigger = trigger
        return builder
    return mark


class Stage(enum.StrEnum):
    """The step within a mode (grasp_state_machine.py)."""
    NONE = ""  # the mode's motion, or none
    MOVING = "moving"  # a planned motion of the grasp frame
    CLOSING = "closing"  # Reach: the gripper closes on the object
    OPENING = "opening"  # Re-Reach, Unload: the gripper opens before the arm moves
    SENSING = "sensing"  # Avoid: the arm stands still while the hit's direction is sensed


@dataclasses.dataclass(frozen=True)
class Decision:
    """The next mode, its trigger and reason; a rule's also carries its action and name (`code`)."""
    mode: Mode
    trigger: Trigger
    reason: str
    action: object | None = None
    code: str | None = None


# A transition's reason is words for a person, printed on one timeline line. The longest the
# controllers wrote in 37,217 committed transitions is 129 characters; 1000 leaves room for
# longer words and refuses a pasted file or a log's corrupt text.
MAX_REASON_CHARS = 1000
WORDS = f"one printable line of at most {MAX_REASON_CHARS} characters (words for a person)"


def words_problem(text: str) -> str | None:
    """Why `text` (a transition's reason, a device fault's description: words a timeline line
    prints) is not WORDS, as "got ...", else None."""
    unprintable = next((k for k, c in enumerate(text) if not c.isprintable()), None)
    if unprintable is not None:
        return f"got {text[unprintable]!r} at character {unprintable}"
    return f"got {len(text)} characters" if len(text) > MAX_REASON_CHARS else None


def as_words(text: str) -> str:
    """A device's or driver's own text (a fault's description: a Modbus library's error, a
    watchdog's lines) made WORDS for a transition's reason: one printable line, its line
    breaks and control characters escaped, cut to MAX_REASON_CHARS with its start and end
    kept. A device's text is not ours to refuse: the run must still fail on the fault."""
    line = one_line(text)
    # shorten adds "..." and " (N characters)": leave room for both.
    return shorten(line, MAX_REASON_CHARS - 40) if len(line) > MAX_REASON_CHARS else line


@public_dataclass
@dataclasses.dataclass(frozen=True)
class Transition:
    """One timeline entry: at t [s] (Context time) from_mode -> to_mode; the corrective
    fields are set only on the transition that starts that action; `code` is the name of the
    rule that decided it (every state-machine transition has one; the open-loop script's have
    None). Its numbers are checked against their ranges when it is built (a hand-made or
    read-back entry included)."""
    t: float = bounded(low=0.0, unit="s", why="Context time since the trial's start")
    from_mode: Mode
    to_mode: Mode
    trigger: Trigger
    reason: str
    # The detector's four channel scores; None: none. Eq. 3 correlations in [-1, 1] for the
    # memorized detector, but each channel over its threshold for the heuristic one (5.2 on
    # a firm grasp): only finite, no common range.
    scores: tuple[float, ...] | None = bounded(
        None, why="Eq. 3 correlations, or the heuristic detector's channel/threshold ratios")
    # Re-Reach: the shift along world y, the stroke [m].
    offset_m: float | None = bounded(None, unit="m", why="a shift of the grasp frame")
    # taxel_aware Re-Reach: the shift along world x, the approach axis [m]; negative in the
    # approach (a back-off), that far back along the Reach's path instead (mostly up).
    approach_offset_m: float | None = bounded(None, unit="m", why="a shift of the grasp frame")
    # Lift-Load: the raised grip force [N], a squeeze (not a pull).
    grip_force_n: float | None = bounded(None, low=0.0, high=235.0, unit="N",
                                         why="the gripper squeezes, it does not pull; the "
                                             "2F-85 grips with at most 235 N (its manual)")
    # Avoid: unit direction, world.
    direction: tuple[float, float, float] | None = bounded(
        None, low=-1.0, high=1.0, length=3, why="the components of a unit vector")
    # Avoid: (left, right) SA gain of the hit [N].
    delta_sa_n: tuple[float, float] | None = bounded(None, unit="N", length=2,
                                                     why="a change of force: either sign")
    # Avoid, Re-Reach: the move's duration [s], the configured one or longer where the arm
    # follows no faster along the move's direction (cartesian_arm_controller.followable_move_s;
    # the reason says why when stretched).
    move_s: float | None = bounded(None, low=0.0, low_open=True, unit="s",
                                   why="a move's duration: positive, stretched to what the "
                                       "arm follows, so no upper bound of its own")
    code: str | None = None  # the deciding rule's name (rule_engine.Rule.name)

    def __post_init__(self):
        """ConfigError naming the first field out of its range, a reason that is not one
        printable line of at most MAX_REASON_CHARS, a `code` that names no rule
        of a registered controller's table, or a to_mode that is the from_mode: an entry
        records a change of mode (no rule's `then` keeps its mode, and the open-loop script
        logs a phase only when its mode changes). The types first (a reason of None, 5 or
        b"x" named, not a TypeError of its check): the checks read the fields' values."""
        check_field_types(self)
        check_ranges(self, type(self).__name__)
        problem = words_problem(self.reason)
        if problem:
            from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: loaded when checking
            raise ConfigError(f"{type(self).__name__}: field 'reason' must be {WORDS}, "
                              f"{problem}")
        if self.code is not None:
            try:
                _check_code(self.code)
            except ValueError as error:
                from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: when checking
                raise ConfigError(str(error)) from None
        if self.to_mode == self.from_mode:
            from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: loaded when checking
            label = getattr(self.to_mode, "label", self.to_mode)
            raise ConfigError(f"{type(self).__name__}: field 'to_mode' must differ from "
                              f"'from_mode' (a transition changes the mode), got {label} to "
                              f"{label}")

    @property
    def decided_by(self) -> str:
        """What made the transition, for printed timelines: its trigger and, after a colon,
        the deciding rule's code ("corrective: finger_strike"); the trigger alone for an
        entry without a code (the open-loop script's)."""
        trigger = self.trigger.value
        return f"{trigger}: {self.code}" if self.code else trigger

    def as_dict(self) -> dict:
        """The JSON form (trial results, logs): t, from, to (Mode.label), trigger, reason,
        then the _OPTIONAL_FIELDS that are set (`code` last), tuples as lists."""
        entry = {"t": self.t, "from": self.from_mode.label, "to": self.to_mode.label,
                 "trigger": self.trigger.value, "reason": self.reason}
        for key in _OPTIONAL_FIELDS:
            value = getattr(self, key)
            if value is not None:
                entry[key] = list(value) if isinstance(value, tuple) else value
        return entry

    @staticmethod
    def from_dict(entry: dict) -> "Transition":
        """The Transition of its JSON form (as_dict); ValueError naming what is wrong (a
        `code` must name a rule of a registered controller's table)."""
        if not isinstance(entry, dict):
            raise ValueError(f"a transition is a mapping of {', '.join(_REQUIRED_KEYS)}, got "
                             f"{given(entry)}")
        missing = [key for key in _REQUIRED_KEYS if key not in entry]
        if missing:
            raise ValueError(f"lacks the field '{missing[0]}' (a transition holds "
                             f"{', '.join(_REQUIRED_KEYS)})")
        optional = {key: tuple(entry[key]) if isinstance(entry[key], list) else entry[key]
                    for key in _OPTIONAL_FIELDS if key in entry}
        if "code" in entry:
            _check_code(entry["code"])  # a ValueError, as for the rest of the JSON form
        return Transition(t=entry["t"], from_mode=Mode.from_label(entry["from"]),
                          to_mode=Mode.from_label(entry["to"]),
                          trigger=_trigger(entry["trigger"]), reason=entry["reason"],
                          **optional)


_REQUIRED_KEYS = ("t", "from", "to", "trigger", "reason")


def _trigger(value) -> Trigger:
    """The Trigger named `value`; ValueError echoing it cut (a log's or a file's text)."""
    try:
        return Trigger(value)
    except ValueError:
        raise ValueError(f"{shown(value)} is not a valid Trigger (known: "
                         f"{', '.join(Trigger)})") from None
_OPTIONAL_FIELDS = ("scores", "offset_m", "approach_offset_m", "grip_force_n", "direction",
                    "delta_sa_n", "move_s", "code")


def _check_code(code) -> None:
    """ValueError unless `code` is the name of a rule of a registered controller's table."""
    what = "Transition: field 'code'"
    if not isinstance(code, str):
        raise ValueError(f"{what} must be a rule's name (text), got {type(code).__name__} "
                         f"{shorten(repr(code))}")
    if len(code) > CODE_MAX_LENGTH:
        raise ValueError(f"{what} {shorten(repr(code), CODE_MAX_LENGTH)} is longer than a "
                         f"rule's name (at most {CODE_MAX_LENGTH} characters)")
    from tegrasp_drake.control.controller_registry import rule_codes  # imports the tables
    if code not in rule_codes():
        raise ValueError(f"{what} {code!r} names no rule of the controllers' rule tables (the "
                         f"rules: docs/controller.md)")
