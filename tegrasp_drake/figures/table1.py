"""Table I of the paper against the simulation: success rate per object and its average, in
the paper's four columns (well placed / misplaced, ~Hold / ~Unload), one bar per controller
of a sweep beside the paper's rate (the real robot with memorized triggers)."""

import numpy as np

from tegrasp_drake.control.controller_registry import controller_color
from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.sweep.table import AVERAGE, PAPER_TABLE1, TABLE1_COLUMNS, table1_rows

PAPER_COLOR = "#2c3e50"
COLUMN_TITLES = {("well_placed", "hold"): "well placed, ~Hold",
                 ("well_placed", "unload"): "well placed, ~Unload",
                 ("misplaced", "hold"): "misplaced, ~Hold",
                 ("misplaced", "unload"): "misplaced, ~Unload"}
OBJECT_TITLES = {"box": "box", "thick_cylinder": "thick\ncylinder",
                 "thin_cylinder": "thin\ncylinder", AVERAGE: "average"}


def plot_table1(records, path) -> str:
    """Writes the figure of sweep `records` to `path`, returns it; ValueError if none finished."""
    rows = table1_rows([r for r in records])
    if not any(cell.trials for row in rows for cell in row.cells):
        raise ValueError("no finished trials to draw: no record has status 'ok'")
    controllers = list(dict.fromkeys(row.controller for row in rows))
    objects = list(dict.fromkeys(row.object_name for row in rows))
    by_key = {(row.controller, row.object_name): row for row in rows}
    series = len(controllers) + 1  # and the paper
    width = 0.8 / series
    figure = new_figure(12.0, 6.5)
    axes = figure.subplots(2, 2, sharey=True).ravel()
    x = np.arange(len(objects))
    for axis, (column, key) in zip(axes, enumerate(TABLE1_COLUMNS)):
        for s, controller in enumerate(controllers):
            cells = [by_key[(controller, o)].cells[column] for o in objects]
            heights = [np.nan if c.percent is None else c.percent for c in cells]
            bars = axis.bar(x + (s - (series - 1) / 2) * width, heights, width,
                            color=controller_color(controller, f"C{s}"), label=controller)
            axis.bar_label(bars, labels=[f"{c.successes}/{c.trials}" if c.trials else ""
                                         for c in cells], fontsize=6.5, rotation=90,
                           padding=2)
        paper = [PAPER_TABLE1[o][column] if o in PAPER_TABLE1 else np.nan for o in objects]
        bars = axis.bar(x + (series - 1) / 2 * width, paper, width, color="white",
                        edgecolor=PAPER_COLOR, hatch="///", label="paper (real robot, memorized)")
        axis.bar_label(bars, labels=["" if np.isnan(p) else f"{p:.0f}%" for p in paper],
                       fontsize=6.5, rotation=90, padding=2)
        axis.set_title(COLUMN_TITLES[key])
        axis.set_xticks(x, [OBJECT_TITLES.get(o, o) for o in objects])
        axis.set_ylim(0.0, 125.0)
        axis.set_yticks(range(0, 101, 25))
        axis.grid(True, axis="y", alpha=0.3)
    for axis in axes[::2]:
        axis.set_ylabel("success rate [%]")
    handles, labels = axes[0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="outside lower center", ncols=len(labels))
    figure.suptitle("Table I: grasp success rate per object, simulation (successes/trials on "
                    "each bar) against the paper\naverage: mean of the objects' rates, as in "
                    "the paper")
    return str(save_figure(figure, path))
