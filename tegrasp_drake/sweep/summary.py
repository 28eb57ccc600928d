"""The results table of a sweep: per controller, Table I's average success rates beside its
false-trigger rate and detection latencies (median, over the trials where the event came on
time), and the paper's row. Made from a results folder's records only (`write_summary`);
analysis/update_results_page.py copies it into docs/results.md."""

import re
import subprocess
from pathlib import Path

from tegrasp_drake.control.controller_registry import controller_label
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS, transition_states
from tegrasp_drake.rig.report_files import write_report
from tegrasp_drake.sweep.records import load_records
from tegrasp_drake.sweep.table import AVERAGE, PAPER_TABLE1, controller_statistics, table1_rows

SUMMARY_FILE = "summary.md"
SUMMARY_START = "| controller | "  # the results table's header row, its first line
PAPER_ROW_NAME = "the paper (real robot, memorized)"
_SUCCESS_HEADERS = ("well-placed ~Hold", "~Unload", "misplaced ~Hold", "~Unload")
_NONE = "–"
# A page's block: `<!-- results table from FOLDER -->`, the table, `<!-- end ... -->`;
# FOLDER is relative to the page's folder.
RESULTS_BLOCK = re.compile(r"(<!-- results table from (?P<folder>\S+) -->\n)(?P<table>.*?)"
                          r"(<!-- end of results table -->)", re.DOTALL)
# A page's line naming the commit of some records: "Records `PATH`, commit `HASH`
# (YYYY-MM-DD)", PATH relative to the repository's root.
RECORDS_LINE = re.compile(r"[Rr]ecords\s+`(?P<path>[^`]+)`,\s+commit\s+`(?P<commit>[0-9a-f]{7,40})`"
                          r"\s+\((?P<date>\d{4}-\d{2}-\d{2})\)")


def _transition_title(name: str) -> str:
    try:
        return "-".join(transition_states(name))
    except ValueError:
        return name  # a name that is not `from_to` (hand-made records)


def _latency_columns(statistics) -> list[str]:
    names = {name for s in statistics.values() for name in s["detection_latency_s"]}
    return ([name for name in REQUIRED_TRANSITIONS if name in names]
            + sorted(names - set(REQUIRED_TRANSITIONS)))


def _percent(successes: int, trials: int, percent=None) -> str:
    if not trials:
        return _NONE
    percent = 100.0 * successes / trials if percent is None else percent
    return f"{percent:.0f} % ({successes}/{trials})"


def summary_rows(records) -> tuple[list[str], list[list[str]]]:
    """(header, rows) of the results table; the paper's row last when the sweep ran its objects."""
    records = list(records)
    statistics = controller_statistics(records)
    latency_columns = _latency_columns(statistics)
    header = (["controller", *_SUCCESS_HEADERS, "false triggers"]
              + [f"{_transition_title(name)} latency" for name in latency_columns])
    rows, paper_compares = [], False
    for row in table1_rows(records):
        if row.object_name != AVERAGE:
            continue
        paper_compares = row.paper_percent is not None  # the paper's three objects
        s = statistics.get(row.controller)
        cells = [controller_label(row.controller)]
        cells += [_percent(c.successes, c.trials, c.percent) for c in row.cells]
        detects = s is not None and (s["detection_latency_s"] or s["false_triggers"]["total"])
        if detects:
            cells.append(_percent(s["false_triggers"]["trials_with_any"], s["trials"]))
            for name in latency_columns:
                d = s["detection_latency_s"].get(name)
                cells.append(_NONE if d is None or d["median"] is None
                             else f"{d['median']:.3f} s ({d['n']})")
        else:
            cells += [_NONE] * (1 + len(latency_columns))
        rows.append(cells)
    if paper_compares:
        paper = [f"{percent} %" for percent in PAPER_TABLE1[AVERAGE]]
        rows.append([PAPER_ROW_NAME, *paper] + [_NONE] * (1 + len(latency_columns)))
    return header, rows


def summary_markdown(records) -> str:
    """The results table as Markdown (a page's block between its markers)."""
    header, rows = summary_rows(records)
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cells) + " |" for cells in rows]
    return "\n".join(lines) + "\n"


def write_summary(records, out_dir) -> list[Path]:
    """Writes `summary.md` into `out_dir` (atomically); returns its path in a list."""
    path = Path(out_dir) / SUMMARY_FILE
    write_report(path, summary_markdown(records), SUMMARY_START)
    return [path]


def readme_with_summaries(text: str, root) -> str:
    """`text` (a Markdown page) with each results-table block regenerated from the results folder
    its marker names (relative to `root`, the page's folder). ValueError when there is no block."""
    def regenerate(match):
        folder = Path(root) / match["folder"]
        if not folder.is_dir():
            raise ValueError(f"{folder}: no trial records for the page's results table (no "
                             "such folder)")
        records = load_records(folder).records.values()
        if not records:
            raise ValueError(f"{folder}: no trial records for the page's results table")
        return match[1] + summary_markdown(records) + match[4]
    if not RESULTS_BLOCK.search(text):
        raise ValueError("no `<!-- results table from FOLDER -->` ... "
                         "`<!-- end of results table -->` block")
    return RESULTS_BLOCK.sub(regenerate, text)


def last_commit(root, path) -> tuple[str, str, str] | None:
    """(full hash, short hash, YYYY-MM-DD) of the last commit changing `path` in `root`, or None."""
    try:
        done = subprocess.run(["git", "-C", str(root), "log", "-1", "--format=%H %h %ad",
                               "--date=short", "--", str(path)],
                              capture_output=True, text=True, timeout=60)
    except OSError:
        return None
    words = done.stdout.split()
    return tuple(words) if done.returncode == 0 and len(words) == 3 else None


def page_with_record_commits(text: str, root, commit_of=last_commit) -> str:
    """`text` with each "Records `PATH`, commit `HASH` (DATE)" naming the last commit that
    changed PATH; a HASH abbreviating it is kept, a PATH without one is left as it is."""
    def renamed(match):
        found = commit_of(root, match["path"])
        if found is None:
            return match[0]
        full, short, date = found
        commit = match["commit"] if full.startswith(match["commit"]) else short
        start = match.start()
        (c0, c1), (d0, d1) = match.span("commit"), match.span("date")
        line = match[0]
        return (line[:c0 - start] + commit + line[c1 - start:d0 - start] + date
                + line[d1 - start:])
    return RECORDS_LINE.sub(renamed, text)
