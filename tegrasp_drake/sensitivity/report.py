"""The sensitivity study's report, from its points' sweep records: per point and controller,
the misplaced trials held and placed (Table I's misplaced ~Hold and ~Unload) and the failure
classes (sweep/failure_classes.py); a tornado chart of the one-factor points; the spread over
a Latin-hypercube sample (docs/sweeps.md, "How much the guesses matter")."""

import collections
import dataclasses
import pathlib

import numpy as np

from tegrasp_drake.figures.figure_files import figure_path, new_figure, save_figure
from tegrasp_drake.rig.files import is_folder
from tegrasp_drake.rig.report_files import write_report
from tegrasp_drake.sensitivity.study import DEFAULT_POINT, point_folder_cell, transfer_spec
from tegrasp_drake.sweep.failure_classes import FAILURE_CLASSES, failure_class
from tegrasp_drake.sweep.records import load_records, record_result
from tegrasp_drake.sweep.spec import expand_trials
from tegrasp_drake.transfer.matrix import cell_folder, running_sweep

REPORT_FILE = "sensitivity.md"
REPORT_START = "# Sensitivity to the guessed parameters\n"  # its title line
FIGURE_STEM = "tornado"
METRICS = (("misplaced held", "held"), ("misplaced placed", "placed"))


@dataclasses.dataclass(frozen=True)
class PointRow:
    """One point and controller: finished trials of `planned`; of its misplaced trials, how
    many were held and how many placed; failure classes over all its trials."""
    point: str
    controller: str
    trials: int
    planned: int
    misplaced: int
    held: int
    placed: int
    failures: tuple[tuple[str, int], ...]  # (class, trials) in FAILURE_CLASSES' order

    def rate(self, metric: str) -> float:
        """`metric` ("held" or "placed") of the misplaced trials, NaN without any."""
        return getattr(self, metric) / self.misplaced if self.misplaced else float("nan")


def point_rows(spec, points, out_dir) -> list[PointRow]:
    """A PointRow per point and controller with finished trials of the spec in `out_dir`."""
    matrix = transfer_spec(spec, points)
    rows = []
    for point in points:
        memorizing, running = point_folder_cell(spec, point)
        folder = cell_folder(out_dir, memorizing, running)
        if not is_folder(folder / "trials"):  # UserPathError when it cannot be looked at
            continue
        planned = {t.trial_id: t for t in expand_trials(running_sweep(matrix, running))}
        records = [r for trial_id, r in load_records(folder).records.items()
                   if trial_id in planned and r.get("result") is not None]
        for controller in spec.sweep.controllers:
            mine = [r for r in records if r["trial"]["controller"] == controller]
            if not mine:
                continue
            results = [(record_result(r), r["trial"]["well_placed"]) for r in mine]
            misplaced = [result for result, well in results if not well]
            classes = collections.Counter(failure_class(result) for result, _ in results)
            rows.append(PointRow(
                point.name, controller, len(mine),
                sum(1 for t in planned.values() if t.controller == controller),
                len(misplaced), sum(bool(r.hold_success) for r in misplaced),
                sum(bool(r.unload_success) for r in misplaced),
                tuple((name, classes[name]) for name in FAILURE_CLASSES if classes[name])))
    return rows


def _percent(part: int, whole: int) -> str:
    return f"{100 * part / whole:.0f} % ({part}/{whole})" if whole else "–"


def _value_text(value: float) -> str:
    return f"{value:g}"


def points_markdown(points, rows: list[PointRow]) -> str:
    """The table: point, what it sets, controller, trials, misplaced held and placed, the
    failure classes that appear."""
    sets = {p.name: ", ".join(f"`{key}` {_value_text(v)}" for key, v in p.values) or "defaults"
            for p in points}
    lines = ["| point | sets | controller | trials | misplaced held | misplaced placed | "
             "failure classes |", "|---|---|---|---|---|---|---|"]
    for row in rows:
        trials = (f"{row.trials}/{row.planned} run" if row.trials < row.planned
                  else str(row.trials))
        failures = ", ".join(f"{name} {n}" for name, n in row.failures) or "none"
        lines.append(f"| {row.point} | {sets[row.point]} | {row.controller} | {trials} | "
                     f"{_percent(row.held, row.misplaced)} | "
                     f"{_percent(row.placed, row.misplaced)} | {failures} |")
    return "\n".join(lines) + "\n"


@dataclasses.dataclass(frozen=True)
class TornadoBar:
    """One parameter in one panel: the rate at the default, at its low and its high end
    (None where that end is the default or has no trials)."""
    parameter: str
    default: float
    low: float | None
    high: float | None

    @property
    def swing(self) -> float:
        ends = [v for v in (self.low, self.high) if v is not None and np.isfinite(v)]
        return max((abs(v - self.default) for v in ends), default=0.0)


def tornado_bars(points, rows: list[PointRow], controller: str, metric: str) -> list[TornadoBar]:
    """The one-factor points' bars of one panel (a controller's misplaced `metric` rate), in
    the points' order; none without the default point's trials."""
    rate = {row.point: row.rate(metric) for row in rows if row.controller == controller}
    if DEFAULT_POINT not in rate:
        return []
    bars = {}
    for point in points:
        if not point.parameter or point.name not in rate:
            continue
        bar = bars.setdefault(point.parameter, {"low": None, "high": None})
        bar[point.end] = rate[point.name]
    return [TornadoBar(key, rate[DEFAULT_POINT], ends["low"], ends["high"])
            for key, ends in bars.items()]


