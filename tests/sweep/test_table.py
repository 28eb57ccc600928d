"""Table I, statistics and success maps from a hand-made set of records."""

import csv
import json

import pytest

from tegrasp_drake.figures.sweep import success_grids, write_success_maps
from tegrasp_drake.sweep.records import make_record
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tegrasp_drake.sweep.table import (
    PAPER_TABLE1,
    controller_statistics,
    exact_mcnemar_p_value,
    paired_comparisons,
    table1_rows,
    write_statistics,
    write_table1,
)
from tests.fake_trials import whole_result

# Successes out of (3 well-placed, 24 misplaced) trials that reproduce the paper's
# Table I: (well hold, well unload, misplaced hold, misplaced unload).
PAPER_COUNTS = {"box": (3, 3, 24, 24), "thick_cylinder": (3, 3, 20, 20),
                "thin_cylinder": (3, 2, 18, 6)}


LOAD_T = 4.0  # [s] the Reach-Load transition of result()'s timeline
FAILURE = "the object still slips after 2 Lift-Load corrections"


def result(hold, unload, *, re_reaches=0, reach_latency=None, **extra):
    """A trial that re-centred `re_reaches` times, went to Load at LOAD_T (the Reach-Load
    event, its latency `reach_latency` behind first contact, if given), and ended Done when
    unloaded, else Failed."""
    timeline = []
    for k in range(re_reaches):
        timeline += [{"t": 1.0 + 0.8 * k, "from": "Reach", "to": "Re-Reach",
                      "trigger": "corrective", "reason": "only the left finger touched"},
                     {"t": 1.4 + 0.8 * k, "from": "Re-Reach", "to": "Reach",
                      "trigger": "corrective", "reason": "re-centred"}]
    timeline.append({"t": LOAD_T, "from": "Reach", "to": "Load", "trigger": "memorized_event",
                     "reason": "Reach-Load event"})
    timeline.append({"t": 9.0, "from": "Load", "to": "Done" if unload else "Failed",
                     "trigger": "timer" if unload else "corrective",
                     "reason": "the test's timeline" if unload else FAILURE})
    latency = {} if reach_latency is None else {"reach_load": reach_latency}
    return whole_result(**{
        "hold_success": hold, "unload_success": unload, "released": unload,
        "transitions": timeline, "final_mode": "Done" if unload else "Failed",
        "failure": "" if unload else FAILURE, "corrective_actions": ["re_reach"] * re_reaches,
        "physical_events": {"reach_load": LOAD_T - reach_latency} if latency else {},
        "detection_latency_s": latency, "false_triggers": 0,
        "sim_time_s": 10.0, "wall_time_s": 20.0, **extra})


def paper_records():
    """Memorized trials with the paper's outcomes; open loop fails every trial but the
    well-placed box, which errors once."""
    records, seen = [], {}
    for trial in expand_trials(SweepSpec(controllers=("memorized", "open_loop"))):
        t = trial.to_dict()
        if trial.controller == "open_loop":
            if trial.pair_id == "box/m11/a2":
                records.append(make_record(t, error={"type": "RuntimeError",
                                                     "message": "x", "traceback": ""}))
            else:
                records.append(make_record(t, result=result(trial.well_placed, False)))
            continue
        counts = PAPER_COUNTS[trial.object_name]
        hold_n, unload_n = counts[:2] if trial.well_placed else counts[2:]
        key = (trial.object_name, trial.well_placed)
        k = seen[key] = seen.get(key, -1) + 1   # k-th trial of this group
        records.append(make_record(t, result=result(
            k < hold_n, k < unload_n, re_reaches=k % 3, reach_latency=0.01 * (k + 1),
            false_triggers=int(k == 0))))
    return records


@pytest.fixture(scope="module")
def records():
    return paper_records()


def test_table_reproduces_the_papers_numbers(records):
    rows = {(r.controller, r.object_name): r for r in table1_rows(records)}
    for object_name in ("box", "thick_cylinder", "thin_cylinder", "average"):
        row = rows[("memorized", object_name)]
        assert [round(c.percent) for c in row.cells] == list(PAPER_TABLE1[object_name])
        assert row.paper_percent == PAPER_TABLE1[object_name]
    thin = rows[("memorized", "thin_cylinder")]
    assert [(c.successes, c.trials) for c in thin.cells] == [(3, 3), (2, 3), (18, 24), (6, 24)]
    average = rows[("memorized", "average")]
    assert [(c.successes, c.trials) for c in average.cells] == [
        (9, 9), (8, 9), (62, 72), (50, 72)]
    # The mean of the objects' rates (as the paper), not the pooled rate 50/72 = 69.4 %.
    assert average.cells[3].percent == pytest.approx((100 + 100 * 20 / 24 + 25) / 3)


def test_errors_are_counted_apart_from_the_rates(records):
    rows = {(r.controller, r.object_name): r for r in table1_rows(records)}
    box = rows[("open_loop", "box")]
    assert box.errors == 1 and rows[("open_loop", "average")].errors == 1
    assert (box.cells[0].successes, box.cells[0].trials) == (2, 2)
    assert (box.cells[1].successes, box.cells[1].trials) == (0, 2)
    assert rows[("open_loop", "thin_cylinder")].cells[2].percent == 0.0


