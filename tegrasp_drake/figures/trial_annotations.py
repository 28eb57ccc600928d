"""What the figures of a trial (Fig. 5a-b, 9, 10) draw over its signals: states,
transitions by trigger, the ground truth's physical events, the matcher's scores and a
title; labels stacked so that none overlaps another (`stack_labels`)."""

import dataclasses

import numpy as np
from matplotlib.lines import Line2D

from tegrasp_drake.control.controller_registry import controller_label
from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.trial_result import TrialResult

STATE_COLORS = {"Reach": "#d9e8f5", "Re-Reach": "#f7d6d0", "Load": "#dcefd9",
                "Lift": "#fff2cc", "Hold": "#e8e0f0", "Avoid": "#f4c7c3", "Place": "#d0ece7",
                "Unload": "#fbe3d4", "Done": "#eeeeee", "Failed": "#f2b8b5"}
# Transition lines: colour, line style and legend text per trigger.
TRIGGER_STYLES = {
    Trigger.MEMORIZED_EVENT: ("#c0392b", "-", "memorized event (Eq. 3 match)"),
    Trigger.HEURISTIC_EVENT: ("#8e44ad", "-", "heuristic event (threshold detector)"),
    Trigger.THRESHOLD: ("#d35400", "--", "threshold (hit, lost object)"),
    Trigger.TIMER: ("0.35", ":", "timer (motion or phase ended)"),
    Trigger.CORRECTIVE: ("#2471a3", "-.", "corrective action"),
    Trigger.FAULT: ("black", "-", "device fault"),
}
PHYSICAL_EVENT_STYLE = ("#117a65", (0, (6, 2)))  # colour, dash pattern
PHYSICAL_EVENT_NAMES = {"reach_load": "first contact", "load_lift": "grip settled",
                        "place_unload": "table touch", "hit": "hit"}
SCORE_THRESHOLDS = "match: SA > 0.9 and RA > 0.7 on all four channels"


def logged_transitions(log) -> list[Transition]:
    """The transitions in the log's meta."""
    return [Transition.from_dict(entry) for entry in log.meta.get("transitions", [])]


def state_spans(log) -> list[tuple[str, float, float]]:
    """(state, start, end) [s] of the run, from the transitions in the log's meta."""
    end_time = float(log.t_ra[-1])
    spans, state, start = [], Mode.REACH.label, 0.0
    for transition in logged_transitions(log):
        spans.append((state, start, transition.t))
        state, start = transition.to_mode.label, transition.t
    spans.append((state, start, end_time))
    return spans


def logged_scenario(log):
    """The Scenario the trial ran (from the YAML in the log's meta); ConfigError for a log
    without one (the figures need its hit and controller)."""
    from tegrasp_drake.scenario.scenario import scenario_from_yaml  # the figures' only use
    if "scenario" not in log.meta:
        raise ConfigError("its metadata has no 'scenario', which the figures need (the "
                          "trial.npz that `tegrasp trial --out DIR` writes has it)")
    return scenario_from_yaml(log.meta["scenario"], "its scenario")


def physical_events(log) -> dict[str, float]:
    """Name -> time [s] of the physical events behind the transitions taken, and the hit, if any."""
    events = {PHYSICAL_EVENT_NAMES.get(name, name): float(t)
              for name, t in (log.meta.get("events") or {}).items() if t is not None}
    hit_time = logged_scenario(log).disturbance.hit_time_s
    if 0.0 <= hit_time <= float(log.t_ra[-1]):
        events[PHYSICAL_EVENT_NAMES["hit"]] = float(hit_time)
    return events


def logged_result(log):
    """The TrialResult a trial's log holds (run_trial's), None for a log without one;
    ConfigError for one that is not a trial result."""
    result = log.meta.get("result")
    try:
        return TrialResult.from_dict(result) if result else None
    except ValueError as e:
        raise ConfigError(f"its metadata's 'result' is {e}; run the trial again to remake "
                          "it") from None


def run_description(log) -> str:
    """'box, memorized triggers, offset (0, 15) mm, seed 0' for the figures' titles ('?'
    for what a log without a trial result does not say)."""
    result = logged_result(log)
    if result is None:
        return (f"?, {controller_label(log.meta.get('controller', ''))}, "
                "offset (0, 0) mm, seed ?")
    offset_mm = [1000.0 * v for v in result.offset_m]
    return (f"{result.object}, {controller_label(result.controller)}, "
            f"offset ({offset_mm[0]:.0f}, {offset_mm[1]:.0f}) mm, seed {result.seed}")


def outcome_description(log) -> str:
    """'hold succeeded (6.65 s), unload succeeded' or what failed."""
    result = logged_result(log)
    if result is None:
        return ""
    hold = "succeeded" if result.hold_success else "failed"
    unload = "succeeded" if result.unload_success else "failed"
    text = f"hold {hold} ({result.hold_time_s:.2f} s held), unload {unload}"
    return text + (f"; {result.failure}" if result.failure else "")


def draw_state_bands(axis, spans) -> None:
    """The states as coloured bands behind the signals."""
    for state, start, end in spans:
        axis.axvspan(start, end, color=STATE_COLORS.get(state, "white"), alpha=0.6, lw=0,
                     zorder=0)


