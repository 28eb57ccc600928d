"""Fig. 9 of the paper for one trial: SA and RA of both fingers over the whole run, with the
states, the transitions by trigger, the physical events and the matcher's scores at each
event-triggered transition."""

from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.figures.trial_annotations import (
    SCORE_THRESHOLDS, draw_annotation_strip, draw_physical_events, draw_state_bands,
    draw_state_strip, draw_transition_lines, logged_transitions, marker_legend_handles,
    outcome_description, physical_events, run_description, state_spans, time_limits)
from tegrasp_drake.rig.channels import FINGER_NAMES

SIGNAL_ROWS = (("SA", 0, "N", "tab:blue"), ("SA", 1, "N", "tab:blue"),
               ("RA", 0, "m/s²", "tab:orange"), ("RA", 1, "m/s²", "tab:orange"))


def plot_trial_states(log, path, *, time_window=None) -> str:
    """Writes the figure to `path` (.png, .pdf or .svg); returns the path as text."""
    transitions, spans, events = logged_transitions(log), state_spans(log), physical_events(log)
    figure = new_figure(12.0, 9.5)
    axes = figure.subplots(2 + len(SIGNAL_ROWS), 1, sharex=True,
                           gridspec_kw={"height_ratios": [0.8, 0.45] + [1.3] * len(SIGNAL_ROWS)})
    annotation_axis, state_axis, signal_axes = axes[0], axes[1], axes[2:]
    for axis, (kind, finger, unit, color) in zip(signal_axes, SIGNAL_ROWS):
        draw_state_bands(axis, spans)
        values = log.sa[:, finger] if kind == "SA" else log.ra[:, finger]
        axis.plot(log.t_ra, values, lw=0.7, color=color, zorder=2)
        draw_transition_lines(axis, transitions)
        draw_physical_events(axis, events)
        equation = "Eq. 1" if kind == "SA" else "Eq. 2"
        axis.set_ylabel(f"{kind} {FINGER_NAMES[finger]} [{unit}]\n({equation})")
        axis.grid(True, axis="y", alpha=0.3)
    signal_axes[-1].set_xlabel("time [s]")
    signal_axes[-1].set_xlim(*(time_window or time_limits(log)))
    figure.suptitle(f"Fig. 9: the tactile signals of a grasp, {run_description(log)}\n"
                    f"{outcome_description(log)}")
    figure.legend(handles=marker_legend_handles(transitions, events), loc="outside lower center",
                  ncols=3, title=f"boxed: the four channels' scores at an event transition "
                                 f"(left/right); {SCORE_THRESHOLDS}",
                  title_fontsize=8, fontsize=8)
    figure.draw_without_rendering()  # fix the layout, then place the labels
    draw_state_strip(state_axis, spans)
    draw_annotation_strip(annotation_axis, transitions, events)
    return str(save_figure(figure, path))
