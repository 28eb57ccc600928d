"""Fig. 10 of the paper for one trial: a hit on the held object, seen by RA, and the Avoid
state's reaction. Around the first Hold -> Avoid transition: RA of both fingers with each
one's hit trigger, SA, and the object's displacement (the gripper carries it along the
avoiding direction)."""

import dataclasses

import numpy as np

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.figures.trial_annotations import (
    PHYSICAL_EVENT_NAMES, draw_annotation_strip, draw_physical_events, draw_state_bands,
    draw_state_strip, draw_transition_lines, logged_scenario, logged_transitions,
    marker_legend_handles, physical_events, run_description, state_spans)
from tegrasp_drake.rig.channels import FINGER_NAMES

FINGER_COLORS = ("tab:blue", "tab:orange")
OBJECT_AXIS_COLORS = ("tab:red", "tab:green", "tab:blue")


class NoAvoidError(ValueError):
    """The trial has no Hold -> Avoid transition to draw."""


@dataclasses.dataclass(frozen=True)
class HitRule:
    """The Avoid hit rule a trial ran with: a film's RA above threshold_mps2 [m/s^2] over its
    level, the mean of its RA at the Hold's controller ticks (every period_s [s]) in the
    level_s [s] before (0: no level, the threshold alone)."""
    threshold_mps2: float
    level_s: float = 0.0
    period_s: float = 0.005


def logged_hit_rule(log) -> HitRule | None:
    """The hit rule the logged trial's controller ran with, None for a controller without an
    Avoid reaction (open loop): its log has no Avoid to draw."""
    from tegrasp_drake.scenario.scenario import controller_in_force
    controller = controller_in_force(logged_scenario(log))
    avoid = getattr(controller, "avoid", None)
    if avoid is None:
        return None
    return HitRule(avoid.hit_ra_mps2, avoid.hit_level_s, controller.update_period_s)


def hit_trigger_lines(t_ra, ra, hold_spans, rule: HitRule):
    """Each film's hit trigger in Hold, reconstructed from the log by the controller's own
    level (corrective_actions.ra_history, ra_level): (t [s] of the Hold's controller ticks,
    (n, films) level + threshold [m/s^2]). A tick reads the film's latest RA sample (t_ra
    [s], ra (samples, films) [m/s^2]); hold_spans: (start, end) [s] of each Hold, the first
    tick in it the one after the transition's. The level restarts with each Hold."""
    from tegrasp_drake.control.corrective_actions import ra_history, ra_level
    t_ra, ra = np.asarray(t_ra, float), np.asarray(ra, float)
    times, lines = [], []
    for start, end in hold_spans:
        count = int(np.floor((end - start) / rule.period_s))
        ticks = start + rule.period_s * np.arange(1, count + 1)
        reads = ra[np.clip(np.searchsorted(t_ra, ticks, side="right") - 1, 0, len(t_ra) - 1)]
        history = ()
        for read in reads:
            lines.append(np.asarray(ra_level(history, ra.shape[1])) + rule.threshold_mps2)
            history = ra_history(history, read, rule.level_s, rule.period_s)
        times.append(ticks)
    if not lines:
        return np.zeros(0), np.zeros((0, ra.shape[1]))
    return np.concatenate(times), np.vstack(lines)


def _hit_text(log) -> str:
    hit = logged_scenario(log).disturbance
    if hit.hit_time_s < 0.0:
        return "no scripted hit"
    force = np.asarray(hit.hit_force_n, float)
    along = ", ".join(f"{v:g}" for v in force / np.linalg.norm(force))
    return (f"hit of {np.linalg.norm(force):.0f} N along ({along}) for "
            f"{1000 * hit.hit_duration_s:.0f} ms at {hit.hit_time_s:.2f} s")


