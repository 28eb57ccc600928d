"""The states of the grasping algorithm (Sec. II-B, Fig. 6b) and what can trigger a change."""

import enum


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


TERMINAL_MODES = (Mode.DONE, Mode.FAILED)

# What made a transition (the `trigger` of each timeline entry).
MEMORIZED_EVENT = "memorized_event"  # the EventMatcher matched the expected memorized event
HEURISTIC_EVENT = "heuristic_event"  # the heuristic controller's threshold detector fired
THRESHOLD = "threshold"  # a hand-set threshold on the live signals (hit, lost object)
TIMER = "timer"  # a planned motion or a timed phase ended
CORRECTIVE = "corrective"  # a corrective action (Re-Reach, Lift-Load) started or ended
FAULT = "fault"  # a device fault
TRIGGERS = (MEMORIZED_EVENT, HEURISTIC_EVENT, THRESHOLD, TIMER, CORRECTIVE, FAULT)

# The transitions each mode checks an event for, by mode (the expected event).
EXPECTED_TRANSITION = {Mode.REACH: "reach_load", Mode.LOAD: "load_lift",
                       Mode.PLACE: "place_unload"}
