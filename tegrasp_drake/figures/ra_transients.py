"""The first-contact RA transient of the replaced accelerometer chain and of the PVDF film,
side by side, at several plant steps (runs/pad_strike.py)."""

import pathlib
from collections.abc import Mapping

import numpy as np

from tegrasp_drake.figures.figure_files import new_figure, save_figure

WINDOW_MS = (-5.0, 30.0)  # around each contact


def _panel(axis, strikes, pad: int, contact_pad: int, values_of, title: str):
    peaks = []
    for time_step, strike in strikes.items():
        contact = strike.contact_times[contact_pad]
        t = 1e3 * (strike.t_ra - contact)
        window = (t >= WINDOW_MS[0]) & (t <= WINDOW_MS[1])
        values = values_of(strike)[window, pad]
        peaks.append(np.abs(values).max())
        axis.plot(t[window], values, marker=".", ms=3, lw=0.8,
                  label=f"dt {1e3 * time_step:g} ms: peak {peaks[-1]:.1f}")
    axis.set_title(f"{title} (peaks {min(peaks):.1f}-{max(peaks):.1f})", fontsize=9)
    axis.set_xlabel("time from the contact [ms]")
    axis.legend(fontsize=7)


def plot_ra_transients(strikes: Mapping[float, object], path,
                       highpass_hz: float = 2.0) -> pathlib.Path:
    """Writes the figure to `path` (PNG, PDF or SVG by its suffix: save_figure, atomically):
    rows the left pad at contact, the right pad while only the left touches, the right pad at
    its contact; columns the accelerometer chain's RA and the film's. `strikes` maps plant
    steps [s] to PadStrikes of one strike."""
    figure = new_figure(12, 10)
    axes = figure.subplots(3, 2)
    rows = (("left pad, its contact", 0, 0), ("right pad, left pad's contact", 1, 0),
            ("right pad, its own contact", 1, 1))
    for row, (what, pad, contact_pad) in enumerate(rows):
        _panel(axes[row, 0], strikes, pad, contact_pad,
               lambda s: s.accelerometer_ra(highpass_hz),
               f"old: accelerometer |HP(a_n)|, {what}")
        _panel(axes[row, 1], strikes, pad, contact_pad, lambda s: np.abs(s.ra),
               f"new: film RA, {what}")
        axes[row, 0].set_ylabel("RA [m/s^2 (equiv.)]")
    figure.suptitle("First-contact RA: rigid-body accelerometer vs PVDF film, "
                    "1 kHz samples at three plant steps")
    return save_figure(figure, path, dpi=110)
