"""WindowNormalizer: the last 0.5 s of each tactile channel, divided by its maximum."""

import dataclasses
import functools
from collections.abc import Mapping

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.api_boundary import check_field_values, public_api
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.rig.echo import shown
from tegrasp_drake.rig.number_text import count_text, number_text
from tegrasp_drake.rig.ranges import (EVENT_WINDOW, READ_PERIOD, SAMPLE_BLOCK, SAMPLE_RATE,
                                      within)
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.tactile.read_batch import (AddHeldSampleRegister, batch_first_sample,
                                              batch_update_offset, samples_per_read)
from tegrasp_drake.tactile.sample_block import (AddSampleRegister, block_samples,
                                               block_update_period, samples_in_block)
from tegrasp_drake.tactile.sampling import RateGroup, rate_groups
from tegrasp_drake.tactile.sliding_window import SlidingWindowState, default_sliding_window


@dataclasses.dataclass
class WindowNormalizerConfig:
    """Window [s], SA and RA rates [Hz], the block [s] a rate takes per update (0: per sample;
    sample_block.py), and read_period_s, the one reader's tick [s] (0: any time; else a per-sample
    rate takes each tick's samples in one update just before it, read_batch.py)."""
    window_s: float = within(0.5, EVENT_WINDOW)
    sa_rate_hz: float = within(100.0, SAMPLE_RATE)
    ra_rate_hz: float = within(1000.0, SAMPLE_RATE)
    block_s: float = within(0.0, SAMPLE_BLOCK)
    read_period_s: float = within(0.0, READ_PERIOD)

    def __post_init__(self):
        check_field_values(self)  # a window's samples are allocated: refused out of range

    def rate_groups(self) -> tuple[RateGroup, ...]:
            return rate_groups(sa_rate_hz=self.sa_rate_hz, ra_rate_hz=self.ra_rate_hz,
                           window_s=self.window_s)


def window_layout(group: RateGroup) -> SlidingWindowState:
    """`group`'s window, at the start of the group's state."""
    return SlidingWindowState(default_sliding_window(len(group.channels), group.window_length))


@dataclasses.dataclass(frozen=True)
class RateWindow:
    """One rate group's sliding window in a WindowNormalizer's Context."""
    group: RateGroup
    layout: SlidingWindowState  # how the state holds the window (window_layout)
    state: object  # DiscreteStateIndex of the group's state vector
    channels: slice  # the group's entries of the four channels
    block_samples: int  # samples per update (1: one per sample period)
    block: object  # the `<group>_block` input port (the last block_samples samples)
    before_read: bool = False  # the samples are a read batch (read_batch.py), not a block


def check_window_states(window_states: Mapping[str, np.ndarray], sizes: dict[str, int]) -> None:
    """ValueError naming what in a WindowNormalizer's `window_states` is not one 1-D array of
    numbers per rate group that starts with the group's empty window (`sizes`: {group name:
    entries of its window, all zero}), and saying what was given."""
    where = "WindowNormalizer: argument 'window_states'"
    unknown = [key for key in window_states if key not in sizes]
    missing = [key for key in sizes if key not in window_states]
    if unknown or missing:
        wrong = ([f"has unknown {_keys(unknown)}"] if unknown else []) + (
            [f"lacks {_keys(missing)}"] if missing else [])
        raise ValueError(f"{where} {' and '.join(wrong)}; give one initial state per rate "
                         f"group of the config, keyed {', '.join(map(shown, sizes))}")
    for name, size in sizes.items():
        state, at = window_states[name], f"{where[:-1]}[{shown(name)}]'"
        if state.dtype.kind not in "biuf":
            raise ValueError(f"{at} must be an array of numbers, got an array of dtype "
                             f"{state.dtype}")
        if state.ndim != 1:
            raise ValueError(f"{at} must be a 1-D array (an empty window of {size} zeros, then "
                             f"the subclass's own state), got a {state.ndim}-D array of "
                             f"shape {state.shape}")
        if len(state) < size:
            raise ValueError(f"{at} must start with an empty window of {size} zeros, got "
                             f"{count_text(len(state), 'number')}")
        filled = np.flatnonzero(state[:size])  # NaN is nonzero
        if len(filled):
            raise ValueError(f"{at} must start with an empty window of {size} zeros, got "
                             f"{number_text(float(state[filled[0]]))} at entry {filled[0]}")


