"""analysis/check_rule_engine_equivalence.py compares two commits' result dicts: a base
whose timelines keep no rule codes is compared with this checkout's on what both record."""

from tests.analysis_script import load_analysis_script


def _script():
    return load_analysis_script("check_rule_engine_equivalence")


def _result(*codes, final_mode="Lift", wall_time_s=1.0):
    entries = [{"t": 3.6, "from": "Reach", "to": "Load", "trigger": "memorized_event",
                "reason": "Reach-Load event"},
               {"t": 3.7, "from": "Load", "to": "Lift", "trigger": "memorized_event",
                "reason": "Load-Lift event"}]
    for entry, code in zip(entries, codes):
        if code is not None:
            entry["code"] = code
    return {"transitions": entries, "final_mode": final_mode, "wall_time_s": wall_time_s}


def test_a_base_without_rule_codes_agrees_with_a_tip_that_has_them():
    differences = _script().differences
    uncoded, coded = _result(), _result("reach_event", "load_lift_event")
    assert differences(uncoded, _result(wall_time_s=9.0)) == []
    assert differences(uncoded, coded) == []
    assert differences(uncoded, _result("reach_event", "load_lift_event",
                                        final_mode="Hold")) == ["final_mode"]


def test_two_sides_that_both_keep_codes_differ_when_another_rule_decided():
    differences = _script().differences
    assert differences(_result("reach_event", "load_lift_event"),
                       _result("reach_event", "load_timeout")) == ["transitions"]
