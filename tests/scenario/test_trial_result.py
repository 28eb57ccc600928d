"""TrialResult: the typed trial result and its JSON form, which sweep records keep."""

import json
import pathlib

import pytest

from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.trial_result import TrialResult
from tegrasp_drake.sweep.runner import check_result
from tests.fake_trials import whole_result

RECORD = (pathlib.Path(__file__).resolve().parents[2] / "analysis" / "results_linkage"
          / "paper_grid" / "trials" / "taxel_aware.box.m02.a1.json")


def test_a_committed_records_result_reads_back_unchanged():
    stored = json.loads(RECORD.read_text())["result"]
    result = TrialResult.from_dict(stored)
    assert result.final_mode == Mode.DONE and result.entered(Mode.RE_REACH)
    written = result.to_dict()
    # Fields newer than the record (lift_grip_fraction) are added with their defaults.
    assert {key: written[key] for key in stored} == stored


# Rule: the JSON form is read whole: a missing or mistyped field is one line naming it; only
# the fields a later version added (FIELDS_ADDED_LATER) may be missing, as in the committed
# records written before them.
@pytest.mark.parametrize("data, words", [
    ({}, "field 'object' is missing"),
    ({"hold_success": True}, "field 'object' is missing"),
])
def test_a_result_missing_a_field_is_refused_naming_it(data, words):
    with pytest.raises(ValueError) as refused:
        TrialResult.from_dict(data)
    message = str(refused.value)
    assert words in message and "TrialResult.to_dict()" in message and "\n" not in message


@pytest.mark.parametrize("field", ["hold_success", "final_mode", "transitions", "seed"])
def test_a_whole_result_without_one_field_is_refused_naming_it(field):
    data = whole_result()
    del data[field]
    with pytest.raises(ValueError, match=f"field '{field}' is missing"):
        TrialResult.from_dict(data)


def test_a_mistyped_field_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="field 'hold_success' must be bool, got str"):
        TrialResult.from_dict(whole_result(hold_success="yes"))


@pytest.mark.parametrize("folder", ["results_seed0", "results_robot/paper_grid",
                                    "geometry_contract/paper_grid"])
def test_committed_records_without_the_later_fields_are_read(folder):
    """Records written before cpu_time_s, lift_grip_fraction and release_height_m."""
    from tegrasp_drake.scenario.trial_result import FIELDS_ADDED_LATER
    trials = RECORD.parents[3] / folder / "trials"
    stored = json.loads(next(iter(sorted(trials.glob("*.json")))).read_text())["result"]
    lacking = [name for name in FIELDS_ADDED_LATER if name not in stored]
    assert lacking
    result = TrialResult.from_dict(stored)
    assert all(getattr(result, name) is None for name in lacking)


def test_the_json_form_round_trips():
    result = TrialResult(object="box", controller="memorized", seed=600, hold_success=True,
                         transitions=(Transition(3.8, Mode.REACH, Mode.LOAD,
                                                 Trigger.MEMORIZED_EVENT, "Reach-Load event",
                                                 scores=(0.9, 0.9, 1.0, 1.0),
                                                 code="reach_event"),),
                         final_mode=Mode.LOAD, physical_events={"reach_load": 3.6})
    data = json.loads(json.dumps(result.to_dict()))
    assert data["final_mode"] == "Load" and data["transitions"][0]["from"] == "Reach"
    assert data["transitions"][0]["code"] == "reach_event"
    assert TrialResult.from_dict(data) == result
    assert "log" not in data


# The trial of a result that names no object, controller or seed, its object at the marker
# (whole_result's defaults): these tests are about the result alone.
A_TRIAL = {"object_name": "", "controller": "", "seed": None, "marker_dx_m": 0.0,
           "marker_dy_m": 0.0, "perturbation": {"dx_m": 0.0, "dy_m": 0.0}}


def test_a_sweep_refuses_a_result_whose_transitions_do_not_parse():
    entry = {"t": 1.0, "from": "reach", "to": "Load", "trigger": "memorized_event",
             "reason": "Reach-Load event"}
    problem = check_result(whole_result(hold_success=True, transitions=[entry]), A_TRIAL)
    assert problem and "'transitions'[0]" in problem and "reach" in problem


