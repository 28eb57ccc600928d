"""Sample rates, window lengths and template resampling for the tactile event
windows; channels that share a rate form one RateGroup, served by one periodic update."""

import dataclasses
import functools

import numpy as np

from tegrasp_drake.rig.channels import RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.rig.number_text import number_text

_INTEGER_TOLERANCE = 1e-9


def samples_per_window(window_s: float, rate_hz: float) -> int:
    """Samples in `window_s` [s] at `rate_hz` [Hz]; ValueError unless an integer >= 2."""
    if not (window_s > 0.0 and rate_hz > 0.0):
        raise ValueError(f"window_s ({number_text(window_s)}) and rate_hz "
                         f"({number_text(rate_hz)}) must be positive")
    exact = window_s * rate_hz
    count = int(round(exact))
    if count < 2 or abs(exact - count) > _INTEGER_TOLERANCE * max(1.0, exact):
        raise ValueError(
            f"a window of {number_text(window_s)} s at {number_text(rate_hz)} Hz holds "
            f"{number_text(exact)} samples; "
            "choose a window and rate whose product is an integer of 2 or more")
    return count


@dataclasses.dataclass(frozen=True)
class RateGroup:
    """Channels (indices into CHANNEL_NAMES) sampled together at one rate."""
    rate_hz: float
    channels: tuple[int, ...]
    window_length: int  # samples per window

    @functools.cached_property
    def name(self) -> str:
        """The group's kinds of channel: "sa", "ra", or "sa_ra" (port names use it)."""
        kinds = (("sa", SA_CHANNELS), ("ra", RA_CHANNELS))
        return "_".join(kind for kind, channels in kinds if channels[0] in self.channels)


def rate_groups(*, sa_rate_hz: float, ra_rate_hz: float,
                window_s: float) -> tuple[RateGroup, ...]:
    """One group for all four channels when the rates match, else an SA and an RA group."""
    if sa_rate_hz == ra_rate_hz:
        return (RateGroup(sa_rate_hz, SA_CHANNELS + RA_CHANNELS,
                          samples_per_window(window_s, sa_rate_hz)),)
    return (RateGroup(sa_rate_hz, SA_CHANNELS, samples_per_window(window_s, sa_rate_hz)),
            RateGroup(ra_rate_hz, RA_CHANNELS, samples_per_window(window_s, ra_rate_hz)))


def resample_window(window: np.ndarray, length: int) -> np.ndarray:
    """Resample each row of `window` to `length` samples, each the mean of the held signal over
    its interval: the area is kept and RA bursts do not alias."""
    window = np.atleast_2d(np.asarray(window, dtype=float))
    length_in = window.shape[-1]
    if length == length_in:
        return window.copy()
    edges_in = np.linspace(0.0, 1.0, length_in + 1)
    edges_out = np.linspace(0.0, 1.0, length + 1)
    integral = np.concatenate(
        [np.zeros((window.shape[0], 1)), np.cumsum(window, axis=-1) / length_in], axis=-1)
    integral_out = np.stack([np.interp(edges_out, edges_in, row) for row in integral])
    return np.diff(integral_out, axis=-1) * length
