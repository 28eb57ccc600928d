"""The results table from sweep records: success beside false triggers and latency, made
by the reports; the results page (docs/results.md) kept equal to its results folders and
naming the commit of each folder's records."""

import pathlib

import pytest

from tegrasp_drake.reports import write_reports
from tegrasp_drake.sweep import SweepSpec, expand_trials, make_record
from tegrasp_drake.sweep.summary import (PAPER_ROW_NAME, RESULTS_BLOCK, RECORDS_LINE, last_commit,
                                         page_with_record_commits, readme_with_summaries,
                                         summary_rows)
from tests.fake_trials import result_of_trial, whole_result

ROOT = pathlib.Path(__file__).resolve().parents[2]
RESULTS_PAGE = ROOT / "docs" / "results.md"


FAILURE = "the object still slips after 2 Lift-Load corrections"


def result(hold, *, latency=None, false_triggers=0, trigger="timer"):
    """A trial through the grasp's modes, to Done when it held, else to Failed from Lift; its
    event transitions taken by `trigger`, each given in `latency` [s] that far behind its
    physical event."""
    latency = latency or {}
    steps = [(4.0, "Reach", "Load", trigger), (4.5, "Load", "Lift", trigger)]
    steps += ([(6.0, "Lift", "Hold", "timer"), (9.0, "Hold", "Place", "timer"),
               (10.5, "Place", "Unload", trigger), (11.5, "Unload", "Done", "timer")]
              if hold else [(5.0, "Lift", "Failed", "corrective")])
    timeline = [{"t": t, "from": start, "to": end, "trigger": by,
                 "reason": FAILURE if end == "Failed" else "the test's timeline"}
                for t, start, end, by in steps]
    events = {f"{start}_{end}".lower(): t - latency[f"{start}_{end}".lower()]
              for t, start, end, _ in steps if f"{start}_{end}".lower() in latency}
    return whole_result(hold_success=hold, unload_success=hold, released=hold,
                        transitions=timeline, final_mode="Done" if hold else "Failed",
                        failure="" if hold else FAILURE, corrective_actions=[],
                        physical_events=events, detection_latency_s=latency,
                        false_triggers=false_triggers, sim_time_s=12.0, wall_time_s=25.0)


def records(objects=("box", "thick_cylinder", "thin_cylinder")):
    """Memorized: the well-placed trial of each object fails, latencies 0.1-0.3 s, one false
    trigger in every fourth trial; heuristic: all succeed with a false Load-Lift each;
    open loop: no event triggers."""
    made = []
    spec = SweepSpec(objects=objects, attempts=1)
    for k, trial in enumerate(expand_trials(spec)):
        index = k % 9  # the trial's marker, per (controller, object)
        if trial.controller == "memorized":
            held = not trial.well_placed  # a failed trial never reached Place
            latency = {"reach_load": 0.1 + 0.01 * index, "load_lift": 0.2,
                       **({"place_unload": 0.3} if held else {})}
            r = result(held, latency=latency, false_triggers=int(index % 4 == 0),
                       trigger="memorized_event")
        elif trial.controller == "heuristic":
            r = result(True, latency={"reach_load": 0.05, "place_unload": 0.01},
                       false_triggers=1, trigger="heuristic_event")
        else:
            r = result(True)
        made.append(make_record(trial.to_dict(), result=result_of_trial(r, trial.to_dict())))
    return made


def by_controller(rows):
    return {cells[0]: cells for cells in rows}


def test_success_false_triggers_and_latency_per_controller():
    header, rows = summary_rows(records())
    assert header == ["controller", "well-placed ~Hold", "~Unload", "misplaced ~Hold",
                      "~Unload", "false triggers", "Reach-Load latency",
                      "Load-Lift latency", "Place-Unload latency"]
    table = by_controller(rows)
    memorized = table["memorized triggers"]
    assert memorized[1] == "0 % (0/3)"  # the centre marker's trial fails on every object
    assert memorized[3] == "100 % (24/24)"
    assert memorized[5] == "33 % (9/27)"      # markers 0, 4 and 8 of each object
    assert memorized[6] == "0.140 s (27)"     # median of 0.10 ... 0.18
    heuristic = table["heuristic thresholds"]
    assert heuristic[5] == "100 % (27/27)" and heuristic[7] == "–"  # no on-time Load-Lift
    assert table["open loop"][5:] == ["–"] * 4  # no event triggers: neither rate nor latency
    assert table[PAPER_ROW_NAME] == [PAPER_ROW_NAME, "100 %", "89 %", "86 %", "69 %",
                                     "–", "–", "–", "–"]


def test_the_papers_row_only_beside_the_papers_three_objects():
    _, rows = summary_rows(records(objects=("box",)))
    assert PAPER_ROW_NAME not in by_controller(rows)


