"""TrialResult: the typed trial result and its JSON form, which sweep records keep."""

import json
import pathlib

from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
from tegrasp_drake.runs.trial_result import TrialResult
from tegrasp_drake.sweep.runner import check_result

RECORD = (pathlib.Path(__file__).resolve().parents[2] / "analysis" / "results_linkage"
          / "paper_grid" / "trials" / "taxel_aware.box.m02.a1.json")


def test_a_committed_records_result_reads_back_unchanged():
    stored = json.loads(RECORD.read_text())["result"]
    result = TrialResult.from_dict(stored)
    assert result.final_mode == Mode.DONE and result.entered(Mode.RE_REACH)
    written = result.to_dict()
    # Fields newer than the record (lift_grip_fraction) are added with their defaults.
    assert {key: written[key] for key in stored} == stored


def test_the_json_form_round_trips():
    result = TrialResult(object="box", controller="memorized", seed=600, hold_success=True,
                         transitions=(Transition(3.8, Mode.REACH, Mode.LOAD,
                                                 Trigger.MEMORIZED_EVENT, "Reach-Load event",
                                                 scores=(0.9, 0.9, 1.0, 1.0)),),
                         final_mode=Mode.LOAD, physical_events={"reach_load": 3.6})
    data = json.loads(json.dumps(result.to_dict()))
    assert data["final_mode"] == "Load" and data["transitions"][0]["from"] == "Reach"
    assert TrialResult.from_dict(data) == result
    assert "log" not in data


def test_a_sweep_refuses_a_result_whose_transitions_do_not_parse():
    entry = {"t": 1.0, "from": "reach", "to": "Load", "trigger": "memorized_event",
             "reason": "Reach-Load event"}
    problem = check_result({"hold_success": True, "unload_success": False,
                            "transitions": [entry]})
    assert problem and "'transitions'[0]" in problem and "reach" in problem
