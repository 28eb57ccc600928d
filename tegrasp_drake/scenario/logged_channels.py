"""A trial log's channels against the samples they are computed from: the paper's Eq. 1 (SA, a
pad's 12 taxels summed) and Eq. 2 (RA, the size of its pad's 3-axis vibration). The channels
are logged at the RA rate from the same ports the taxels and pad accelerations are logged
from (scenario/trial_log_writer.py), so a log whose taxels were reversed, shifted, swapped
between pads or edited no longer sums to its SA channels, and is refused rather than drawn
or replayed as if it were one trial."""

import numpy as np

from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS, TAXELS_PER_PAD
from tegrasp_drake.rig.number_text import distinct_number_texts, number_text
from tegrasp_drake.rig.station_interface import PAD_ACCELERATION_AXES

# Relative to the larger of a channel's value and what it is computed from (the taxels' or
# the axes' absolute sum), plus one part in 1e9 of a newton or m/s^2: the logged channel and
# the sum here are the same float64 operations (measured: equal to the last bit in a 12 s
# trial's 12001 samples); 1e-9 lets a different summation order by, and no edited sample.
_RELATIVE_TOLERANCE = 1e-9


def _held_taxel_rows(t_sa: np.ndarray, t_ra: np.ndarray) -> np.ndarray:
    """For each RA time, the index of the taxel sample its SA channel holds, or -1 past the
    last one. The taxel port is a zero-order hold updated at the SA rate, and a logger at time
    t records the value held up to t: the sample at the first SA time at or after t (a time
    within one part in 1e6 of an SA period of it counts as the same: the two loggers' times
    are products of different periods, rounded differently)."""
    period = float(np.median(np.diff(t_sa)))
    rows = np.searchsorted(t_sa, t_ra - 1e-6 * period, side="left")
    rows[rows >= len(t_sa)] = -1
    return rows


def _first_off(logged: np.ndarray, computed: np.ndarray, scale: np.ndarray) -> int | None:
    """The first sample where `logged` differs from `computed` beyond the tolerance, or None."""
    off = np.flatnonzero(np.abs(logged - computed)
                         > _RELATIVE_TOLERANCE * (np.maximum(np.abs(logged), scale) + 1.0))
    return int(off[0]) if off.size else None


def logged_channels_problem(arrays: dict) -> str | None:
    """What is wrong if the log's SA channels are not Eq. 1 of its taxels as held at each RA
    time, or its RA channels not Eq. 2 of its pad accelerations, or None. Each check needs its
    arrays (finite, of their shapes: trial_arrays_problem) and is skipped without them."""
    if all(name in arrays for name in ("t_sa", "taxels", "t_ra", "channels")):
        t_ra, channels = np.asarray(arrays["t_ra"], float), np.asarray(arrays["channels"], float)
        taxels = np.asarray(arrays["taxels"], dtype=float)
        rows = _held_taxel_rows(np.asarray(arrays["t_sa"], dtype=float), t_ra)
        inside = np.flatnonzero(rows >= 0)
        for pad, column in enumerate(SA_CHANNELS):
            pad_taxels = taxels[rows[inside], pad * TAXELS_PER_PAD:(pad + 1) * TAXELS_PER_PAD]
            off = _first_off(channels[inside, column], np.add.reduce(pad_taxels, axis=1),
                             np.add.reduce(np.abs(pad_taxels), axis=1))
            if off is not None:
                k, row = int(inside[off]), int(rows[inside[off]])
                logged, summed = distinct_number_texts(float(channels[k, column]),
                                                       float(pad_taxels[off].sum()))
                return (f"'channels' sample {k} (t = {number_text(float(t_ra[k]))} s) column "
                        f"{column} ({CHANNEL_NAMES[column]}) holds {logged}, but the pad's 12 "
                        f"taxels at sample {row} sum to {summed} (Eq. 1); the taxels or the "
                        "channels were changed after the trial")
    if all(name in arrays for name in ("pad_acceleration", "channels")):
        channels = np.asarray(arrays["channels"], dtype=float)
        axes = np.asarray(arrays["pad_acceleration"], dtype=float)
        for pad, column in enumerate(RA_CHANNELS):
            pad_axes = axes[:, pad * PAD_ACCELERATION_AXES:(pad + 1) * PAD_ACCELERATION_AXES]
            size = np.sqrt(np.einsum("ij,ij->i", pad_axes, pad_axes))
            off = _first_off(channels[:, column], size, np.abs(pad_axes).sum(axis=1))
            if off is not None:
                logged, computed = distinct_number_texts(float(channels[off, column]),
                                                         float(size[off]))
                return (f"'channels' sample {off} column {column} ({CHANNEL_NAMES[column]}) "
                        f"holds {logged}, but the pad's acceleration there has size "
                        f"{computed} m/s^2 (Eq. 2); the accelerations or the channels were "
                        "changed after the trial")
    return None