def test_a_sweep_refuses_a_result_whose_transition_names_no_rule():
    entry = {"t": 1.0, "from": "Reach", "to": "Load", "trigger": "memorized_event",
             "reason": "Reach-Load event", "code": "reach_evnt"}
    problem = check_result(whole_result(hold_success=True, transitions=[entry]), A_TRIAL)
    assert problem and "'transitions'[0]" in problem and "reach_evnt" in problem
    assert check_result(whole_result(hold_success=True, final_mode="Load",
                                     transitions=[{**entry, "code": "reach_event"}]),
                        A_TRIAL) is None


def _reach_load(t: float) -> Transition:
    return Transition(t, Mode.REACH, Mode.LOAD, Trigger.MEMORIZED_EVENT, "Reach-Load event")


def _load_lift(t: float) -> Transition:
    return Transition(t, Mode.LOAD, Mode.LIFT, Trigger.MEMORIZED_EVENT, "Load-Lift event")


@pytest.mark.parametrize("fields, words", [
    ({"hold_time_s": -1.0}, "field 'hold_time_s' must be at least 0"),
    ({"sim_time_s": -3.0}, "field 'sim_time_s' must be at least 0"),
    ({"lift_height_m": float("nan")}, "field 'lift_height_m' must be a finite number"),
    ({"final_tilt_deg": 270.0}, "field 'final_tilt_deg' must lie in [0, 180]"),
    ({"lift_height_m": 42.0}, "field 'lift_height_m' must lie in [0, 2]"),
    ({"release_height_m": -5.0}, "field 'release_height_m' must lie in [-2, 2]"),
    ({"false_triggers": -2}, "field 'false_triggers' must be at least 0"),
    ({"offset_m": [float("nan"), 0.0]}, "field 'offset_m[0]' must be a finite number"),
    ({"seed": -1}, "field 'seed' must lie in"),
    ({"detection_latency_s": {"reach_load": float("inf")}},
     "field 'detection_latency_s.reach_load' must be a finite number"),
    ({"physical_events": {"hit": -1.0}}, "field 'physical_events.hit' must be at least 0"),
    ({"transitions": (_reach_load(5.0), _load_lift(1.0))},
     "field 'transitions[1].t' must not be before transitions[0].t"),
])
def test_a_result_with_a_value_out_of_its_range_is_refused_naming_the_field(fields, words):
    with pytest.raises(ConfigError) as refused:
        TrialResult(**fields)
    message = str(refused.value)
    assert "\n" not in message and message.startswith("TrialResult")
    assert words in message, message


def test_a_transition_with_a_value_out_of_its_range_is_refused_naming_the_field():
    with pytest.raises(ConfigError, match=r"Transition: field 'scores\[2\]' must be a finite"):
        Transition(1.0, Mode.REACH, Mode.LOAD, Trigger.MEMORIZED_EVENT, "Reach-Load event",
                   scores=(0.9, 0.9, float("nan"), 1.0))
    with pytest.raises(ConfigError, match="Transition: field 'grip_force_n' must be a finite"):
        Transition(1.0, Mode.LIFT, Mode.LOAD, Trigger.CORRECTIVE, "Lift-Load",
                   grip_force_n=float("nan"))
    entry = _reach_load(1.0).as_dict() | {"t": -0.5}
    with pytest.raises(ValueError, match="Transition: field 't' must be at least 0"):
        TrialResult.from_dict(whole_result(transitions=[entry]))


def test_a_damaged_records_result_is_refused_naming_the_record_file_and_field(
        tmp_path, monkeypatch, capfd):
    """A record whose result was edited (its checksum remade) holds a negative hold time:
    it is corrupt, and the figures refuse it in one line naming the record's file and the
    field."""
    from tegrasp_drake.sweep.records import load_records, make_record, write_record
    from tests.fake_trials import fake_trial
    from tests.bad_input.probes import assert_one_line_error, run_cli
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    (trial,) = [t.to_dict() for t in expand_trials(SweepSpec(
        objects=("box",), controllers=("memorized",), attempts=1, grid=((-0.01, -0.015),),
        base_seed=600))]
    result = fake_trial(trial)
    result["hold_time_s"] = -1.0
    write_record(tmp_path / "sweep", make_record(trial, result=result))
    # Checksummed, but its result is read at load: corrupt, named with the field.
    (reason,) = load_records(tmp_path / "sweep").corrupt.values()
    assert "'hold_time_s'" in reason
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["plot", "latency", "sweep", "--out", "latency.png"], capfd)
    assert_one_line_error(code, text, "memorized.box.m00.a0.json", "'hold_time_s'")
    assert not (tmp_path / "latency.png").exists()