def test_the_reports_write_the_summary(tmp_path):
    from tegrasp_drake.sweep.records import write_record
    for record in records(objects=("box",)):
        write_record(tmp_path, record)
    paths = write_reports(tmp_path)
    assert tmp_path / "summary.md" in paths
    assert "| memorized triggers | 0 % (0/1) |" in (tmp_path / "summary.md").read_text()


def test_the_results_pages_tables_are_those_of_their_results_folders():
    text = RESULTS_PAGE.read_text(encoding="utf-8")
    folders = [m["folder"] for m in RESULTS_BLOCK.finditer(text)]
    assert "../analysis/results_seed0" in folders and len(folders) >= 7
    assert readme_with_summaries(text, RESULTS_PAGE.parent) == text, (
        "a table of docs/results.md differs from its folder's records: run "
        "`python analysis/update_results_page.py`")


def test_the_results_page_names_the_commit_of_each_tables_records():
    text = RESULTS_PAGE.read_text(encoding="utf-8")
    named = {m["path"] for m in RECORDS_LINE.finditer(text)}
    for match in RESULTS_BLOCK.finditer(text):
        assert match["folder"].removeprefix("../") + "/trials" in named, match["folder"]
    if last_commit(ROOT, "analysis/results_seed0/trials") is None:
        pytest.skip("not a git checkout: the commits cannot be read")
    assert page_with_record_commits(text, ROOT) == text, (
        "docs/results.md names another commit than the last one of some records: run "
        "`python analysis/update_results_page.py`")


def test_a_stale_commit_is_replaced_and_an_abbreviation_of_the_right_one_kept():
    def commit_of(root, path):
        return {"a/trials": ("0123456789abcdef", "0123456", "2026-11-24")}.get(path)
    stale = "Records `a/trials`, commit `fedcba9` (2026-01-01).\nrecords `b/trials`, commit\n`1234567` (2026-01-02)."
    assert page_with_record_commits(stale, ".", commit_of) == (
        "Records `a/trials`, commit `0123456` (2026-11-24).\n"
        "records `b/trials`, commit\n`1234567` (2026-01-02).")
    kept = "Records `a/trials`, commit `01234567` (2026-11-24)"
    assert page_with_record_commits(kept, ".", commit_of) == kept


def test_a_readme_without_the_block_or_records_is_an_error(tmp_path):
    with pytest.raises(ValueError, match="results table from FOLDER"):
        readme_with_summaries("# no table here\n", tmp_path)
    block = "<!-- results table from empty -->\nold\n<!-- end of results table -->\n"
    with pytest.raises(ValueError, match="no trial records"):
        readme_with_summaries(block, tmp_path)


# Rule: a results folder's reports are each written through a staging file and a rename: a
# write killed past its handlers (SIGKILL) leaves the earlier reports whole, and the next
# write leaves the reports and nothing beside them.
def test_a_killed_report_write_keeps_the_earlier_reports_and_the_next_leaves_no_leftover(
        tmp_path):
    import subprocess
    import sys
    from tests.killed_runs import environment, killed_before_rename
    from tegrasp_drake.reports import report_starts
    from tegrasp_drake.sweep.records import write_record
    for record in records(objects=("box",)):
        write_record(tmp_path, record)
    earlier = {name: start + "the earlier report" for name, start in report_starts().items()}
    for name, text in earlier.items():
        (tmp_path / name).write_bytes(text.encode())
    statements = ("from tegrasp_drake.reports import write_reports\n"
                  f"write_reports({str(tmp_path)!r})")
    killed_before_rename(statements)
    assert all((tmp_path / name).read_bytes() == text.encode() for name, text in earlier.items())
    subprocess.run([sys.executable, "-c", statements], env=environment(), check=True,
                   timeout=300)  # a bound on a hang, not a measure of speed
    assert not [path.name for path in tmp_path.iterdir() if path.name.startswith(".")]
    assert all((tmp_path / name).read_bytes() != text.encode() for name, text in earlier.items())


# Rule: writing a results folder's reports parses each record's result once, not once for
# every table and figure that reads it; outside write_reports every call parses it again.
def test_the_reports_parse_each_records_result_once(tmp_path, monkeypatch):
    from tegrasp_drake.scenario.trial_result import TrialResult
    from tegrasp_drake.sweep.records import record_result, write_record
    written = records(objects=("box",))
    for record in written:
        write_record(tmp_path, record)
    parsed = []
    from_dict = TrialResult.from_dict.__func__

    def counted(cls, data):
        parsed.append(data)
        return from_dict(cls, data)
    monkeypatch.setattr(TrialResult, "from_dict", classmethod(counted))
    write_reports(tmp_path)
    finished = [record for record in written if record["result"] is not None]
    # each twice: once when load_records checks it, once for all the tables and figures
    assert len(parsed) == 2 * len(finished)
    parsed.clear()
    record_result(finished[0])
    record_result(finished[0])
    assert len(parsed) == 2
