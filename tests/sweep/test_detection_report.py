"""Detection quality per trigger and McNemar comparisons from sweep records."""

import pytest

from tegrasp_drake.sweep.detection_report import (
    corrective_counts, event_trigger_rows, hit_avoid_rows, paired_comparison, report_markdown)
from tests.fake_trials import whole_result


def chain(*steps) -> list[dict]:
    """A timeline from Reach through `steps`, each (t, to, trigger, reason): every transition
    leaves the mode the one before it entered, as a trial's do."""
    timeline, mode = [], "Reach"
    for t, to, trigger, reason in steps:
        timeline.append({"t": t, "from": mode, "to": to, "trigger": trigger, "reason": reason})
        mode = to
    return timeline


RE_REACH = ((3.0, "Re-Reach", "corrective", "only the left finger touched"),
            (3.4, "Reach", "corrective", "re-centred"))


def record(controller, pair, *, hold=True, unload=None, reach_t=4.05, well_placed=False):
    """A record that re-centred once (one Re-Reach) before its Reach-Load detection at
    reach_t; unload: as hold unless given (a trial unloads only after it held)."""
    unload = hold if unload is None else unload
    steps = RE_REACH + ((reach_t, "Load", "memorized_event", "Reach-Load event"),)
    if unload:  # a trial judged unloaded ends Done
        steps += ((12.0, "Done", "timer", "the test's timeline"),)
    return {"trial_id": f"{controller}/{pair}",
            "trial": {"controller": controller, "pair_id": pair, "well_placed": well_placed},
            "result": whole_result(**{"transitions": chain(*steps), "hold_success": hold,
                                      "unload_success": unload, "released": unload,
                                      "final_mode": "Done" if unload else "Load",
                                      "corrective_actions": ["re_reach"],
                                      "physical_events": {"reach_load": 4.0}})}


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
    text = report_markdown(records, ["taxel_aware", "open_loop"], "open_loop", "t")
    assert "| taxel_aware | misplaced hold | 8 |" in text


def test_corrective_actions_are_counted_once_per_trial():
    """Two Re-Reaches, then a re-grasp of the object held tilted (a taxel_aware trial)."""
    steps = RE_REACH + ((3.6, "Re-Reach", "corrective", "only the left finger touched"),
                        (4.0, "Reach", "corrective", "re-centred"),
                        (4.6, "Load", "memorized_event", "Reach-Load event"),
                        (4.65, "Lift", "memorized_event", "Load-Lift event"),
                        (6.15, "Hold", "timer", "lift motion ended"),
                        (6.3, "Place", "corrective", "held tilted: put down to re-grasp"),
                        (8.8, "Re-Reach", "corrective", "re-grasp: open and close again"),
                        (10.4, "Reach", "corrective", "re-centred"),
                        (11.6, "Load", "memorized_event", "Reach-Load event"))
    result = whole_result(transitions=chain(*steps), hold_success=False, final_mode="Load",
                          corrective_actions=["re_reach", "re_reach", "regrasp"])
    records = {"a": {"trial": {"controller": "taxel_aware", "pair_id": "a",
                               "well_placed": False}, "result": result}}
    assert corrective_counts(records)["taxel_aware"] == {"re_reach": 1, "regrasp": 1}


def hit_record(controller, pair, *, hit, avoids=(), trigger="corrective_event",
               hold_at=5.5):
    """A trial in Hold from hold_at [s], hit at `hit` (None: no hit), Avoids at `avoids`."""
    transitions = [{"t": 4.0, "from": "Reach", "to": "Load", "trigger": "memorized_event",
                    "reason": "Reach-Load event"},
                   {"t": 4.5, "from": "Load", "to": "Lift", "trigger": "memorized_event",
                    "reason": "Load-Lift event"},
                   {"t": hold_at, "from": "Lift", "to": "Hold", "trigger": "timer",
                    "reason": "lift motion ended"}]
    for t in avoids:
        transitions += [{"t": t, "from": "Hold", "to": "Avoid", "trigger": trigger,
                         "reason": "hit"},
                        {"t": t + 0.6, "from": "Avoid", "to": "Hold", "trigger": "timer",
                         "reason": "avoiding motion ended"}]
    transitions.append({"t": transitions[-1]["t"] + 5.0, "from": "Hold", "to": "Done",
                        "trigger": "timer", "reason": "the test's timeline"})
    events = {"reach_load": 3.95} if hit is None else {"reach_load": 3.95, "hit": hit}
    return {"trial": {"controller": controller, "pair_id": pair, "well_placed": True},
            "result": whole_result(transitions=transitions, hold_success=True,
                                   unload_success=True, final_mode="Done", released=True,
                                   corrective_actions=["avoid"] * len(avoids),
                                   physical_events=events)}


def test_a_hit_in_hold_is_detected_missed_or_preceded_by_a_false_avoid():
    records = {
        "on_time": hit_record("memorized", "a", hit=7.1, avoids=(7.115,)),
        "slow": hit_record("memorized", "b", hit=7.1, avoids=(7.16,)),
        "missed": hit_record("memorized", "c", hit=7.1),
        "early": hit_record("memorized", "d", hit=7.1, avoids=(6.5, 7.11)),
        "no_hit": hit_record("memorized", "e", hit=None, avoids=(6.0,)),
        "quiet": hit_record("memorized", "f", hit=None),
        # Hit before Hold (still lifting): not a hit in Hold, not counted as one.
        "in_lift": hit_record("memorized", "g", hit=5.0, hold_at=5.5),
        "threshold": hit_record("heuristic", "a", hit=7.1, avoids=(7.105,),
                                trigger="threshold"),
    }
    memorized, heuristic = sorted(hit_avoid_rows(records), key=lambda r: r.controller,
                                  reverse=True)
    assert memorized.controller == "memorized"
    assert (memorized.hits_in_hold, memorized.detected, memorized.missed) == (4, 3, 1)
    assert (memorized.false, memorized.reached_hold) == (2, 7)
    assert memorized.median_latency_s == pytest.approx(0.015)
    assert memorized.triggers == ("corrective_event",)
    assert (heuristic.detected, heuristic.triggers) == (1, ("threshold",))
    text = report_markdown(records, ["memorized", "heuristic"], "heuristic", "t")
    assert "| memorized | corrective_event | 4 | 3 | 1 | 2 of 7 | 15 ms |" in text


def test_a_sweep_without_hits_or_avoids_has_no_hit_rows():
    records = {"a": record("taxel_aware", "a")}
    assert hit_avoid_rows(records) == []
    assert "Hit in Hold" not in report_markdown(records, ["taxel_aware"], "taxel_aware", "t")