def test_every_numeric_field_of_a_result_declares_its_range():
    from tegrasp_drake.rig.ranges import unranged_numeric_fields
    assert unranged_numeric_fields(TrialResult, Transition) == []


@pytest.mark.parametrize("fields, words", [
    ({"transitions": (_reach_load(1.0), _load_lift(2.0)), "final_mode": Mode.LOAD},
     "field 'final_mode' is Load but the last transition enters Lift"),
    ({"final_mode": Mode.DONE}, "field 'final_mode' is Done but no transition was taken"),
    ({"hold_success": True, "unload_success": True, "final_mode": Mode.DONE,
      "released": False}, "field 'unload_success' is true but 'released' is false"),
    ({"hold_success": True, "unload_success": True, "final_mode": Mode.DONE,
      "released": True, "final_tilt_deg": 45.0},
     "field 'unload_success' is true but 'final_tilt_deg' is 45"),
])
def test_a_result_breaking_a_relation_of_its_modes_or_its_unload_is_refused(fields, words):
    """run_trial's final mode is the last transition's (Reach when none was taken), and an
    unload is judged a success only released and upright: a result saying otherwise is one
    no trial produced."""
    if fields.get("final_mode") == Mode.DONE and "unload_success" in fields:
        fields = fields | {"transitions": (
            _reach_load(1.0), _load_lift(2.0),
            Transition(3.0, Mode.LIFT, Mode.DONE, Trigger.TIMER, "done"))}
    with pytest.raises(ConfigError) as refused:
        TrialResult(**fields)
    message = str(refused.value)
    assert "\n" not in message and message.startswith("TrialResult")
    assert words in message, message



def _edited(path: str, value) -> dict:
    """The committed RECORD's result with the value at `path` (keys and list indices, dotted)
    replaced by `value`."""
    data = json.loads(RECORD.read_text())["result"]
    *parents, last = [int(key) if key.isdigit() else key for key in path.split(".")]
    target = data
    for key in parents:
        target = target[key]
    target[last] = value
    return data


@pytest.mark.parametrize("path, value, words", [
    ("transitions.2.from", "Load", "field 'transitions[2].from' must be Reach"),
    ("detection_latency_s.reach_load", -0.5,
     "field 'detection_latency_s.reach_load' must be at least -0.01"),
    ("detection_latency_s.reach_hold", 0.05,
     "field 'detection_latency_s.reach_hold' names no event transition"),
    ("transitions.9.trigger", "timer",
     "field 'detection_latency_s.load_lift' but no event-triggered transition"),
    ("physical_events.reach_load", None,
     "field 'detection_latency_s.reach_load' but 'physical_events.reach_load' is not given"),
    ("detection_latency_s.reach_load", 0.05,
     "field 'detection_latency_s.reach_load' must be transitions[8].t - "
     "physical_events.reach_load = 0.0407407 s"),
    ("physical_events.place_unload", 17.5,
     "field 'detection_latency_s.place_unload' but every place_unload detection came more"),
    ("physical_events.slip", 12.0, "field 'physical_events.slip' names no physical event"),
    ("failure", "dropped in Hold", "field 'failure' is 'dropped in Hold' but no transition"),
    ("corrective_actions", ["re_reach", "re_reach", "re_reach"],
     "field 'corrective_actions' must be the actions the transitions start, in order, "
     "[re_reach, re_reach, re_reach, re_reach]"),
    ("corrective_actions", ["re_reach", "re_reach", "re_reach", "re_reach", "avoid"],
     "field 'corrective_actions' must be the actions"),
    ("transitions.8.trigger", "heuristic_event",
     "field 'transitions[8].trigger' (at 11.3 s) is heuristic_event, which the taxel_aware "
     "controller never fires (it fires corrective, corrective_event, fault, memorized_event, "
     "threshold, timer); correct the trigger or the result's 'controller'"),
    ("controller", "heuristic", "field 'transitions[8].trigger' (at 11.3 s) is "
     "memorized_event, which the heuristic controller never fires"),
    ("controller", "open_loop", "field 'transitions[0].trigger' (at 3.075 s) is corrective, "
     "which the open_loop controller never fires (it fires timer)"),
    ("physical_events.place_unload", 15.0, "field 'physical_events.place_unload' is 15 s, "
     "before 15.85 s, when the trial last entered Place before its place_unload transition "
     "(the event is searched from there); correct the event's time or the timeline"),
    ("physical_events.reach_load", 10.0, "field 'physical_events.reach_load' is 10 s, before "
     "10.45 s, when the trial last entered Reach before its reach_load transition"),
])
def test_a_committed_result_edited_to_contradict_itself_is_refused(path, value, words):
    """Each edit of a real result gives one judge_trial cannot: a timeline whose modes do not
    chain, a latency earlier than a false trigger or of a transition not detected, a physical
    event that is none, behind no transition taken or before its search starts, a failure no
    transition gave, a trigger the result's controller never fires."""
    TrialResult.from_dict(_edited("failure", ""))  # the record as it is reads
    with pytest.raises(ValueError) as refused:
        TrialResult.from_dict(_edited(path, value))
    message = str(refused.value)
    assert "\n" not in message and words in message, message


