"""The figures of one trial, as `tegrasp trial`/`demo` write them: Fig. 9 (states), Fig. 5a-b
(signals), the RA at first contact (contact_ra) and, when the trial has a Hold -> Avoid
transition, Fig. 10 (avoid)."""

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.figures.avoid import logged_hit_rule, plot_avoid_reaction
from tegrasp_drake.figures.contact_ra import plot_contact_ra
from tegrasp_drake.figures.figure_files import figure_path
from tegrasp_drake.figures.signals import plot_trial_signals
from tegrasp_drake.figures.states import plot_trial_states
from tegrasp_drake.figures.trial_annotations import logged_transitions


# The figures' file stems (STEM.FORMAT in the run folder).
TRIAL_FIGURE_STEMS = ("states", "signals", "contact_ra", "avoid")
# The result's field that records each figure's path (result.json), by stem.
TRIAL_FIGURE_KEYS = dict(zip(TRIAL_FIGURE_STEMS, ("figure", "signals_figure",
                                                  "contact_ra_figure", "avoid_figure")))


def write_trial_figures(log, folder, figure_format: str = "png") -> dict[str, str]:
    """Writes the trial's figures into `folder`; returns their paths as the result's fields:
    figure (Fig. 9), signals_figure (Fig. 5a-b), contact_ra_figure (when a pad touched) and
    avoid_figure (Fig. 10, after a hit in Hold)."""
    states, signals, contact_ra, avoid = (figure_path(folder, stem, figure_format)
                                          for stem in TRIAL_FIGURE_STEMS)
    keys = TRIAL_FIGURE_KEYS
    figures = {keys["states"]: plot_trial_states(log, states),
               keys["signals"]: plot_trial_signals(log, signals)}
    contact_ra = plot_contact_ra(log, contact_ra)
    if contact_ra is not None:
        figures[keys["contact_ra"]] = contact_ra
    if any(t.to_mode == Mode.AVOID for t in logged_transitions(log)):
        figures[keys["avoid"]] = plot_avoid_reaction(
            log, avoid,
            hit_rule=logged_hit_rule(log))
    return figures
