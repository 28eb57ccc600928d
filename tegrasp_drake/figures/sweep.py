"""Per-position success maps: one panel per (controller, object, phase), the marker grid
seen from above (stroke y across, palm normal x up), each marker coloured by its success
rate; the well-placed marker outlined."""

from collections import defaultdict
from pathlib import Path

import numpy as np

from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES
from tegrasp_drake.sweep.records import record_result
from tegrasp_drake.sweep.spec import BUILTIN_OBJECTS
from tegrasp_drake.sweep.table import succeeded

PHASES = ("hold", "unload")


def success_grids(records):
    """Success counts per marker, errors left out as in Table I: (normal_offsets_mm,
    stroke_offsets_mm, {(controller, object, phase): (successes, trials)}) indexed [x, y]."""
    ok = [r for r in records if r["status"] == "ok"]
    xs = sorted({round(r["trial"]["marker_dx_m"] * 1e6) for r in ok})
    ys = sorted({round(r["trial"]["marker_dy_m"] * 1e6) for r in ok})
    grids = defaultdict(lambda: (np.zeros((len(xs), len(ys)), int),
                                 np.zeros((len(xs), len(ys)), int)))
    for record in ok:
        trial, result = record["trial"], record_result(record)
        i = xs.index(round(trial["marker_dx_m"] * 1e6))
        j = ys.index(round(trial["marker_dy_m"] * 1e6))
        for phase in PHASES:
            successes, trials = grids[(trial["controller"], trial["object_name"], phase)]
            successes[i, j] += succeeded(result, phase)
            trials[i, j] += 1
    return np.array(xs) / 1000.0, np.array(ys) / 1000.0, dict(grids)


def plot_success_maps(records):
    """A matplotlib Figure: rows are controllers, columns objects x (~Hold, ~Unload)."""
    from matplotlib.patches import Rectangle

    xs_mm, ys_mm, grids = success_grids(records)
    if not grids:
        raise ValueError("no finished trials to draw: no record has status 'ok'")
    controllers = [c for c in CONTROLLER_NAMES if any(k[0] == c for k in grids)]
    controllers += sorted({k[0] for k in grids} - set(controllers))
    objects = [o for o in BUILTIN_OBJECTS if any(k[1] == o for k in grids)]
    objects += sorted({k[1] for k in grids} - set(objects))
    columns = [(o, p) for o in objects for p in PHASES]

    figure = new_figure(1.0 + 2.3 * len(columns), 0.6 + 2.4 * len(controllers))
    axes = figure.subplots(len(controllers), len(columns), squeeze=False)
    image = None
    for row, controller in enumerate(controllers):
        for column, (object_name, phase) in enumerate(columns):
            ax = axes[row, column]
            ax.set_title(f"{controller}\n{object_name} ~{phase.capitalize()}", fontsize=8)
            ax.set_xticks(range(len(ys_mm)), [f"{v:+g}" for v in ys_mm], fontsize=7)
            ax.set_yticks(range(len(xs_mm)), [f"{v:+g}" for v in xs_mm], fontsize=7)
            if row == len(controllers) - 1:
                ax.set_xlabel("stroke y (mm)", fontsize=7)
            if column == 0:
                ax.set_ylabel("palm normal x (mm)", fontsize=7)
            if (controller, object_name, phase) not in grids:
                continue
            successes, trials = grids[(controller, object_name, phase)]
            with np.errstate(invalid="ignore", divide="ignore"):
                rate = np.where(trials > 0, successes / trials, np.nan)
            image = ax.imshow(rate, origin="lower", cmap="RdYlGn", vmin=0.0, vmax=1.0)
            if 0.0 in xs_mm and 0.0 in ys_mm:  # Outline the well-placed marker.
                i0, j0 = list(xs_mm).index(0.0), list(ys_mm).index(0.0)
                ax.add_patch(Rectangle((j0 - 0.5, i0 - 0.5), 1.0, 1.0, fill=False,
                                       linewidth=1.5, edgecolor="black"))
            for i in range(trials.shape[0]):
                for j in range(trials.shape[1]):
                    if trials[i, j]:
                        ax.text(j, i, f"{successes[i, j]}/{trials[i, j]}", ha="center",
                                va="center", fontsize=7)
    if image is not None:
        figure.colorbar(image, ax=axes, shrink=0.6, label="success rate")
    figure.suptitle("Success rate per marker position")
    return figure


def write_success_maps(records, out_dir, file_name="success_maps.png") -> Path:
    """Saves the success maps in `out_dir` (format by `file_name`'s suffix); returns the path."""
    return save_figure(plot_success_maps(list(records)), Path(out_dir) / file_name)