@pytest.mark.parametrize("controller, code, from_mode, words", [
    ("memorized", "finger_strike", Mode.REACH, "field 'transitions[0].code' (at 1 s) is "
     "'finger_strike', which names no rule of the memorized controller (docs/controller.md "
     "lists its rules); correct the code or the result's 'controller'"),
    ("open_loop", "reach_event", Mode.REACH, "which names no rule of the open_loop controller "
     "(it has no rules, so its transitions carry no code)"),
    ("memorized", "released", Mode.REACH, "field 'transitions[0].code' (at 1 s) is "
     "'released', a rule that does not apply in Reach, the mode the transition left"),
])
def test_a_transition_coded_by_a_rule_its_controller_lacks_or_not_of_its_mode_is_refused(
        controller, code, from_mode, words):
    trigger = Trigger.TIMER if controller == "open_loop" else Trigger.MEMORIZED_EVENT
    entry = Transition(1.0, from_mode, Mode.LOAD, trigger, "Reach-Load event", code=code)
    with pytest.raises(ConfigError) as refused:
        TrialResult(controller=controller, transitions=(entry,), final_mode=Mode.LOAD)
    assert words in str(refused.value), refused.value
    TrialResult(controller="taxel_aware", final_mode=Mode.LOAD, transitions=(
        Transition(1.0, Mode.REACH, Mode.LOAD, Trigger.MEMORIZED_EVENT, "Reach-Load event",
                   code="reach_event"),))


def test_the_search_starts_at_the_last_entry_before_the_last_event_transition():
    """First contact and the settled grip after the last Reach before them, the table touch
    after the last Place; a Reach entered after the Load-Lift does not move its start."""
    from tegrasp_drake.scenario.physical_event_search import physical_event_search_starts
    timeline = [Transition(1.0, Mode.REACH, Mode.RE_REACH, Trigger.CORRECTIVE, "one-sided"),
                Transition(2.0, Mode.RE_REACH, Mode.REACH, Trigger.CORRECTIVE, "re-centred"),
                _reach_load(3.0), _load_lift(4.0),
                Transition(5.0, Mode.LIFT, Mode.HOLD, Trigger.TIMER, "lift motion ended"),
                Transition(8.0, Mode.HOLD, Mode.PLACE, Trigger.TIMER, "held 3 s"),
                Transition(9.0, Mode.PLACE, Mode.UNLOAD, Trigger.MEMORIZED_EVENT, "touch")]
    assert physical_event_search_starts(timeline) == {
        "reach_load": 2.0, "load_lift": 2.0, "place_unload": 8.0}
    assert physical_event_search_starts(timeline[2:4]) == {"reach_load": 0.0, "load_lift": 0.0}


