"""The RA at first contact (the paper's Fig. 5a-b, zoomed): each pad's film signal and Eq. 2
from 40 ms before to 60 ms after the first taxel contact, at the RA's 1 ms peak-hold samples,
so that the film's ring (the fingertip's 400 Hz mode decaying over about 10 ms) is visible.
The taxels, sampled at 108 Hz, see the contact up to one period after the film."""

from tegrasp_drake.figures.figure_files import new_figure, save_figure
from tegrasp_drake.figures.trial_annotations import run_description
from tegrasp_drake.scenario.grasp_outcome import first_contact_time
from tegrasp_drake.rig.channels import FINGER_NAMES

CONTACT_ZOOM_S = (-0.04, 0.06)  # the window around first contact [s]


def plot_contact_ra(log, path) -> str | None:
    """Writes the figure to `path` and returns it as text; None (no file) if no pad touched."""
    contact = first_contact_time(log)
    if contact is None:
        return None
    window = (log.t_ra >= contact + CONTACT_ZOOM_S[0]) & (log.t_ra <= contact + CONTACT_ZOOM_S[1])
    t_ms = 1e3 * (log.t_ra[window] - contact)
    figure = new_figure(12.0, 4.5)
    axes = figure.subplots(1, len(FINGER_NAMES), sharey=True)
    for finger, (axis, name) in enumerate(zip(axes, FINGER_NAMES)):
        film = log.pad_acceleration[window, 3 * finger:3 * finger + 3]
        axis.plot(t_ms, film[:, 2], lw=0.8, color="tab:blue", marker=".", ms=3,
                  label="film, pad normal z (signed)")
        axis.plot(t_ms, log.ra[window, finger], lw=0.8, color="tab:orange", marker=".", ms=3,
                  label="RA = |a| (Eq. 2)")
        axis.axvline(0.0, color="#117a65", ls=(0, (6, 2)), lw=1.0, label="first taxel contact")
        axis.set_title(f"{name} pad")
        axis.set_xlabel("time from the first taxel contact [ms]")
        axis.grid(True, alpha=0.3)
    axes[0].set_ylabel("film signal [m/s² equiv.]")
    axes[-1].legend(loc="upper right", fontsize=8)
    figure.suptitle(f"RA at first contact (1 ms peak-hold samples), {run_description(log)}")
    return str(save_figure(figure, path))
