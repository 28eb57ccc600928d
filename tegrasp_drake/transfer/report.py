"""The transfer matrix's table and heat map, from its cells' sweep records: per cell and
controller, match rates and latencies per event transition, false triggers, hold and unload
success and cost (docs/transfer.md, "A transfer sweep")."""

import dataclasses
import pathlib

import numpy as np

from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.figures.figure_files import figure_path, new_figure, save_figure
from tegrasp_drake.sweep.detection_report import event_trigger_rows
from tegrasp_drake.sweep.records import load_records, record_result
from tegrasp_drake.sweep.spec import expand_trials
from tegrasp_drake.transfer.matrix import cell_folder, cell_name, running_sweep
from tegrasp_drake.rig.files import is_folder
from tegrasp_drake.rig.report_files import write_report

TABLE_FILE = "transfer.md"
TABLE_START = "# Transfer matrix\n"  # its title line
FIGURE_STEM = "transfer_matrix"


@dataclasses.dataclass(frozen=True)
class CellRow:
    memorizing: str
    running: str
    controller: str
    trials: int  # finished
    planned: int  # the spec's trials of this cell and controller
    # per REQUIRED_TRANSITIONS: (detected, trials that waited for it, median latency [s])
    transitions: tuple[tuple[int, int, float | None], ...]
    false_triggers: int
    hold: int
    unload: int
    cpu_s: float | None  # median per trial
    sim_s: float | None

    @property
    def partly_run(self) -> bool:
        return self.trials < self.planned

    def trials_text(self) -> str:
        """"81" for a finished cell, "41/81 run" for one with trials still to run."""
        return f"{self.trials}/{self.planned} run" if self.partly_run else str(self.trials)

    def match_rate(self, k: int) -> float:
        detected, waited, _ = self.transitions[k]
        return detected / waited if waited else float("nan")


def cell_rows(spec, out_dir) -> list[CellRow]:
    """One CellRow per (cell, controller) with finished trials of the spec in `out_dir`
    (records of other trials in a cell's folder are left out, as the sweep's reports do)."""
    rows = []
    for memorizing, running in spec.cells:
        folder = cell_folder(out_dir, memorizing, running)
        if not is_folder(folder / "trials"):  # UserPathError when it cannot be looked at
            continue
        planned = {trial.trial_id: trial.controller
                   for trial in expand_trials(running_sweep(spec, running))}
        records = {trial_id: record for trial_id, record in load_records(folder).records.items()
                   if trial_id in planned and record.get("result") is not None}
        for controller in spec.sweep.controllers:
            mine = {k: r for k, r in records.items() if r["trial"]["controller"] == controller}
            if not mine:
                continue
            triggers = {row.trigger: row for row in event_trigger_rows(mine)}
            transitions = tuple(
                (triggers[t].detected, triggers[t].trials, triggers[t].median_latency_s)
                if t in triggers else (0, 0, None) for t in REQUIRED_TRANSITIONS)
            results = [record_result(r) for r in mine.values()]
            cpu = [r.cpu_time_s for r in results if r.cpu_time_s is not None]
            sim = [r.sim_time_s for r in results if r.sim_time_s is not None]
            rows.append(CellRow(
                memorizing, running, controller, len(results),
                sum(1 for c in planned.values() if c == controller), transitions,
                sum(int(r.false_triggers) for r in results),
                sum(bool(r.hold_success) for r in results),
                sum(bool(r.unload_success) for r in results),
                float(np.median(cpu)) if cpu else None, float(np.median(sim)) if sim else None))
    return rows


def _percent(part: int, whole: int) -> str:
    return f"{100 * part / whole:.0f} % ({part}/{whole})" if whole else "–"