def test_an_unload_without_a_hold_is_refused_not_counted():
    trial = expand_trials(SweepSpec(objects=("box",), controllers=("memorized",),
                                    grid=((0.0, 0.0),), attempts=1))[0].to_dict()
    with pytest.raises(ValueError, match="'unload_success' is true but 'hold_success'"):
        table1_rows([make_record(trial, result=result(False, True))])


def test_markdown_and_csv_files(records, tmp_path):
    markdown_path, csv_path = write_table1(records, tmp_path)
    markdown = markdown_path.read_text()
    assert "## memorized triggers (the paper's method)" in markdown
    assert "| Thin cylinder | 100% (3/3) | 100% | 67% (2/3) | 67% | 75% (18/24) | 75% | " \
           "25% (6/24) | 25% | 0 |" in markdown
    assert "| Average | 100% (9/9) | 100% | 89% (8/9) | 89% | 86% (62/72) | 86% | " \
           "69% (50/72) | 69% | 0 |" in markdown
    with open(csv_path, newline="") as file:
        rows = {(r["controller"], r["object"]): r for r in csv.DictReader(file)}
    thick = rows[("memorized", "thick_cylinder")]
    assert thick["misplaced_hold_successes"] == "20" and thick["misplaced_hold_trials"] == "24"
    assert thick["misplaced_hold_percent"] == "83.33"
    assert thick["paper_misplaced_hold_percent"] == "83"
    assert rows[("open_loop", "box")]["errors"] == "1"
    assert len(rows) == 8


def test_user_objects_have_no_paper_numbers(tmp_path):
    from tegrasp_drake.rig.objects import ObjectConfig
    spec = SweepSpec(objects=("box", "mug"), controllers=("memorized",), attempts=1,
                     user_objects={"mug": ObjectConfig(name="mug", shape="cylinder",
                                                        size=[0.04, 0.1], mass=0.3,
                                                        friction=0.6)})
    records = [make_record(t.to_dict(), result=result(True, True))
               for t in expand_trials(spec)]
    rows = {r.object_name: r for r in table1_rows(records)}
    assert rows["mug"].paper_percent is None and rows["average"].paper_percent is None
    assert rows["box"].paper_percent == PAPER_TABLE1["box"]


def test_statistics_of_latency_actions_and_false_triggers(records, tmp_path):
    statistics = controller_statistics(records)
    memorized = statistics["memorized"]
    assert memorized["trials"] == 81 and statistics["open_loop"]["errors"] == 1
    reach = memorized["detection_latency_s"]["reach_load"]
    # Per object: 3 well-placed latencies 0.01..0.03 and 24 misplaced 0.01..0.24.
    values = sorted([0.01 * (k + 1) for k in range(3)] * 3
                    + [0.01 * (k + 1) for k in range(24)] * 3)
    assert reach["n"] == 81 and reach["median"] == pytest.approx(values[40])
    assert reach["p90"] == pytest.approx(values[72])  # linear percentile, 0.9 x 80
    re_reaches = 3 * (1 + 2 + 8 * 1 + 8 * 2)  # k % 3 over k < 3 and k < 24, three objects
    assert memorized["corrective_actions"]["counts"] == {"re_reach": re_reaches}
    assert memorized["false_triggers"]["total"] == 6  # k == 0 in six groups
    paths = write_statistics(records, tmp_path)
    assert "| reach_load | 81 | 0 |" in paths[0].read_text()
    assert json.loads(paths[1].read_text())["controllers"]["memorized"]["trials"] == 81


def test_paired_comparison_uses_the_same_scenes(records):
    hold = [c for c in paired_comparisons(records) if c["phase"] == "hold"][0]
    assert (hold["controller_a"], hold["controller_b"]) == ("memorized", "open_loop")
    assert hold["pairs"] == 80  # the errored open-loop trial has no pair
    assert hold["a_success"] == 9 + 62 - 1 and hold["b_success"] == 8
    assert hold["b_only"] == 0 and hold["a_only"] == 62
    assert hold["p_value"] == pytest.approx(2 * 0.5 ** 62)


def test_exact_mcnemar_p_values():
    assert exact_mcnemar_p_value(0, 0) == 1.0
    assert exact_mcnemar_p_value(3, 3) == 1.0
    assert exact_mcnemar_p_value(5, 0) == pytest.approx(2 / 32)
    assert exact_mcnemar_p_value(1, 4) == pytest.approx(2 * 6 / 32)


def test_success_map_grids_and_png(records, tmp_path):
    xs, ys, grids = success_grids(records)
    assert list(xs) == [-10.0, 0.0, 10.0] and list(ys) == [-15.0, 0.0, 15.0]
    successes, trials = grids[("memorized", "thin_cylinder", "unload")]
    assert trials.sum() == 27 and trials[1, 1] == 3 and successes[1, 1] == 2
    assert successes.sum() == 2 + 6
    path = write_success_maps(records, tmp_path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert path.stat().st_size > 20_000
