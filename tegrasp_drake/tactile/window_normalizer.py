"""WindowNormalizer: the last 0.5 s of each tactile channel, divided by its maximum."""

import dataclasses
import functools

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.tactile.sampling import rate_groups
from tegrasp_drake.tactile.sliding_window import SlidingWindowState, default_sliding_window


@dataclasses.dataclass
class WindowNormalizerConfig:
    """Window length [s] and the rates [Hz] at which SA and RA channels are sampled."""
    window_s: float = 0.5
    sa_rate_hz: float = 100.0
    ra_rate_hz: float = 1000.0


class WindowNormalizer(LeafSystem):
    """Keeps the last `window_s` of each channel in the Context; outputs them max-normalised.

    Periodic discrete updates sample the SA entries of `channels` at sa_rate_hz and the RA
    entries at ra_rate_hz (one update for all four when the rates match). Before a full
    window has been sampled, the older part of the window is zero.

    .. pydrake_system::

        name: WindowNormalizer
        input_ports:
        - channels
        output_ports:
        - sa_window
        - ra_window

    Ports:
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2).
        sa_window: 2 * N_sa values, [sa_left window, sa_right window], oldest first, each
            divided by its max |value| (an all-zero window stays zero); unitless.
        ra_window: 2 * N_ra values, likewise for ra_left, ra_right.
    with N_sa = window_s * sa_rate_hz and N_ra = window_s * ra_rate_hz.
    """

    def __init__(self, config: WindowNormalizerConfig | None = None):
        super().__init__()
        config = dataclasses.replace(config or WindowNormalizerConfig())
        self._config = config
        self._channels_port = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._window_lengths = {}
        self._window_ports = {}
        for group in rate_groups(sa_rate_hz=config.sa_rate_hz,
                                 ra_rate_hz=config.ra_rate_hz, window_s=config.window_s):
            layout = SlidingWindowState(
                default_sliding_window(len(group.channels), group.window_length))
            index = self.DeclareDiscreteState(layout.size)
            channels = slice(group.channels[0], group.channels[-1] + 1)
            self.DeclarePeriodicDiscreteUpdateEvent(
                1.0 / group.rate_hz, 0.0,
                functools.partial(self._sample, index=index, layout=layout,
                                  channels=channels))
            for kind, kind_channels in (("sa", SA_CHANNELS), ("ra", RA_CHANNELS)):
                if kind_channels[0] in group.channels:
                    first_row = group.channels.index(kind_channels[0])
                    rows = slice(first_row, first_row + len(kind_channels))
                    self._window_lengths[kind] = group.window_length
                    self._window_ports[kind] = self.DeclareVectorOutputPort(
                        f"{kind}_window", len(kind_channels) * group.window_length,
                        functools.partial(self._calc_window, index=index, layout=layout,
                                          rows=rows),
                        prerequisites_of_calc={self.discrete_state_ticket(index)})

    @property
    def config(self) -> WindowNormalizerConfig:
        return dataclasses.replace(self._config)

    def window_length(self, kind: str) -> int:
        """Samples per channel in the `kind` ("sa" or "ra") window."""
        return self._window_lengths[kind]

    def _sample(self, context, discrete_state, *, index, layout, channels):
        samples = self._channels_port.Eval(context)[channels]
        layout.push(discrete_state.get_mutable_vector(index).get_mutable_value(), samples)

    def _calc_window(self, context, output, *, index, layout, rows):
        window = layout.current(context.get_discrete_state(index).value())[rows]
        output.SetFromVector(np.ravel(normalize_by_max(window)))
