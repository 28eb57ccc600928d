"""A figure of the memorized events, like Fig. 5c of the paper.

One row per transition (grasp order), one column per channel (SA_L, SA_R, RA_L, RA_R),
one line per object; time is relative to the transition's physical event (dashed line).
"""

import pathlib
from collections.abc import Mapping

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from tegrasp_drake.rig.channels import CHANNEL_NAMES
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import transition_order

_COLUMN_TITLES = {"sa_left": "SA left", "sa_right": "SA right", "ra_left": "RA left",
                  "ra_right": "RA right"}


def plot_memorized_events(events_by_object: Mapping[str, Mapping[str, MemorizedEvent]],
                          path) -> pathlib.Path:
    """Save a PNG grid of every object's memorized events to `path`; returns the path."""
    transitions = sorted({t for events in events_by_object.values() for t in events},
                         key=transition_order)
    if not transitions:
        raise ValueError("no memorized events to plot")
    figure = Figure(figsize=(3.0 * len(CHANNEL_NAMES), 2.2 * len(transitions)),
                    layout="constrained")
    FigureCanvasAgg(figure)
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
            ax.axvline(0.0, color="0.5", linestyle="--", linewidth=0.8)
            ax.grid(True, alpha=0.3)
            if row == 0:
                ax.set_title(_COLUMN_TITLES[channel])
            if column == 0:
                ax.set_ylabel(f"{transition}\nnormalised")
            if row == len(transitions) - 1:
                ax.set_xlabel("time from transition [s]")
    axes[0, 0].legend(fontsize="small")
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=100)
    return path
