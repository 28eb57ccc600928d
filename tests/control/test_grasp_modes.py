"""The state machine's vocabulary: modes by label, triggers, and a timeline entry's JSON."""

import json

import pytest

from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger

REACH_LOAD = {"t": 3.76, "from": "Reach", "to": "Load", "trigger": "memorized_event",
              "reason": "Reach-Load event", "scores": [0.9004, 0.9007, 0.9987, 0.9986]}


def test_every_mode_is_found_by_its_label():
    assert [Mode.from_label(mode.label) for mode in Mode] == list(Mode)
    assert Mode.from_label("Re-Reach") == Mode.RE_REACH
    with pytest.raises(ValueError, match="unknown mode 'Grasp'"):
        Mode.from_label("Grasp")


def test_only_the_detectors_triggers_are_events():
    assert {t for t in Trigger if t.is_event} == {Trigger.MEMORIZED_EVENT,
                                                  Trigger.HEURISTIC_EVENT}
    assert [t.value for t in Trigger] == ["memorized_event", "heuristic_event", "threshold",
                                          "timer", "corrective", "fault", "corrective_event"]


def test_a_transition_keeps_the_json_field_names_and_order():
    transition = Transition(t=3.76, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                            trigger=Trigger.MEMORIZED_EVENT, reason="Reach-Load event",
                            scores=(0.9004, 0.9007, 0.9987, 0.9986))
    entry = transition.as_dict()
    assert list(entry) == ["t", "from", "to", "trigger", "reason", "scores"]
    assert json.dumps(entry) == json.dumps(REACH_LOAD)
    assert Transition.from_dict(entry) == transition


def test_a_transition_without_scores_has_no_scores_field():
    entry = Transition(t=8.5, from_mode=Mode.UNLOAD, to_mode=Mode.DONE, trigger=Trigger.TIMER,
                       reason="script ended").as_dict()
    assert entry == {"t": 8.5, "from": "Unload", "to": "Done", "trigger": "timer",
                     "reason": "script ended"}


def test_an_avoid_transition_lists_its_direction_after_the_scores():
    avoid = Transition(t=7.02, from_mode=Mode.HOLD, to_mode=Mode.AVOID,
                       trigger=Trigger.THRESHOLD, reason="hit: RA above the hit threshold",
                       scores=(0.0, 0.0, 0.0, 0.0), direction=(0.0, 1.0, 0.0),
                       delta_sa_n=(3.1, -0.2))
    entry = avoid.as_dict()
    assert list(entry)[-3:] == ["scores", "direction", "delta_sa_n"]
    assert entry["direction"] == [0.0, 1.0, 0.0] and entry["delta_sa_n"] == [3.1, -0.2]
    assert Transition.from_dict(json.loads(json.dumps(entry))) == avoid


def test_a_rule_driven_transition_writes_and_reads_back_its_rule_code():
    reach_load = Transition(t=3.76, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                            trigger=Trigger.MEMORIZED_EVENT, reason="Reach-Load event",
                            scores=(0.9004, 0.9007, 0.9987, 0.9986), code="reach_event")
    entry = json.loads(json.dumps(reach_load.as_dict()))
    assert entry == {**REACH_LOAD, "code": "reach_event"}
    assert Transition.from_dict(entry) == reach_load


@pytest.mark.parametrize("code, words", [
    ("reach_evnt", "'reach_evnt' names no rule of the controllers"),
    ("x" * 5000, "is longer than"),
    (7, "must be a rule's name (text), got int"),
], ids=["unknown", "too-long", "not-text"])
def test_a_code_that_names_no_rule_is_refused_in_one_line_naming_it(code, words):
    with pytest.raises(ValueError) as refused:
        Transition.from_dict({**REACH_LOAD, "code": code})
    message = str(refused.value)
    assert "field 'code'" in message and words in message, message
    assert "\n" not in message and len(message) < 400, message


@pytest.mark.parametrize("reason, words", [
    ("x" * 1001, "got 1001 characters"),
    ("held\n3 s", "got '\\n' at character 4"),
    ("held\x1b[2J", "holds an escape (character 0x1b) at position 4"),
], ids=["too-long", "two-lines", "terminal-escape"])
def test_a_reason_that_is_not_one_printable_line_is_refused_in_one_line(reason, words):
    """A reason is printed on the timeline's one line per transition (results and logs read
    back included): a pasted file or a terminal escape is refused, not printed."""
    with pytest.raises(ValueError) as refused:
        Transition.from_dict({**REACH_LOAD, "reason": reason})
    message = str(refused.value)
    assert "field 'reason'" in message and words in message, message
    assert "\n" not in message and len(message) < 400, message
    assert Transition.from_dict({**REACH_LOAD, "reason": "x" * 1000}).reason == "x" * 1000


@pytest.mark.parametrize("reason, words", [
    (None, "must be str, got None"), (5, "must be str, got int 5"),
    (b"x", "must be str, got bytes b'x'")])
def test_a_reason_that_is_not_text_is_refused_naming_the_field(reason, words):
    """The types are checked before the reason's words are read: one line naming the field
    and what it takes, not a bare TypeError or AttributeError of the check."""
    with pytest.raises(ValueError) as refused:
        Transition(t=0.0, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                   trigger=Trigger.MEMORIZED_EVENT, reason=reason)
    message = str(refused.value)
    assert message == f"Transition: field 'reason' {words}", message
