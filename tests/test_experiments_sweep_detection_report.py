"""Detection quality per trigger and McNemar comparisons from sweep records (issue #14)."""

import pytest

from tegrasp_drake.experiments.sweep.detection_report import (
    corrective_counts, event_trigger_rows, mcnemar_p, paired_comparison, report_markdown)


def record(controller, pair, *, hold=True, unload=True, reach_t=4.05, well_placed=False,
           actions=()):
    transitions = [{"t": 3.0, "from": "Reach", "to": "Re-Reach", "trigger": "corrective"},
                   {"t": reach_t, "from": "Reach", "to": "Load",
                    "trigger": "memorized_event"}]
    return {"trial_id": f"{controller}/{pair}",
            "trial": {"controller": controller, "pair_id": pair, "well_placed": well_placed},
            "result": {"transitions": transitions, "hold_success": hold,
                       "unload_success": unload, "corrective_actions": list(actions),
                       "physical_events": {"reach_load": 4.0}}}


def test_a_late_match_is_detected_with_its_latency_and_an_early_one_is_false():
    records = {str(k): r for k, r in enumerate([record("memorized", "a", reach_t=4.05),
                                                record("memorized", "b", reach_t=4.03),
                                                record("memorized", "c", reach_t=3.5)])}
    (row,) = [r for r in event_trigger_rows(records) if r.trigger == "reach_load"]
    assert (row.trials, row.detected, row.false, row.other) == (3, 2, 1, 0)
    assert row.median_latency_s == pytest.approx(0.04)


def test_mcnemar_counts_the_discordant_pairs_of_the_same_scenes():
    records = {}
    for k in range(8):
        records[f"t{k}"] = record("taxel_aware", f"s{k}", hold=True)
        records[f"o{k}"] = record("open_loop", f"s{k}", hold=k < 2)
    records["lonely"] = record("taxel_aware", "other-scene", hold=False)
    c = paired_comparison(records, "taxel_aware", "open_loop", ("misplaced", "hold"))
    assert (c.pairs, c.only_first, c.only_second) == (8, 6, 0)
    assert c.p_value == pytest.approx(2 * 0.5 ** 6)
    assert mcnemar_p(0, 0) == 1.0
    text = report_markdown(records, ["taxel_aware", "open_loop"], "open_loop", "t")
    assert "| taxel_aware | misplaced hold | 8 |" in text


def test_corrective_actions_are_counted_once_per_trial():
    records = {"a": record("taxel_aware", "a", actions=("re_reach", "re_reach", "regrasp"))}
    assert corrective_counts(records)["taxel_aware"] == {"re_reach": 1, "regrasp": 1}
