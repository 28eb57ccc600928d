"""Figures of a closed-loop trial: the full run with its states (paper Fig. 9) and the
reaction to a hit (Fig. 10)."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tegrasp_drake.control.grasp_modes import Mode, Transition  # noqa: E402
from tegrasp_drake.rig.channels import FINGER_NAMES  # noqa: E402

STATE_COLORS = {"Reach": "#d9e8f5", "Re-Reach": "#f7d6d0", "Load": "#dcefd9",
                "Lift": "#fff2cc", "Hold": "#e8e0f0", "Avoid": "#f4c7c3", "Place": "#d0ece7",
                "Unload": "#fbe3d4", "Done": "#eeeeee", "Failed": "#f2b8b5"}


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


def _draw_states(axis, log, *, labels: bool):
    for state, start, end in state_spans(log):
        axis.axvspan(start, end, color=STATE_COLORS.get(state, "white"), lw=0)
        if labels and end - start > 0.25:
            label = axis.text((start + end) / 2, 0.97, state, fontsize=7, ha="center",
                              va="top", transform=axis.get_xaxis_transform(), clip_on=True)
            label.set_in_layout(False)  # labels of states outside a zoomed window
    for transition in logged_transitions(log):
        style = "-" if transition.trigger.is_event else ":"
        axis.axvline(transition.t, color="tab:red", lw=0.8, ls=style)


def plot_trial_states(log, path, *, time_window=None) -> str:
    """Writes a PNG like Fig. 9: SA and RA of each finger over the run, the state bands
    behind them, solid red lines at event-triggered transitions, dotted at the others."""
    fig, axes = plt.subplots(4, 1, figsize=(12, 9), sharex=True)
    rows = [("SA", k, "N") for k in range(2)] + [("RA", k, "m/s^2") for k in range(2)]
    for axis, (kind, k, unit) in zip(axes, rows):
        _draw_states(axis, log, labels=axis is axes[0])
        values = log.sa[:, k] if kind == "SA" else log.ra[:, k]
        axis.plot(log.t_ra, values, lw=0.6, color="tab:blue" if kind == "SA" else "tab:orange")
        axis.set_ylabel(f"{kind} {FINGER_NAMES[k]} [{unit}]")
    if time_window is not None:
        axes[-1].set_xlim(*time_window)
    axes[-1].set_xlabel("time [s]")
    result = log.meta.get("result", {})
    fig.suptitle(f"{result.get('object', '')} {result.get('controller', '')}: hold "
                 f"{result.get('hold_success')}, unload {result.get('unload_success')}",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return str(path)


def plot_avoid_reaction(log, path, *, hit_threshold=None, before_s=0.3, after_s=1.2) -> str:
    """Writes a PNG like Fig. 10: RA and SA around the first Hold -> Avoid transition, with
    the hit threshold, and the grasp frame's commanded lateral motion."""
    avoid = [e for e in logged_transitions(log) if e.to_mode == Mode.AVOID]
    if not avoid:
        raise ValueError("the trial has no Avoid transition (was there a hit in Hold?)")
    t0 = avoid[0].t
    window = (t0 - before_s, t0 + after_s)
    fig, axes = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
    fast = (log.t_ra >= window[0]) & (log.t_ra <= window[1])
    _draw_states(axes[0], log, labels=True)
    lines = axes[0].plot(log.t_ra[fast], log.ra[fast], lw=0.7)
    if hit_threshold is not None:
        lines.append(axes[0].axhline(hit_threshold, color="k", ls="--", lw=0.8))
    axes[0].set_ylabel("RA [m/s^2]")
    axes[0].legend(lines, list(FINGER_NAMES) + ["hit threshold"] * (hit_threshold is not None),
                   fontsize=7)
    _draw_states(axes[1], log, labels=False)
    lines = axes[1].plot(log.t_ra[fast], log.sa[fast], lw=0.7)
    axes[1].set_ylabel("SA [N]")
    axes[1].legend(lines, list(FINGER_NAMES), fontsize=7)
    slow = (log.t_slow >= window[0]) & (log.t_slow <= window[1])
    _draw_states(axes[2], log, labels=False)
    xy = log.object_state[slow, 4:6] - log.object_state[slow, 4:6][0]
    lines = axes[2].plot(log.t_slow[slow], 1000 * xy)
    axes[2].set_ylabel("object x, y shift [mm]")
    axes[2].legend(lines, ["x", "y"], fontsize=7)
    axes[2].set_xlabel("time [s]")
    axes[2].set_xlim(*window)
    direction = None if avoid[0].direction is None else list(avoid[0].direction)
    fig.suptitle(f"Hold -> Avoid at {t0:.3f} s, moving along {direction}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return str(path)
