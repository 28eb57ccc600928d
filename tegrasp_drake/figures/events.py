"""Fig. 5c of the paper: the memorized events, one row per transition, one column per channel, one
line per object; each window max-normalised, time relative to the physical event (dashed line)."""

import pathlib
from collections.abc import Mapping

from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import transition_order
from tegrasp_drake.figures.figure_files import MAX_LINES_TOLD_APART, new_figure, save_figure

MAX_OBJECTS_PER_FIGURE = MAX_LINES_TOLD_APART  # one line per object in each panel
from tegrasp_drake.rig.channels import CHANNEL_NAMES

_COLUMN_TITLES = {"sa_left": "SA left (Eq. 1)", "sa_right": "SA right (Eq. 1)",
                  "ra_left": "RA left (Eq. 2)", "ra_right": "RA right (Eq. 2)"}
_TRANSITION_TITLES = {"reach_load": "Reach-Load", "load_lift": "Load-Lift",
                      "place_unload": "Place-Unload"}


def plot_memorized_events(events_by_object: Mapping[str, Mapping[str, MemorizedEvent]],
                          path) -> pathlib.Path:
    """Writes every object's memorized events to `path` (.png, .pdf or .svg); returns it.
    ValueError for more than MAX_OBJECTS_PER_FIGURE objects (`tegrasp plot events --object`
    picks some)."""
    if len(events_by_object) > MAX_OBJECTS_PER_FIGURE:
        raise ValueError(f"{len(events_by_object)} objects' memorized events; a figure tells "
                         f"at most {MAX_OBJECTS_PER_FIGURE} apart")
    transitions = sorted({t for events in events_by_object.values() for t in events},
                         key=transition_order)
    if not transitions:
        raise ValueError("no memorized events to plot")
    figure = new_figure(3.0 * len(CHANNEL_NAMES), 0.6 + 2.2 * len(transitions))
    axes = figure.subplots(len(transitions), len(CHANNEL_NAMES), sharex=True, sharey=True,
                           squeeze=False)
    for row, transition in enumerate(transitions):
        for column, channel in enumerate(CHANNEL_NAMES):
            ax = axes[row, column]
            for object_name in sorted(events_by_object):
                event = events_by_object[object_name].get(transition)
                if event is not None:
                    ax.plot(event.sample_times(channel), event.channel(channel),
                            label=object_name, linewidth=1.0)
            ax.axvline(0.0, color="0.5", linestyle="--", linewidth=0.8,
                       label="physical event")
            ax.grid(True, alpha=0.3)
            if row == 0:
                ax.set_title(_COLUMN_TITLES[channel])
            if column == 0:
                ax.set_ylabel(f"{_TRANSITION_TITLES.get(transition, transition)}\n"
                              "normalised [-]")
            if row == len(transitions) - 1:
                ax.set_xlabel("time from transition [s]")
    axes[0, 0].legend(fontsize="small", title="object")
    figure.suptitle("Fig. 5c: the memorized predicted tactile events (0.5 s windows of the "
                    "ideal grasp, each normalised by its maximum)")
    return save_figure(figure, path)
