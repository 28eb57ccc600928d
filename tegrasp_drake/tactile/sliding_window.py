"""The last N samples of a few channels, kept in a buffer inside a Context's state.

The buffer has N + slack columns per channel (row-major). The window is the contiguous
slice buffer[:, offset:offset + N], oldest sample first, so reading it copies nothing. A
push writes one column and advances the offset; when the offset reaches `slack`, the newest
N - 1 samples move back to the buffer's start (one copy every `slack` pushes instead of a
roll every push). A zero buffer with offset 0 is an all-zero window.

In a Context the window starts a state vector, [offset, held, buffer | ...], where `held`
counts the samples pushed up to N (SlidingWindowState).
"""

import dataclasses
import functools
import math

import numpy as np

# Pushes between two compactions, as a fraction of the window length: each compaction
# copies N - 1 samples (and makes the matcher recompute its correlations), while each
# column of slack lengthens the state that Drake copies at every update.
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
    """A SlidingWindow at the start of a flat vector (a Context's discrete state group),

        [offset, held, buffer: channels x (N + slack), row-major | anything else]

    `held` counts the samples pushed, up to N: the window is full once it holds N. While it
    is not, its older part is zero. The vector may go on after the window's `size` entries
    (with what a system keeps about the window, such as the EventMatcher's correlations).
    """
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
        """The samples a push of `samples` (one per channel) should take into the window
        held in `state`, and which of them are missing.

        A non-finite sample (NaN or inf: a sensor glitch, a lost frame) is missing: the
        channel's newest sample in the window enters in its place, so that the window and
        the sums kept over it stay finite. Returns (samples, missing: a bool per channel,
        or None when none is, the common case, checked at a fraction of isfinite's cost).
        """
        if math.isfinite(sum(samples.tolist())):
            return samples, None
        missing = ~np.isfinite(samples)
        return np.where(missing, self.newest(state), samples), missing.tolist()

    def current(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N) of the window held in `state`, oldest sample first."""
        offset = int(state[0])
        return self.rows(state)[:, offset:offset + self.window.length]

    def push(self, state: np.ndarray, samples) -> tuple[np.ndarray, int, bool]:
        """Append one sample per channel to the window held in `state`, in place (the
        module docstring says how).

        Returns, after the push, the buffer (a view, as `rows`), the window's offset in it
        (0 exactly when the push compacted) and whether the window is full.
        """
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