def draw_tornado(points, rows: list[PointRow], controllers, path) -> pathlib.Path | None:
    """Panels, rows by metric (misplaced held, placed) and columns by controller: each
    parameter two bars from the default's rate, to its low end's (blue, below) and to its
    high end's (orange, above), a tick at each end's rate; parameters ordered by their
    largest swing over all panels, largest on top. None when no panel has a bar."""
    panels = {(c, m): tornado_bars(points, rows, c, m) for c in controllers for _, m in METRICS}
    swing = collections.defaultdict(float)
    for bars in panels.values():
        for bar in bars:
            swing[bar.parameter] = max(swing[bar.parameter], bar.swing)
    if not swing:
        return None
    order = sorted(swing, key=lambda key: swing[key])  # barh draws the first at the bottom
    figure = new_figure(3.2 * len(controllers) + 2.5, 1.2 + 0.35 * len(order) * len(METRICS))
    axes = np.atleast_2d(figure.subplots(len(METRICS), len(controllers), sharey=True,
                                         squeeze=False))
    for j, controller in enumerate(controllers):
        for i, (title, metric) in enumerate(METRICS):
            ax = axes[i, j]
            bars = {bar.parameter: bar for bar in panels[controller, metric]}
            for k, key in enumerate(order):
                bar = bars.get(key)
                if bar is None:
                    continue
                for end, colour, shift in (("low", "tab:blue", -0.18),
                                           ("high", "tab:orange", 0.18)):
                    value = getattr(bar, end)
                    if value is not None and np.isfinite(value):
                        ax.barh(k + shift, 100 * (value - bar.default), left=100 * bar.default,
                                height=0.34, color=colour, label=f"{end} end")
                        ax.plot(100 * value, k + shift, marker="|", color=colour,
                                markersize=7)  # seen also where an end leaves the rate
                ax.axvline(100 * bar.default, color="black", linewidth=0.8)
            ax.set_xlim(-2, 102)
            ax.set_ylim(-0.6, len(order) - 0.4)
            ax.set_title(f"{controller}: {title}", fontsize=9)
            ax.set_yticks(range(len(order)), order, fontsize=7)
            ax.set_xlabel("% of misplaced trials", fontsize=8)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    if unique:
        figure.legend(unique.values(), unique.keys(), loc="outside lower center", ncols=2,
                      fontsize=8)
    return save_figure(figure, path)


def spread_markdown(rows: list[PointRow], controllers) -> str:
    """Per controller, the lowest, median and highest misplaced held and placed rates over
    the points other than the default (the sample's spread)."""
    lines = ["| controller | points | misplaced held: low / median / high | "
             "misplaced placed: low / median / high |", "|---|---|---|---|"]
    for controller in controllers:
        mine = [r for r in rows if r.controller == controller and r.point != DEFAULT_POINT
                and r.misplaced]
        if not mine:
            continue
        cells = []
        for _, metric in METRICS:
            rates = 100 * np.array([r.rate(metric) for r in mine])
            cells.append(f"{rates.min():.0f} / {np.median(rates):.0f} / {rates.max():.0f} %")
        lines.append(f"| {controller} | {len(mine)} | {cells[0]} | {cells[1]} |")
    return "\n".join(lines) + "\n"


def ends_markdown(points, rows: list[PointRow]) -> str:
    """Which failure classes appear at which end: per one-factor parameter and controller,
    the classes at its low end, at the defaults and at its high end."""
    classes = {(r.point, r.controller): ", ".join(f"{name} {n}" for name, n in r.failures)
               or "none" for r in rows}
    ends = {}
    for point in points:
        if point.parameter:
            ends.setdefault(point.parameter, {})[point.end] = point.name
    lines = ["| parameter | controller | low end | defaults | high end |",
             "|---|---|---|---|---|"]
    controllers = list(dict.fromkeys(r.controller for r in rows))
    for key, names in ends.items():
        for controller in controllers:
            cells = [classes.get((names[end], controller), "not run") if end in names
                     else "(the default)" for end in ("low", "high")]
            lines.append(f"| `{key}` | {controller} | {cells[0]} | "
                         f"{classes.get((DEFAULT_POINT, controller), 'not run')} | {cells[1]} |")
    return "\n".join(lines) + "\n"


def write_sensitivity_report(spec, points, out_dir, *,
                             figure_format: str = "png") -> list[pathlib.Path]:
    """Writes OUT/sensitivity.md and the tornado chart OUT/tornado.<format> (when one-factor
    points have trials) from the points' records; returns the paths written."""
    rows = point_rows(spec, points, out_dir)
    if not rows:
        return []
    out_dir = pathlib.Path(out_dir)
    controllers = [c for c in spec.sweep.controllers if any(r.controller == c for r in rows)]
    written = []
    figure = draw_tornado(points, rows, controllers,
                          figure_path(out_dir, FIGURE_STEM, figure_format))
    text = [REPORT_START.rstrip("\n"), "",
            f"{len(points)} points, events memorized "
            + ("in each point's own world" if spec.events == "each_point"
               else "once, at the defaults") + ". Misplaced: the trials off the centre marker.",
            ""]
    if figure is not None:
        written.append(figure)
        text += [f"![tornado chart]({figure.name})", "",
                 "Each bar runs from the rate at the defaults (black line) to the rate with "
                 "one parameter at its low (blue) or high (orange) end.", ""]
    if any(p.parameter for p in points):
        text += ["## Failure classes at each end", "", ends_markdown(points, rows)]
    text += ["## Spread over the points", "", spread_markdown(rows, controllers),
             "## Each point", "", points_markdown(points, rows)]
    missing = [p.name for p in points if not any(r.point == p.name for r in rows)]
    if missing:
        text += [f"Not run yet (no finished trial): {', '.join(missing)}.", ""]
    written.insert(0, write_report(out_dir / REPORT_FILE, "\n".join(text), REPORT_START))
    return written