def test_a_latency_is_its_detections_time_minus_its_events_to_round_off():
    """A latency written by hand from a decimal (its event the detection's time minus it)
    reads; one off by a nanosecond does not. The latency is the last detection's counted."""
    again = (Transition(1.4, Mode.LOAD, Mode.RE_REACH, Trigger.CORRECTIVE, "no Load-Lift event"),
             Transition(2.0, Mode.RE_REACH, Mode.REACH, Trigger.CORRECTIVE, "re-centred"),
             _reach_load(3.3))
    for latency in (0.05, 0.043, 1e-3, 0.0):
        TrialResult(transitions=(_reach_load(3.3),), final_mode=Mode.LOAD,
                    physical_events={"reach_load": 3.3 - latency},
                    detection_latency_s={"reach_load": latency})
    TrialResult(transitions=(_reach_load(1.0), *again), final_mode=Mode.LOAD,
                physical_events={"reach_load": 3.3 - 0.043},
                detection_latency_s={"reach_load": 0.043}, corrective_actions=["re_reach"])
    with pytest.raises(ConfigError, match="off by 1e-09 s"):
        TrialResult(transitions=(_reach_load(3.3),), final_mode=Mode.LOAD,
                    physical_events={"reach_load": 3.3 - 0.043},
                    detection_latency_s={"reach_load": 0.043 + 1e-9})
    with pytest.raises(ConfigError, match=r"must be transitions\[3\].t - physical_events"):
        TrialResult(transitions=(_reach_load(1.0), *again), final_mode=Mode.LOAD,
                    physical_events={"reach_load": 2.5},
                    detection_latency_s={"reach_load": 0.043}, corrective_actions=["re_reach"])
    # The first detection's event, before the Reach the last detection came in.
    with pytest.raises(ConfigError, match="'physical_events.reach_load' is 0.957 s, before 2 s"):
        TrialResult(transitions=(_reach_load(1.0), *again), final_mode=Mode.LOAD,
                    physical_events={"reach_load": 1.0 - 0.043},
                    detection_latency_s={"reach_load": 0.043}, corrective_actions=["re_reach"])


def test_the_failure_is_the_reason_of_the_transition_to_failed():
    lost = Transition(2.0, Mode.LOAD, Mode.FAILED, Trigger.THRESHOLD,
                      "object lost: no finger in contact")
    TrialResult(transitions=(_reach_load(1.0), lost), final_mode=Mode.FAILED,
                failure="object lost: no finger in contact")
    for failure in ("", "dropped in Hold"):
        with pytest.raises(ConfigError, match=r"field 'failure' must be the reason of "
                                              r"transitions\[1\], the first to Failed, "
                                              "'object lost: no finger in contact'"):
            TrialResult(transitions=(_reach_load(1.0), lost), final_mode=Mode.FAILED,
                        failure=failure)


def test_a_physical_event_needs_its_transition_taken():
    with pytest.raises(ConfigError, match="field 'physical_events.place_unload' but no "):
        TrialResult(transitions=(_reach_load(1.0),), final_mode=Mode.LOAD,
                    physical_events={"reach_load": 0.95, "place_unload": 2.0})
    TrialResult(transitions=(_reach_load(1.0),), final_mode=Mode.LOAD,
                physical_events={"reach_load": 0.95, "hit": 2.0})


def test_a_release_height_needs_an_unload_and_an_older_result_has_none():
    with pytest.raises(ConfigError, match="field 'release_height_m' is 0.06 but no transition "
                                          "goes to Unload"):
        TrialResult(transitions=(_reach_load(1.0),), final_mode=Mode.LOAD,
                    release_height_m=0.06)
    with pytest.raises(ConfigError, match="field 'release_height_m' must be a finite number"):
        TrialResult(release_height_m=float("nan"))
    stored = json.loads(RECORD.read_text())["result"]
    assert "release_height_m" not in stored  # written before the field
    assert TrialResult.from_dict(stored).release_height_m is None
    assert TrialResult.from_dict({**stored, "release_height_m": 0.06}).release_height_m == 0.06


def test_a_lift_grip_fraction_needs_a_lift_from_load():
    with pytest.raises(ConfigError, match="field 'lift_grip_fraction' is 5 but no transition"):
        TrialResult(transitions=(_reach_load(1.0),), final_mode=Mode.LOAD,
                    lift_grip_fraction=5.0)
    TrialResult(transitions=(_reach_load(1.0), _load_lift(2.0)), final_mode=Mode.LIFT,
                lift_grip_fraction=5.0)


@pytest.mark.parametrize("data", [None, "controller", ["transitions"], 3])
def test_from_dict_of_what_is_not_a_dict_is_a_type_error_naming_the_argument(data):
    with pytest.raises(TypeError, match=r"^TrialResult.from_dict: argument 'data' must be a "
                       r"dict \(a trial result's JSON form\), got "):
        TrialResult.from_dict(data)
