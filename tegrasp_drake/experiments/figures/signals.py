"""Figures of a trial: raw taxels and pad films, SA/RA with phases (paper Fig. 5a-b), and the
RA around first contact over a few tens of milliseconds."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tegrasp_drake.experiments.grasp_outcome import first_contact_time  # noqa: E402
from tegrasp_drake.rig.channels import FINGER_NAMES  # noqa: E402

CONTACT_ZOOM_S = (-0.04, 0.06)  # the last row's window around first contact [s]


def _mark_phases(axis, log):
    for name, t in log.meta.get("phase_starts", {}).items():
        axis.axvline(t, color="0.6", lw=0.6, ls="--")
    for name, t in (log.meta.get("events") or {}).items():
        if t is not None:
            axis.axvline(t, color="tab:red", lw=0.8, alpha=0.6)


def plot_trial_signals(log, path) -> None:
    """Writes a PNG: per finger, raw taxel forces and the pad film's signal (Fig. 5a), the
    processed SA and RA channels with phase boundaries (dashed) and events (red) (Fig. 5b),
    and RA from 40 ms before to 60 ms after the first taxel contact (the film's ring; the
    taxels, sampled at 108 Hz, see the contact up to a period after the film)."""
    fig, axes = plt.subplots(5, 2, figsize=(13, 12.5))
    contact = first_contact_time(log)
    for k, finger in enumerate(FINGER_NAMES):
        ax = axes[0, k]
        ax.plot(log.t_sa, log.taxels[:, 12 * k:12 * (k + 1)], lw=0.7)
        ax.set_title(f"{finger} finger: raw taxel normal forces (12)")
        ax.set_ylabel("F_z [N]")
        ax = axes[1, k]
        ax.plot(log.t_ra, log.pad_acceleration[:, 3 * k:3 * (k + 1)], lw=0.5)
        ax.set_ylabel("film [m/s^2 equiv.]")
        ax.set_title(f"{finger} pad film (x, y, z; the film's axis is the pad normal z)")
        ax = axes[2, k]
        ax.plot(log.t_ra, log.sa[:, k], color="tab:blue", lw=0.8)
        ax.set_ylabel("SA [N] (Eq. 1)")
        _mark_phases(ax, log)
        ax = axes[3, k]
        ax.plot(log.t_ra, log.ra[:, k], color="tab:orange", lw=0.6)
        ax.set_ylabel("RA [m/s^2] (Eq. 2)")
        ax.set_xlabel("time [s]")
        _mark_phases(ax, log)
        for ax in axes[:4, k]:
            ax.sharex(axes[3, k])
        ax = axes[4, k]
        if contact is None:
            ax.set_title("no contact")
            continue
        window = ((log.t_ra >= contact + CONTACT_ZOOM_S[0])
                  & (log.t_ra <= contact + CONTACT_ZOOM_S[1]))
        ax.plot(1e3 * (log.t_ra[window] - contact), log.ra[window, k], color="tab:orange",
                lw=0.8, marker=".", ms=3)
        ax.set_title(f"{finger} RA around first contact (1 ms peak-hold samples)")
        ax.set_xlabel("time from the first taxel contact [ms]")
        ax.set_ylabel("RA [m/s^2]")
    starts = log.meta.get("phase_starts", {})
    for name, t in starts.items():
        axes[2, 0].text(t, axes[2, 0].get_ylim()[1] * 0.9, name, fontsize=7, rotation=90,
                        va="top")
    fig.suptitle(f"{log.meta.get('controller', '')} trial: "
                 f"{log.meta.get('object', '')}", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
