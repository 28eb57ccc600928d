"""Table I of the paper from sweep records, and statistics of the trials. "~Hold": held 3 s;
"~Unload": held, then placed upright (Sec. IV-C); the average row is the mean of the
objects' rates, as the paper's (docs/sweeps.md, "A sweep")."""

import csv
import io
import json
import math
from collections import Counter, defaultdict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tegrasp_drake.sweep.failure_classes import failure_class_counts, failure_classes_markdown
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_title
from tegrasp_drake.rig.report_files import write_report
from tegrasp_drake.sweep.records import mixed_records_problem, record_result
from tegrasp_drake.sweep.spec import BUILTIN_OBJECTS

# (placement, phase) columns of Table I, in the paper's order.
TABLE1_COLUMNS = (("well_placed", "hold"), ("well_placed", "unload"),
                  ("misplaced", "hold"), ("misplaced", "unload"))
AVERAGE = "average"
# The paper's Table I (percent), for the memorized-trigger method on the real robot.
PAPER_TABLE1 = {
    "box": (100, 100, 100, 100),
    "thick_cylinder": (100, 100, 83, 83),
    "thin_cylinder": (100, 67, 75, 25),
    AVERAGE: (100, 89, 86, 69),
}
_OBJECT_TITLES = {"box": "Box", "thick_cylinder": "Thick cylinder",
                  "thin_cylinder": "Thin cylinder", AVERAGE: "Average"}
_COLUMN_TITLES = ("Well-placed ~Hold", "Well-placed ~Unload",
                  "Misplaced ~Hold", "Misplaced ~Unload")


@dataclass(frozen=True)
class Table1Cell:
    successes: int
    trials: int
    percent: float | None  # None without trials


@dataclass(frozen=True)
class Table1Row:
    controller: str
    object_name: str                   # an object's name, or "average"
    cells: tuple[Table1Cell, ...]      # in TABLE1_COLUMNS order
    paper_percent: tuple[int, ...] | None
    errors: int


def succeeded(result, phase: str) -> bool:
    """A TrialResult's success in a phase: "hold", or "unload" (held, then placed upright)."""
    if phase == "hold":
        return result.hold_success
    return result.hold_success and result.unload_success


def ordered_names(names, preferred) -> list:
    """`names` in the `preferred` order, then the others sorted."""
    return [n for n in preferred if n in names] + sorted(set(names) - set(preferred))


def table1_rows(records) -> list[Table1Row]:
    """Table I rows per controller: one per object, then the average row; ValueError when
    the records are not one sweep's or records of one row matched against different memorized
    events (mixed_records_problem)."""
    records = list(records)
    problem = mixed_records_problem(records)
    if problem:
        raise ValueError(f"table1_rows: {problem}")
    counts = defaultdict(lambda: [0, 0])   # (controller, object, column) -> [succ, trials]
    errors = Counter()                     # (controller, object) -> error records
    controllers, objects = set(), set()
    for record in records:
        trial = record["trial"]
        key = (trial["controller"], trial["object_name"])
        controllers.add(key[0])
        objects.add(key[1])
        if record["status"] != "ok":
            errors[key] += 1
            continue
        placement = "well_placed" if trial["well_placed"] else "misplaced"
        for column in TABLE1_COLUMNS:
            if column[0] == placement:
                cell = counts[(*key, column)]
                cell[0] += succeeded(record_result(record), column[1])
                cell[1] += 1

    rows = []
    object_order = ordered_names(objects, BUILTIN_OBJECTS)
    for controller in ordered_names(controllers, CONTROLLER_NAMES):
        object_rows = []
        for object_name in object_order:
            cells = []
            for column in TABLE1_COLUMNS:
                s, n = counts[(controller, object_name, column)]
                cells.append(Table1Cell(s, n, 100.0 * s / n if n else None))
            object_rows.append(Table1Row(controller, object_name, tuple(cells),
                                         PAPER_TABLE1.get(object_name),
                                         errors[(controller, object_name)]))
        average_cells = []
        for i in range(len(TABLE1_COLUMNS)):
            cells = [row.cells[i] for row in object_rows if row.cells[i].trials]
            average_cells.append(Table1Cell(
                sum(c.successes for c in cells), sum(c.trials for c in cells),
                float(np.mean([c.percent for c in cells])) if cells else None))
        # The paper's average only compares with an average over the paper's objects.
        paper_average = PAPER_TABLE1[AVERAGE] if object_order == list(BUILTIN_OBJECTS) else None
        rows += object_rows + [Table1Row(controller, AVERAGE, tuple(average_cells),
                                         paper_average,
                                         sum(row.errors for row in object_rows))]
    return rows


