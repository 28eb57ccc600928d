"""WindowNormalizer: the last 0.5 s of each tactile channel, divided by its maximum."""

import dataclasses
import functools
import math
from collections.abc import Callable

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.tactile.sampling import RateGroup, rate_groups
from tegrasp_drake.tactile.sliding_window import SlidingWindowState, default_sliding_window


@dataclasses.dataclass
class WindowNormalizerConfig:
    """Window length [s] and the rates [Hz] at which SA and RA channels are sampled."""
    window_s: float = 0.5
    sa_rate_hz: float = 100.0
    ra_rate_hz: float = 1000.0

    def rate_groups(self) -> tuple[RateGroup, ...]:
        """The channels sampled together, one periodic update per group."""
        return rate_groups(sa_rate_hz=self.sa_rate_hz, ra_rate_hz=self.ra_rate_hz,
                           window_s=self.window_s)


def window_layout(group: RateGroup) -> SlidingWindowState:
    """How a WindowNormalizer holds `group`'s window in its state (and in the group's
    `*_window_position` and `*_window_buffer` outputs)."""
    return SlidingWindowState(default_sliding_window(len(group.channels), group.window_length))


def entering_samples(channels: np.ndarray, rows: slice, newest: Callable[[], np.ndarray]
                     ) -> tuple[np.ndarray, list[bool] | None]:
    """The samples a tick pushes into a rate group's window, and which of them are missing.

    The group's `rows` of the four channels enter the window, except a non-finite one (NaN
    or inf: a sensor glitch, a lost frame), which is missing: the channel's newest sample
    in the window, `newest()` (called only then), enters in its place, so that the window
    and the sums kept over it stay finite. Returns (samples, missing: a bool per row, or
    None when none is). The EventScorer slides its correlations by these same samples and
    scores a channel 0 while a missing sample is in its window.
    """
    samples = channels[rows]
    if math.isfinite(sum(samples.tolist())):  # the common case, at a fraction of isfinite's cost
        return samples, None
    missing = ~np.isfinite(samples)
    return np.where(missing, newest(), samples), missing.tolist()


class WindowNormalizer(LeafSystem):
    """Keeps the last `window_s` of each channel in the Context; outputs them max-normalised,
    and raw for the EventMatcher to score (the paper's Fig. 3, Sec. III-A and III-B).

    Periodic discrete updates sample the SA entries of `channels` at sa_rate_hz and the RA
    entries at ra_rate_hz (one update for all four when the rates match). Before a full
    window has been sampled, the older part of the window is zero. A non-finite sample is
    missing: the channel's previous sample enters instead (entering_samples). As for any
    discrete state, a system that updates at the same tick reads the windows before that
    tick's sample (the EventMatcher's scorer adds it from `channels`).

    .. pydrake_system::

        name: WindowNormalizer
        input_ports:
        - channels
        output_ports:
        - sa_window
        - ra_window
        - sa_window_position
        - sa_window_buffer
        - ra_window_position
        - ra_window_buffer

    Ports:
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2).
        sa_window: 2 * N_sa values, [sa_left window, sa_right window], oldest first, each
            divided by its max |value| (an all-zero window stays zero); unitless.
        ra_window: 2 * N_ra values, likewise for ra_left, ra_right.
        sa_window_position, sa_window_buffer (and ra_*): the raw SA windows as the state
            holds them (N), laid out by `window_layout` (SlidingWindowState): the position
            (offset, samples held, each window's oldest sample) and the buffer. One
            `sa_ra_window_*` pair instead when the rates match.
    with N_sa = window_s * sa_rate_hz and N_ra = window_s * ra_rate_hz.
    """

    def __init__(self, config: WindowNormalizerConfig | None = None):
        super().__init__()
        config = dataclasses.replace(config or WindowNormalizerConfig())
        self._config = config
        self._channels_port = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._window_lengths = {}
        self._window_ports = {}
        raw_windows = {}
        for group in config.rate_groups():
            layout = window_layout(group)
            indices = (self.DeclareDiscreteState(layout.position_size),
                       self.DeclareDiscreteState(layout.buffer_size))
            channels = slice(group.channels[0], group.channels[-1] + 1)
            self.DeclarePeriodicDiscreteUpdateEvent(
                1.0 / group.rate_hz, 0.0,
                functools.partial(self._sample, indices=indices, layout=layout,
                                  channels=channels))
            for kind, kind_channels in (("sa", SA_CHANNELS), ("ra", RA_CHANNELS)):
                if kind_channels[0] in group.channels:
                    first_row = group.channels.index(kind_channels[0])
                    rows = slice(first_row, first_row + len(kind_channels))
                    self._window_lengths[kind] = group.window_length
                    self._window_ports[kind] = self.DeclareVectorOutputPort(
                        f"{kind}_window", len(kind_channels) * group.window_length,
                        functools.partial(self._calc_window, indices=indices, layout=layout,
                                          rows=rows),
                        prerequisites_of_calc={self.discrete_state_ticket(i)
                                               for i in indices})
            raw_windows[group.name] = indices
        for name, (position, buffer) in raw_windows.items():
            self.DeclareStateOutputPort(f"{name}_window_position", position)
            self.DeclareStateOutputPort(f"{name}_window_buffer", buffer)

    @property
    def config(self) -> WindowNormalizerConfig:
        return dataclasses.replace(self._config)

    def window_length(self, kind: str) -> int:
        """Samples per channel in the `kind` ("sa" or "ra") window."""
        return self._window_lengths[kind]

    def _sample(self, context, discrete_state, *, indices, layout, channels):
        position = discrete_state.get_mutable_value(indices[0])
        buffer = discrete_state.get_mutable_value(indices[1])
        samples, _ = entering_samples(self._channels_port.Eval(context), channels,
                                      lambda: layout.newest_in(position, buffer))
        layout.push_into(position, buffer, samples)

    def _calc_window(self, context, output, *, indices, layout, rows):
        window = layout.window_in(*(context.get_discrete_state(i).value() for i in indices))
        output.SetFromVector(np.ravel(normalize_by_max(window[rows])))