def _keys(names: list[str]) -> str:
    """'key 'x'' or 'keys 'x', 'y'', as a message names keys of a mapping."""
    return f"key{'' if len(names) == 1 else 's'} {', '.join(map(shown, names))}"


class WindowNormalizer(LeafSystem):
    """Keeps the last `window_s` of each channel in the Context and outputs them
    max-normalised (the paper's Fig. 3, Sec. III-A).

    One periodic update per rate group; a rate in blocks or read batches pushes the
    `<group>_block` input's samples in order, so at each block end or reader's tick the
    windows equal the per-sample ones. An unfilled window is zero at its old end; a
    non-finite sample repeats the channel's previous one. A subclass keeps its own state
    after the window in the group's vector (`window_states`), updated in `_after_push`.

    .. pydrake_system::

        name: WindowNormalizer
        input_ports:
        - channels
        - sa_block (optional)
        - ra_block (optional)
        output_ports:
        - sa_window
        - ra_window

    Ports:
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2).
        sa_block, ra_block (sa_ra_block when the rates match): the rate's last
            block_samples samples, oldest first, for a rate in blocks or read batches.
        sa_window, ra_window: [left, right] windows of window_s * rate samples, oldest
            first, each divided by its max |value| (all-zero stays zero); unitless.
    """

    @public_api
    def __init__(self, config: WindowNormalizerConfig | None = None, *,
                 window_states: Mapping[str, np.ndarray] | None = None):
        """window_states: for a subclass, {group name: initial state}: an empty window, then
        what the subclass keeps."""
        super().__init__()
        config = dataclasses.replace(config or WindowNormalizerConfig())
        self._config = config
        self._channels_port = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._window_lengths = {}
        rate_windows = []
        if window_states is not None:
            check_window_states(window_states, {group.name: window_layout(group).size
                                                for group in config.rate_groups()})
        for group in config.rate_groups():
            layout = window_layout(group)
            initial = (np.zeros(layout.size) if window_states is None
                       else np.asarray(window_states[group.name], dtype=float))
            samples = block_samples(group.rate_hz, config.block_s)
            batch = (samples_per_read(group.rate_hz, config.read_period_s) if samples == 1
                     else 1)
            samples = max(samples, batch)
            window = RateWindow(group, layout, self.DeclareDiscreteState(initial),
                                slice(group.channels[0], group.channels[-1] + 1), samples,
                                self.DeclareVectorInputPort(f"{group.name}_block",
                                                            samples * len(group.channels)),
                                before_read=batch > 1)
            if batch > 1:
                self.DeclarePeriodicDiscreteUpdateEvent(
                    config.read_period_s,
                    batch_update_offset(group.rate_hz, config.read_period_s),
                    functools.partial(self._sample_batch, window))
            elif samples > 1:
                self.DeclarePeriodicDiscreteUpdateEvent(
                    block_update_period(1.0 / group.rate_hz, samples), 0.0,
                    functools.partial(self._sample_block, window))
            else:
                self.DeclarePeriodicDiscreteUpdateEvent(1.0 / group.rate_hz, 0.0,
                                                        functools.partial(self._sample, window))
            rate_windows.append(window)
            for kind, kind_channels in (("sa", SA_CHANNELS), ("ra", RA_CHANNELS)):
                if kind_channels[0] in group.channels:
                    first_row = group.channels.index(kind_channels[0])
                    self._window_lengths[kind] = group.window_length
                    self.DeclareVectorOutputPort(
                        f"{kind}_window", len(kind_channels) * group.window_length,
                        functools.partial(self._calc_window, window, slice(
                            first_row, first_row + len(kind_channels))),
                        prerequisites_of_calc={self.discrete_state_ticket(window.state)})
        self._rate_windows = tuple(rate_windows)

    @property
    def config(self) -> WindowNormalizerConfig:
        return dataclasses.replace(self._config)

    @property
    def rate_windows(self) -> tuple[RateWindow, ...]:
        return self._rate_windows

    def window_length(self, kind: str) -> int:
        """Samples per channel in the `kind` ("sa" or "ra") window."""
        return self._window_lengths[kind]

    def _sample(self, window: RateWindow, context, discrete_state) -> None:
        """Pushes this tick's samples into `window`, then calls `_after_push`."""
        state = discrete_state.get_mutable_value(window.state)
        samples, missing = window.layout.entering_samples(
            state, self._channels_port.Eval(context)[window.channels])
        pushed = window.layout.push(state, samples)
        self._after_push(window, state, pushed, missing, context, context.get_time())

    def _sample_block(self, window: RateWindow, context, discrete_state) -> None:
        """Pushes the block input's samples taken since the last update, oldest first."""
        state = discrete_state.get_mutable_value(window.state)
        period, now = 1.0 / window.group.rate_hz, context.get_time()
        taken = samples_in_block(now, period, window.block_samples)
        block = window.block.Eval(context).reshape(window.block_samples, -1)
        for k in range(window.block_samples - taken, window.block_samples):
            samples, missing = window.layout.entering_samples(state, block[k])
            pushed = window.layout.push(state, samples)
            self._after_push(window, state, pushed, missing, context,
                             now - (window.block_samples - 1 - k) * period)

    def _sample_batch(self, window: RateWindow, context, discrete_state) -> None:
        """Pushes the read batch's samples (read_batch.py), each at its own time."""
        state = discrete_state.get_mutable_value(window.state)
        rate, read_period = window.group.rate_hz, self._config.read_period_s
        period = 1.0 / rate
        first = batch_first_sample(context.get_time(), rate, read_period,
                                   window.block_samples)
        block = window.block.Eval(context).reshape(window.block_samples, -1)
        for k in range(window.block_samples):
            samples, missing = window.layout.entering_samples(state, block[k])
            pushed = window.layout.push(state, samples)
            self._after_push(window, state, pushed, missing, context, (first + k) * period)

    def _after_push(self, window: RateWindow, state: np.ndarray,
                    pushed: tuple[np.ndarray, int, bool], missing: list[bool] | None,
                    context, sample_time: float) -> None:
        """Subclass hook after each push: pushed is SlidingWindowState.push's (buffer,
        offset, full), missing entering_samples's, sample_time the sample's time [s]."""

    def _calc_window(self, window: RateWindow, rows: slice, context, output):
        raw = window.layout.current(context.get_discrete_state(window.state).value())
        output.SetFromVector(np.ravel(normalize_by_max(raw[rows])))


def ConnectWindowChannels(builder, normalizer: WindowNormalizer, channels) -> None:
    """Connects the four channels' port to a WindowNormalizer (or EventMatcher) in
    `builder`: its `channels` input and, for a rate in blocks or read batches, a register
    (`<name>_<group>_block` or `_batch`) to its `<group>_block` input."""
    builder.Connect(channels, normalizer.GetInputPort("channels"))
    for window in normalizer.rate_windows:
        if window.block_samples == 1:
            continue
        add, kind = ((AddHeldSampleRegister, "batch") if window.before_read
                     else (AddSampleRegister, "block"))
        builder.Connect(add(builder, channels, samples=window.block_samples,
                            sample_period_s=1.0 / window.group.rate_hz,
                            entries=window.group.channels,
                            name=f"{normalizer.get_name()}_{window.group.name}_{kind}"),
                        window.block)