def _percent_text(percent) -> str:
    return "–" if percent is None else f"{percent:.0f}%"


TABLE1_TITLE = "# Table I: grasping success rate for each object"


def table1_markdown(rows) -> str:
    lines = [TABLE1_TITLE, "",
             "~Hold: held the object for 3 s. ~Unload: held it and placed it upright. "
             "Well placed: the expected position (centre marker); misplaced: the other "
             "markers. Each cell: our rate (successes/trials), then the paper's rate "
             "(real robot, memorized triggers). Average: mean of the objects' rates, as in "
             "the paper; counts pooled. Errors: trials whose simulation raised, not counted."]
    header = ["Object"]
    for title in _COLUMN_TITLES:
        header += [title, "paper"]
    header.append("Errors")
    for controller in ordered_names({row.controller for row in rows}, CONTROLLER_NAMES):
        lines += ["", f"## {controller_title(controller)}", "",
                  "| " + " | ".join(header) + " |",
                  "|" + "---|" * len(header)]
        for row in rows:
            if row.controller != controller:
                continue
            cells = [_OBJECT_TITLES.get(row.object_name, row.object_name)]
            for i, cell in enumerate(row.cells):
                cells.append(f"{_percent_text(cell.percent)} ({cell.successes}/{cell.trials})")
                cells.append(_percent_text(row.paper_percent[i] if row.paper_percent else None))
            cells.append(str(row.errors))
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def title_start(title: str) -> str:
    """How a Markdown report of level-1 heading `title` (`# ...`) starts: that line."""
    return f"{title}\n"


def csv_header_text(header: list) -> str:
    """The header row of a CSV report (a CSV file of a table is known by it)."""
    text = io.StringIO()
    csv.writer(text).writerow(header)
    return text.getvalue()


def markdown_and_csv_starts(stem: str, title: str, header: list) -> dict[str, str]:
    """The file names of the report table `stem` and how each starts (report_files)."""
    return {f"{stem}.md": title_start(title), f"{stem}.csv": csv_header_text(header)}


def write_markdown_and_csv(out_dir, stem: str, title: str, markdown: str, header: list,
                           rows: list[list]) -> list[Path]:
    """Writes `stem`.md (the text `markdown`, opening on its title line `title`) and `stem`.csv
    (`header`, then `rows`) into `out_dir`, each atomically and only over an earlier report of
    its kind (write_report); returns their paths. Every report table of a results folder is
    written so."""
    out_dir = Path(out_dir)
    starts = markdown_and_csv_starts(stem, title, header)
    markdown_path, csv_path = out_dir / f"{stem}.md", out_dir / f"{stem}.csv"
    write_report(markdown_path, markdown, starts[markdown_path.name])
    rows_text = io.StringIO()
    csv.writer(rows_text).writerows(rows)
    write_report(csv_path, csv_header_text(header) + rows_text.getvalue(),
                 starts[csv_path.name])
    return [markdown_path, csv_path]


def table1_fieldnames() -> list[str]:
    """The columns of table1.csv."""
    fieldnames = ["controller", "object"]
    for placement, phase in TABLE1_COLUMNS:
        name = f"{placement}_{phase}"
        fieldnames += [f"{name}_successes", f"{name}_trials", f"{name}_percent",
                       f"paper_{name}_percent"]
    fieldnames.append("errors")
    return fieldnames