def transfer_markdown(rows: list[CellRow]) -> str:
    """The transfer table (module docstring) as Markdown."""
    header = ["memorized in", "run in", "controller", "trials"]
    header += [f"{t} match (median latency)" for t in REQUIRED_TRANSITIONS]
    header += ["false triggers / trial", "hold", "unload", "CPU s / trial"]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        cells = [row.memorizing, row.running, row.controller, row.trials_text()]
        for detected, waited, latency in row.transitions:
            text = _percent(detected, waited)
            cells.append(text + (f" ({1000 * latency:.0f} ms)" if latency is not None else ""))
        cells += [f"{row.false_triggers / row.trials:.2f}", _percent(row.hold, row.trials),
                  _percent(row.unload, row.trials),
                  "–" if row.cpu_s is None else f"{row.cpu_s:.1f}"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def _heatmap_panels(rows: list[CellRow]):
    """(title, value of a row in [0, 1]) of each heat-map panel."""
    panels = [(f"{t} match", lambda row, k=k: row.match_rate(k))
              for k, t in enumerate(REQUIRED_TRANSITIONS)]
    panels += [("hold success", lambda row: row.hold / row.trials),
               ("unload success", lambda row: row.unload / row.trials)]
    return panels


def heatmap_label(row: CellRow, value: float) -> str:
    """A heat-map cell's text: the rate in percent, and "41/81 run" while trials remain."""
    text = f"{100 * value:.0f}"
    return f"{text}\n{row.trials_text()}" if row.partly_run else text


def draw_transfer_heatmap(rows: list[CellRow], path) -> pathlib.Path:
    """Heat maps, memorizing world (rows) by running world (columns), of each transition's match
    rate and of hold and unload success (heatmap_label); blank where a cell has no trials."""
    memorizing = list(dict.fromkeys(row.memorizing for row in rows))
    running = list(dict.fromkeys(row.running for row in rows))
    panels = _heatmap_panels(rows)
    figure = new_figure(max(6.0, 1.0 + 0.55 * len(running)) * len(panels) / 2,
                        1.6 + 0.45 * len(memorizing) + 1.2)
    axes = figure.subplots(1, len(panels), sharey=True)
    for ax, (title, value) in zip(np.atleast_1d(axes), panels):
        grid = np.full((len(memorizing), len(running)), np.nan)
        labels = {}
        for row in rows:
            at = (memorizing.index(row.memorizing), running.index(row.running))
            grid[at] = value(row)
            labels[at] = heatmap_label(row, grid[at])
        image = ax.imshow(grid, vmin=0.0, vmax=1.0, cmap="viridis", aspect="auto")
        for (i, j), v in np.ndenumerate(grid):
            if np.isfinite(v):
                ax.text(j, i, labels[i, j], ha="center", va="center", fontsize=7,
                        color="white" if v < 0.5 else "black")
        ax.set_title(title, fontsize=9)
        ax.set_xticks(range(len(running)), running, rotation=60, ha="right", fontsize=7)
        ax.set_yticks(range(len(memorizing)), memorizing, fontsize=7)
        ax.set_xlabel("run in", fontsize=8)
    np.atleast_1d(axes)[0].set_ylabel("memorized in", fontsize=8)
    figure.colorbar(image, ax=axes, shrink=0.8, label="rate")
    return save_figure(figure, path)


def heatmap_rows(rows: list[CellRow]) -> list[CellRow]:
    """The heat map's rows: the memorized controller's, else the first controller's."""
    controllers = list(dict.fromkeys(row.controller for row in rows))
    chosen = "memorized" if "memorized" in controllers else controllers[0]
    return [row for row in rows if row.controller == chosen]


def not_run_note(spec, rows: list[CellRow]) -> str:
    """A line naming the spec's cells with no finished trial, or "" when none is missing."""
    run = {(row.memorizing, row.running) for row in rows}
    missing = [cell_name(a, b) for a, b in spec.cells if (a, b) not in run]
    return f"\nNot run yet (no finished trial): {', '.join(missing)}.\n" if missing else ""


def write_transfer_reports(spec, out_dir, *, figure_format: str = "png") -> list[pathlib.Path]:
    """Writes OUT/transfer.md and the heat map OUT/transfer_matrix.<format> from the cells'
    records; returns the paths written (none when no cell has a finished trial)."""
    rows = cell_rows(spec, out_dir)
    if not rows:
        return []
    out_dir = pathlib.Path(out_dir)
    text = (TABLE_START + "\nEvents memorized in one world (row), trials run in another."
            " Cells: " + ", ".join(cell_name(a, b) for a, b in spec.cells) + ".\n\n"
            + transfer_markdown(rows) + not_run_note(spec, rows))
    written = [write_report(out_dir / TABLE_FILE, text, TABLE_START)]
    written.append(draw_transfer_heatmap(heatmap_rows(rows),
                                         figure_path(out_dir, FIGURE_STEM, figure_format)))
    return written
