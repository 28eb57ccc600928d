"""The last N samples of a few channels in a Context's state vector, [offset, held,
buffer | ...]: the buffer has N + slack columns per channel and the window is the view
buffer[:, offset:offset + N], oldest first; a push writes a column, and every `slack`
pushes the newest N - 1 samples move back to the start."""

import dataclasses
import functools
import math

import numpy as np

# slack per window length: a compaction copies N - 1 samples, slack lengthens the state
SLACK_FRACTION = 0.2

_BUFFER_AT = 2  # a window's state: [offset, held | buffer]


@dataclasses.dataclass(frozen=True)
class SlidingWindow:
    """Layout of a sliding window of `length` samples per channel."""
    n_channels: int
    length: int  # N, samples per window
    slack: int  # pushes between two compactions (>= 1)

    def __post_init__(self):
        if self.n_channels < 1 or self.length < 2 or self.slack < 1:
            raise ValueError(f"invalid sliding window {self}")

    @functools.cached_property
    def columns(self) -> int:
        """Buffer columns per channel."""
        return self.length + self.slack



@dataclasses.dataclass(frozen=True)
class SlidingWindowState:
    """A SlidingWindow at the start of a flat state vector; `held` counts pushes up to N
    (until full the older part is zero); entries after `size` are the system's own."""
    window: SlidingWindow

    @functools.cached_property
    def size(self) -> int:
        """Entries of the vector that hold the window."""
        return _BUFFER_AT + self.window.n_channels * self.window.columns

    def rows(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N + slack) of the buffer in `state`."""
        return state[_BUFFER_AT:self.size].reshape(self.window.n_channels,
                                                   self.window.columns)

    def newest(self, state: np.ndarray) -> np.ndarray:
        """The window's newest sample of each channel (0 while the window is empty)."""
        return self.rows(state)[:, int(state.item(0)) + self.window.length - 1].copy()

    def entering_samples(self, state: np.ndarray, samples: np.ndarray
                         ) -> tuple[np.ndarray, list[bool] | None]:
        """(samples to push, missing): a non-finite sample is replaced by the channel's newest, so
        the window's sums stay finite; missing: a bool per channel, or None when all are finite."""
        if math.isfinite(sum(samples.tolist())):
            return samples, None
        missing = ~np.isfinite(samples)
        return np.where(missing, self.newest(state), samples), missing.tolist()

    def current(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N) of the window held in `state`, oldest sample first."""
        offset = int(state[0])
        return self.rows(state)[:, offset:offset + self.window.length]

    def push(self, state: np.ndarray, samples) -> tuple[np.ndarray, int, bool]:
        """Appends a sample per channel in place: (buffer view, offset (0 on compaction), full)."""
        length = self.window.length
        rows = self.rows(state)
        offset = int(state.item(0))
        if offset == self.window.slack:
            rows[:, :length - 1] = rows[:, offset + 1:offset + length]
            rows[:, length - 1] = samples
            offset = 0
        else:
            rows[:, offset + length] = samples
            offset += 1
        state[0] = offset
        held = state.item(1)
        if held < length:
            held += 1.0
            state[1] = held
        return rows, offset, held == length


def default_sliding_window(n_channels: int, length: int) -> SlidingWindow:
    """The layout the tactile event systems use: slack of SLACK_FRACTION of the window."""
    return SlidingWindow(n_channels, length, max(1, int(length * SLACK_FRACTION)))