def table1_starts() -> dict[str, str]:
    """table1.md and table1.csv, and how each starts (report_files)."""
    return markdown_and_csv_starts("table1", TABLE1_TITLE, table1_fieldnames())


def write_table1(records, out_dir) -> list[Path]:
    """Writes `table1.md` and `table1.csv` into `out_dir`; returns their paths."""
    rows = table1_rows(records)
    fieldnames = table1_fieldnames()
    csv_rows = []
    for row in rows:
        values = [row.controller, row.object_name]
        for i, cell in enumerate(row.cells):
            values += [cell.successes, cell.trials,
                       "" if cell.percent is None else f"{cell.percent:.2f}",
                       "" if row.paper_percent is None else row.paper_percent[i]]
        values.append(row.errors)
        csv_rows.append(values)
    return write_markdown_and_csv(out_dir, "table1", TABLE1_TITLE, table1_markdown(rows),
                                  fieldnames, csv_rows)


# Statistics


def _distribution(values) -> dict:
    if not values:
        return {"n": 0, "median": None, "p90": None}
    return {"n": len(values), "median": float(np.median(values)),
            "p90": float(np.percentile(values, 90))}


def controller_statistics(records) -> dict:
    """Per controller: latencies, corrective actions, false triggers, errors, run times."""
    by_controller = defaultdict(list)
    for record in records:
        by_controller[record["trial"]["controller"]].append(record)
    statistics = {}
    for controller in ordered_names(by_controller, CONTROLLER_NAMES):
        results = [record_result(r) for r in by_controller[controller] if r["status"] == "ok"]
        latencies = defaultdict(list)
        missed = Counter()
        actions = Counter()
        trials_with_actions = 0
        for result in results:
            for transition, latency in result.detection_latency_s.items():
                if latency is None:
                    missed[transition] += 1
                else:
                    latencies[transition].append(latency)
            # A list of action names, or a mapping from name to count.
            taken = Counter(result.corrective_actions)
            actions.update({str(k): v for k, v in taken.items()})
            trials_with_actions += sum(taken.values()) > 0
        false_triggers = [result.false_triggers for result in results]
        statistics[controller] = {
            "trials": len(results),
            "errors": len(by_controller[controller]) - len(results),
            "detection_latency_s": {
                transition: {**_distribution(latencies[transition]),
                             "not_detected": missed[transition]}
                for transition in sorted(set(latencies) | set(missed))},
            "corrective_actions": {"trials_with_any": trials_with_actions,
                                   "counts": dict(sorted(actions.items()))},
            "false_triggers": {"total": int(sum(false_triggers)),
                               "trials_with_any": sum(f > 0 for f in false_triggers),
                               "mean_per_trial": (float(np.mean(false_triggers))
                                                  if false_triggers else None)},
            "sim_time_s": _distribution([r.sim_time_s for r in results
                                         if r.sim_time_s is not None]),
            "wall_time_s": _distribution([r.wall_time_s for r in results
                                          if r.wall_time_s is not None]),
        }
    return statistics


def exact_mcnemar_p_value(a_only: int, b_only: int) -> float:
    """Two-sided exact McNemar test: P(a split at least this uneven | no difference)."""
    n = a_only + b_only
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, k) for k in range(min(a_only, b_only) + 1)) / 2.0 ** n
    return min(1.0, 2.0 * tail)