def plot_avoid_reaction(log, path, *, hit_rule: HitRule | None = None, before_s=0.3,
                        after_s=1.2) -> str:
    """Writes the figure to `path`, returns it; hit_rule's trigger is drawn when given: each
    film's level + threshold in Hold (hit_trigger_lines), or the threshold alone without a
    level."""
    transitions, spans = logged_transitions(log), state_spans(log)
    avoid = [e for e in transitions if e.to_mode == Mode.AVOID]
    if not avoid:
        raise NoAvoidError("the trial has no Avoid transition (was there a hit in Hold? "
                           "e.g. --scenario-name box_hit_in_hold)")
    t0 = avoid[0].t
    window = (t0 - before_s, t0 + after_s)
    events = {name: t for name, t in physical_events(log).items()
              if window[0] <= t <= window[1]}
    shown = [e for e in transitions if window[0] <= e.t <= window[1]]
    figure = new_figure(10.0, 8.5)
    axes = figure.subplots(5, 1, sharex=True,
                           gridspec_kw={"height_ratios": [0.3, 0.4, 1.3, 1.3, 1.3]})
    annotation_axis, state_axis, ra_axis, sa_axis, object_axis = axes
    fast = (log.t_ra >= window[0]) & (log.t_ra <= window[1])
    for k, finger in enumerate(FINGER_NAMES):
        ra_axis.plot(log.t_ra[fast], log.ra[fast, k], lw=0.8, color=FINGER_COLORS[k],
                     label=f"RA {finger}", zorder=2)
        sa_axis.plot(log.t_ra[fast], log.sa[fast, k], lw=0.8, color=FINGER_COLORS[k],
                     label=f"SA {finger}", zorder=2)
    if hit_rule is not None and hit_rule.level_s <= 0.0:
        ra_axis.axhline(hit_rule.threshold_mps2, color="black", ls="--", lw=0.8,
                        label=f"hit threshold {hit_rule.threshold_mps2:.3g} m/s²")
    elif hit_rule is not None:
        holds = [(a, b) for state, a, b in spans
                 if state == Mode.HOLD.label and b > window[0] and a < window[1]]
        t_tick, trigger = hit_trigger_lines(log.t_ra, log.ra, holds, hit_rule)
        for k, finger in enumerate(FINGER_NAMES):
            ra_axis.step(t_tick, trigger[:, k], where="post", color=FINGER_COLORS[k], ls="--",
                         lw=0.8, zorder=3,
                         label=f"hit trigger {finger}: {hit_rule.threshold_mps2:.3g} m/s² over "
                               f"its mean of the {1000 * hit_rule.level_s:g} ms before in Hold")
    ra_axis.set_ylabel("RA (Eq. 2) [m/s²]")
    sa_axis.set_ylabel("SA (Eq. 1) [N]")
    slow = (log.t_slow >= window[0]) & (log.t_slow <= window[1])
    p_WO = log.object_state[slow, 4:7]
    for axis, name in enumerate("xyz"):
        object_axis.plot(log.t_slow[slow], 1000.0 * (p_WO[:, axis] - p_WO[0, axis]),
                         color=OBJECT_AXIS_COLORS[axis], lw=1.0, label=f"world {name}", zorder=2)
    object_axis.set_ylabel(f"object displacement\nsince {window[0]:.2f} s [mm]")
    object_axis.set_xlabel("time [s]")
    object_axis.set_xlim(*window)
    for axis in (ra_axis, sa_axis, object_axis):
        draw_state_bands(axis, spans)
        draw_transition_lines(axis, shown)
        draw_physical_events(axis, events)
        axis.grid(True, axis="y", alpha=0.3)
        axis.legend(loc="best", fontsize=8)
    direction = "none" if avoid[0].direction is None else \
        "(" + ", ".join(f"{v:g}" for v in avoid[0].direction) + ")"
    hit_time = events.get(PHYSICAL_EVENT_NAMES["hit"])
    delay = "" if hit_time is None else f", {1000 * (t0 - hit_time):.0f} ms after the hit"
    figure.suptitle(f"Fig. 10: a hit in Hold and the Avoid reaction\n{run_description(log)}\n"
                    f"{_hit_text(log)}; Hold -> Avoid at {t0:.3f} s{delay}, moving along "
                    f"{direction}", fontsize=10)
    figure.legend(handles=marker_legend_handles(shown, events), loc="outside lower center",
                  ncols=2, fontsize=8)
    figure.draw_without_rendering()  # fix the layout, then place the labels
    draw_state_strip(state_axis, [(s, max(a, window[0]), min(b, window[1]))
                                  for s, a, b in spans if b > window[0] and a < window[1]])
    draw_annotation_strip(annotation_axis, shown, events)
    return str(save_figure(figure, path))
