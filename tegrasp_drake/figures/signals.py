"""Fig. 5a-b of the paper for one trial: per finger, the raw signals (the 12 taxel forces and
the pad's vibration, Fig. 5a) and the processed SA and RA channels (Eq. 1-2, Fig. 5b), with
the states, the transitions by trigger and the physical events."""

from matplotlib.lines import Line2D

from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.figures.trial_annotations import (
    draw_physical_events, draw_state_bands, draw_state_strip, draw_transition_lines,
    logged_transitions, marker_legend_handles, outcome_description, physical_events,
    run_description, state_spans, time_limits)
from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.rig.taxel_layout import COLUMNS, ROWS

# A taxel's line: its colour by row (along the approach axis), its style by column.
ROW_COLORS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a")
COLUMN_STYLES = ("-", "--", ":")
AXIS_COLORS = ("tab:red", "tab:green", "tab:blue")
AXIS_NAMES = ("x (across the pad)", "y (toward the fingertip)", "z (pad normal)")



def _taxel_legend_handles() -> list:
    rows = [Line2D([], [], color=ROW_COLORS[r], lw=1.5,
                   label=f"row {r}" + (" (palm)" if r == 0 else " (tip)" if r == ROWS - 1
                                       else "")) for r in range(ROWS)]
    columns = [Line2D([], [], color="0.3", ls=COLUMN_STYLES[c], lw=1.2, label=f"column {c}")
               for c in range(COLUMNS)]
    return rows + columns


def _plot_taxels(axis, log, finger: int) -> None:
    for k in range(TAXELS_PER_PAD):
        row, column = divmod(k, COLUMNS)
        axis.plot(log.t_sa, log.taxels[:, TAXELS_PER_PAD * finger + k], lw=0.8,
                  color=ROW_COLORS[row], ls=COLUMN_STYLES[column])


def plot_trial_signals(log, path) -> str:
    """Writes the figure to `path` (.png, .pdf or .svg); returns the path as text."""
    transitions, spans, events = logged_transitions(log), state_spans(log), physical_events(log)
    figure = new_figure(14.0, 11.0)
    axes = figure.subplots(5, 2, sharex=True,
                           gridspec_kw={"height_ratios": [0.4, 1.2, 1.2, 1.2, 1.2]})
    for finger, name in enumerate(FINGER_NAMES):
        state_axis, taxel_axis, vibration_axis, sa_axis, ra_axis = axes[:, finger]
        _plot_taxels(taxel_axis, log, finger)
        taxel_axis.set_title(f"{name} finger: (a) raw signals", loc="left")
        taxel_axis.set_ylabel("taxel normal force [N]")
        for axis in range(3):
            vibration_axis.plot(log.t_ra, log.pad_acceleration[:, 3 * finger + axis], lw=0.6,
                                color=AXIS_COLORS[axis])
        vibration_axis.set_ylabel("pad vibration [m/s²]")
        sa_axis.plot(log.t_ra, log.sa[:, finger], lw=0.8, color="tab:blue", zorder=2)
        sa_axis.set_title(f"{name} finger: (b) processed signals", loc="left")
        sa_axis.set_ylabel("SA (Eq. 1) [N]")
        ra_axis.plot(log.t_ra, log.ra[:, finger], lw=0.6, color="tab:orange", zorder=2)
        ra_axis.set_ylabel("RA (Eq. 2) [m/s²]")
        ra_axis.set_xlabel("time [s]")
        for axis in (taxel_axis, vibration_axis, sa_axis, ra_axis):
            draw_state_bands(axis, spans)
            draw_transition_lines(axis, transitions)
            draw_physical_events(axis, events)
            axis.grid(True, axis="y", alpha=0.3)
    axes[-1, 0].set_xlim(*time_limits(log))
    axes[1, 1].legend(handles=_taxel_legend_handles(), loc="upper left",
                      bbox_to_anchor=(1.01, 1.0), title="12 taxels")
    axes[2, 1].legend(handles=[Line2D([], [], color=c, label=n)
                               for c, n in zip(AXIS_COLORS, AXIS_NAMES)],
                      loc="upper left", bbox_to_anchor=(1.01, 1.0), title="pad frame axis")
    axes[3, 1].legend(handles=marker_legend_handles(transitions, events), loc="upper left",
                      bbox_to_anchor=(1.01, 1.0), fontsize=8)
    figure.suptitle(f"Fig. 5a-b: raw and processed tactile signals, {run_description(log)}\n"
                    f"{outcome_description(log)}")
    figure.draw_without_rendering()  # fix the layout, then place the labels
    for finger in range(len(FINGER_NAMES)):
        draw_state_strip(axes[0, finger], spans)
    return str(save_figure(figure, path))