def paired_comparisons(records) -> list[dict]:
    """Every pair of controllers on the trials both ran (same scene, same seed)."""
    outcomes = defaultdict(dict)  # controller -> pair_id -> result
    for record in records:
        if record["status"] == "ok":
            outcomes[record["trial"]["controller"]][record["trial"]["pair_id"]] = \
                record_result(record)
    controllers = ordered_names(outcomes, CONTROLLER_NAMES)
    comparisons = []
    for i, a in enumerate(controllers):
        for b in controllers[i + 1:]:
            shared = sorted(set(outcomes[a]) & set(outcomes[b]))
            for phase in ("hold", "unload"):
                a_ok = [succeeded(outcomes[a][p], phase) for p in shared]
                b_ok = [succeeded(outcomes[b][p], phase) for p in shared]
                a_only = sum(x and not y for x, y in zip(a_ok, b_ok))
                b_only = sum(y and not x for x, y in zip(a_ok, b_ok))
                comparisons.append({"controller_a": a, "controller_b": b, "phase": phase,
                                    "pairs": len(shared), "a_success": sum(a_ok),
                                    "b_success": sum(b_ok), "a_only": a_only,
                                    "b_only": b_only,
                                    "p_value": exact_mcnemar_p_value(a_only, b_only)})
    return comparisons


def _number_text(value, unit="") -> str:
    return "–" if value is None else f"{value:.3g}{unit}"


STATISTICS_TITLE = "# Trial statistics"


def statistics_starts() -> dict[str, str]:
    """statistics.md and statistics.json, and how each starts (report_files): the JSON
    object's first key, sorted first."""
    return {"statistics.md": title_start(STATISTICS_TITLE),
            "statistics.json": '{\n "controllers": '}


def statistics_markdown(statistics, comparisons) -> str:
    lines = [STATISTICS_TITLE, ""]
    for controller, s in statistics.items():
        lines += [f"## {controller_title(controller)}", "",
                  f"Trials: {s['trials']}, errors (not counted): {s['errors']}.", "",
                  "| Transition | Detected | Not detected | Latency median | Latency p90 |",
                  "|---|---|---|---|---|"]
        for transition, d in s["detection_latency_s"].items():
            lines.append(f"| {transition} | {d['n']} | {d['not_detected']} | "
                         f"{_number_text(d['median'], ' s')} | {_number_text(d['p90'], ' s')} |")
        actions = s["corrective_actions"]
        counts = ", ".join(f"{k} {v}" for k, v in actions["counts"].items()) or "none"
        ft = s["false_triggers"]
        lines += ["", f"Corrective actions: in {actions['trials_with_any']} trials; {counts}.",
                  f"False triggers: {ft['total']} in {ft['trials_with_any']} trials "
                  f"(mean {_number_text(ft['mean_per_trial'])} per trial).",
                  "Simulated time per trial: median "
                  f"{_number_text(s['sim_time_s']['median'], ' s')}; "
                  f"wall time per trial: median {_number_text(s['wall_time_s']['median'], ' s')}, "
                  f"p90 {_number_text(s['wall_time_s']['p90'], ' s')}.", ""]
    if comparisons:
        lines += ["## Paired comparisons (same scenes and seeds; exact McNemar test)", "",
                  "| A | B | Phase | Pairs | A success | B success | A only | B only | p |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for c in comparisons:
            lines.append(f"| {c['controller_a']} | {c['controller_b']} | {c['phase']} | "
                         f"{c['pairs']} | {c['a_success']} | {c['b_success']} | "
                         f"{c['a_only']} | {c['b_only']} | {c['p_value']:.3g} |")
    return "\n".join(lines) + "\n"


def write_statistics(records, out_dir) -> list[Path]:
    """Writes `statistics.md` and `statistics.json` into `out_dir` (each atomically); returns
    their paths."""
    records = list(records)
    statistics = controller_statistics(records)
    comparisons = paired_comparisons(records)
    out_dir = Path(out_dir)
    markdown_path, json_path = out_dir / "statistics.md", out_dir / "statistics.json"
    counted = failure_class_counts(records)
    failures = {controller: counted[controller] for controller in statistics
                if controller in counted}
    starts = statistics_starts()
    write_report(markdown_path, statistics_markdown(statistics, comparisons) + "\n"
                 + failure_classes_markdown(failures), starts[markdown_path.name])
    write_report(json_path, json.dumps({"controllers": statistics,
                                        "paired_comparisons": comparisons,
                                        "failure_classes": failures},
                                       indent=1, sort_keys=True) + "\n",
                 starts[json_path.name])
    return [markdown_path, json_path]
