"""Detection latency distributions from sweep records: for each event-triggered transition
(Reach-Load, Load-Lift, Place-Unload), each controller's latencies (the transition's time minus its
physical event's, runs/trial.py) as a box plot with every trial's value beside it; false triggers
(a transition before its physical event) have no latency and are counted under the axis."""

from collections import defaultdict

import numpy as np

from tegrasp_drake.events.transitions import TRANSITIONS
from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_color
from tegrasp_drake.sweep.records import record_result

TRANSITION_TITLES = {"reach_load": "Reach-Load (first contact)",
                     "load_lift": "Load-Lift (grip settled)",
                     "place_unload": "Place-Unload (table touch)"}


def latency_samples(records) -> dict[str, dict[str, list[float]]]:
    """transition -> controller -> detection latencies [s] of the finished trials."""
    samples = defaultdict(lambda: defaultdict(list))
    for record in records:
        if record["status"] != "ok":
            continue
        controller = record["trial"]["controller"]
        for transition, latency in record_result(record).detection_latency_s.items():
            if latency is not None:
                samples[transition][controller].append(float(latency))
    return samples


def false_trigger_counts(records) -> dict[str, tuple[int, int]]:
    """controller -> (false triggers, finished trials)."""
    counts = defaultdict(lambda: [0, 0])
    for record in records:
        if record["status"] == "ok":
            count = counts[record["trial"]["controller"]]
            count[0] += int(record_result(record).false_triggers)
            count[1] += 1
    return {controller: tuple(count) for controller, count in counts.items()}


def plot_latency_distributions(records, path) -> str:
    """Writes the figure for sweep `records` to `path` (.png, .pdf or .svg); returns the path
    as text. ValueError when no finished trial has a detected event transition."""
    records = list(records)
    samples = latency_samples(records)
    if not samples:
        raise ValueError("no detection latencies to draw: no finished trial detected an "
                         "event transition")
    transitions = sorted(samples, key=lambda name: (
        list(TRANSITIONS).index(name) if name in TRANSITIONS else len(TRANSITIONS), name))
    controllers = [c for c in CONTROLLER_NAMES if any(c in samples[t] for t in transitions)]
    controllers += sorted({c for t in transitions for c in samples[t]} - set(controllers))
    false_triggers = false_trigger_counts(records)
    figure = new_figure(4.2 * len(transitions), 4.8)
    axes = figure.subplots(1, len(transitions), squeeze=False)[0]
    rng = np.random.default_rng(0)  # horizontal jitter of the dots only
    for axis, transition in zip(axes, transitions):
        labels = []
        for i, controller in enumerate(controllers):
            values_ms = 1000.0 * np.asarray(samples[transition].get(controller, []))
            color = controller_color(controller, f"C{i}")
            if len(values_ms):
                axis.boxplot([values_ms], positions=[i], widths=0.5, showfliers=False,
                             medianprops={"color": color, "lw": 1.5})
                axis.scatter(i + 0.32 + rng.uniform(-0.06, 0.06, len(values_ms)), values_ms,
                             s=6, color=color, alpha=0.6, lw=0)
                median = f"median {np.median(values_ms):.0f} ms"
            else:
                median = "none detected"
            labels.append(f"{controller}\nn={len(values_ms)}, {median}")
        axis.set_xticks(range(len(controllers)), labels, fontsize=7.5)
        axis.set_xlim(-0.6, len(controllers) - 0.3)
        axis.set_title(TRANSITION_TITLES.get(transition, transition))
        axis.set_ylabel("detection latency [ms]")
        axis.set_ylim(bottom=0.0)
        axis.grid(True, axis="y", alpha=0.3)
    note = "; ".join(f"{c}: {false_triggers[c][0]} false triggers in {false_triggers[c][1]} "
                     "trials" for c in controllers if c in false_triggers)
    figure.suptitle("Detection latency of the event-triggered transitions per controller "
                    f"(transition time minus physical event)\n{note} (no latency: not drawn)")
    return str(save_figure(figure, path))