def draw_transition_lines(axis, transitions) -> None:
    """A vertical line at each transition, styled by its trigger (TRIGGER_STYLES)."""
    for transition in transitions:
        color, style, _ = TRIGGER_STYLES[transition.trigger]
        axis.axvline(transition.t, color=color, ls=style, lw=0.9, zorder=3)


def draw_physical_events(axis, events: dict) -> None:
    color, dashes = PHYSICAL_EVENT_STYLE
    for t in events.values():
        axis.axvline(t, color=color, ls=dashes, lw=0.9, zorder=3)


def marker_legend_handles(transitions, events: dict) -> list:
    """Legend entries for the transition lines by trigger (those present) and physical events."""
    handles = []
    for trigger in TRIGGER_STYLES:
        if any(t.trigger == trigger for t in transitions):
            color, style, text = TRIGGER_STYLES[trigger]
            handles.append(Line2D([], [], color=color, ls=style, lw=1.2,
                                  label=f"transition: {text}"))
    if events:
        color, dashes = PHYSICAL_EVENT_STYLE
        handles.append(Line2D([], [], color=color, ls=dashes, lw=1.2,
                              label="physical event (ground truth)"))
    return handles


@dataclasses.dataclass
class Label:
    """A label at time t [s] of a strip axis."""
    t: float
    text: str
    color: str = "black"
    boxed: bool = False


def stack_labels(axis, labels: list[Label], *, fontsize: float = 7.5, bottom: float = 0.0,
                 gap_px: float = 4.0) -> int:
    """Places `labels` at their times in `axis`, each on the lowest level where it overlaps none
    (leader lines from higher ones); returns the levels. Call once layout and limits are set."""
    figure = axis.figure
    renderer = figure.canvas.get_renderer()
    texts, right_edges, levels = [], [], []
    for label in sorted(labels, key=lambda item: item.t):
        text = axis.text(label.t, bottom, label.text, ha="center", va="center",
                         fontsize=fontsize, color=label.color, zorder=5, clip_on=False,
                         bbox=(dict(boxstyle="round,pad=0.2", fc="white", ec=label.color,
                                    lw=0.6) if label.boxed else None))
        text.set_in_layout(False)  # placed after the layout, which must not move for it
        box = _extent(text, renderer)
        level = next((k for k, right in enumerate(right_edges) if box.x0 > right + gap_px),
                     len(right_edges))
        if level == len(right_edges):
            right_edges.append(box.x1)
        else:
            right_edges[level] = box.x1
        texts.append((label, text))
        levels.append(level)
    count = max(len(right_edges), 1)
    height = (1.0 - bottom) / count
    for (label, text), level in zip(texts, levels):
        y = bottom + (level + 0.5) * height
        text.set_y(y)
        if level > 0:
            axis.plot([label.t, label.t], [bottom, y - 0.3 * height], color=label.color,
                      lw=0.6, zorder=4)
    return count


def _extent(text, renderer):
    """The text's extent on the canvas [px], its box included."""
    if text.get_bbox_patch() is None:
        return text.get_window_extent(renderer)
    text.update_bbox_position_size(renderer)
    return text.get_bbox_patch().get_window_extent(renderer)


def draw_state_strip(axis, spans) -> None:
    """A strip of the states over time: a coloured bar per state, its name on it or above it."""
    axis.set_ylim(0.0, 1.0)
    axis.set_yticks([])
    for side in ("left", "right", "top"):
        axis.spines[side].set_visible(False)
    bar_top = 0.3
    for state, start, end in spans:
        axis.fill_between([start, end], 0.0, bar_top, color=STATE_COLORS.get(state, "white"),
                          lw=0.5, edgecolor="0.6")
    labels = [Label((start + end) / 2.0, state) for state, start, end in spans if end > start]
    stack_labels(axis, labels, bottom=bar_top)
    axis.set_ylabel("state", rotation=0, ha="right", va="center")


def score_labels(transitions) -> list[Label]:
    """A boxed label of the four channel scores at each event-triggered transition."""
    labels = []
    for transition in transitions:
        if not transition.trigger.is_event or transition.scores is None:
            continue
        sa_left, sa_right, ra_left, ra_right = transition.scores
        color = TRIGGER_STYLES[transition.trigger][0]
        labels.append(Label(transition.t, f"{transition.from_mode.label}-"
                            f"{transition.to_mode.label} {transition.t:.2f} s\n"
                            f"SA {sa_left:.2f}/{sa_right:.2f}  RA {ra_left:.2f}/{ra_right:.2f}",
                            color=color, boxed=True))
    return labels


def event_labels(events: dict) -> list[Label]:
    color, _ = PHYSICAL_EVENT_STYLE
    return [Label(t, name, color=color) for name, t in events.items()]


def draw_annotation_strip(axis, transitions, events: dict) -> None:
    """A strip above the signals: the scores at each event-triggered transition (boxed,
    left/right per channel) and the names of the physical events, stacked."""
    axis.set_ylim(0.0, 1.0)
    axis.axis("off")
    stack_labels(axis, score_labels(transitions) + event_labels(events), fontsize=7.0)


def time_limits(log) -> tuple[float, float]:
    return 0.0, float(np.max(log.t_ra))
