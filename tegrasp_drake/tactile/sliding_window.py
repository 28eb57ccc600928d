"""The last N samples of a few channels, kept in a buffer inside a Context's state vector.

The buffer has N + slack columns per channel (row-major). The window is the contiguous
slice buffer[:, offset:offset + N], oldest sample first, so reading it copies nothing. A
push writes one column and advances the offset; when the offset reaches `slack`, the newest
N - 1 samples move back to the buffer's start (one copy every `slack` pushes instead of a
roll every push). A zero buffer with offset 0 is an all-zero window.
"""

import dataclasses

import numpy as np

# Pushes between two compactions, as a fraction of the window length: each compaction
# copies N - 1 samples (and makes the matcher recompute its correlations), while each
# column of slack lengthens the state that Drake copies at every update.
SLACK_FRACTION = 0.2


@dataclasses.dataclass(frozen=True)
class SlidingWindow:
    """Layout and operations of a sliding window of `length` samples per channel."""
    n_channels: int
    length: int  # N, samples per window
    slack: int  # pushes between two compactions (>= 1)

    def __post_init__(self):
        if self.n_channels < 1 or self.length < 2 or self.slack < 1:
            raise ValueError(f"invalid sliding window {self}")

    @property
    def columns(self) -> int:
        """Buffer columns per channel."""
        return self.length + self.slack

    def window(self, buffer: np.ndarray, offset: int) -> np.ndarray:
        """View (channels, N) of the window, oldest sample first."""
        return buffer[:, offset:offset + self.length]

    def push(self, buffer: np.ndarray, offset: int, samples) -> int:
        """Append one sample per channel to `buffer` in place; returns the new offset.

        buffer: (channels, >= N + slack) array; only its first N + slack columns are used.
        The new offset is 0 exactly when the buffer was compacted.
        """
        if offset == self.slack:
            buffer[:, :self.length - 1] = buffer[:, offset + 1:offset + self.length]
            buffer[:, self.length - 1] = samples
            return 0
        buffer[:, offset + self.length] = samples
        return offset + 1


@dataclasses.dataclass(frozen=True)
class SlidingWindowState:
    """A SlidingWindow in a flat state vector laid out as [offset, buffer (row-major)]."""
    window: SlidingWindow

    @property
    def size(self) -> int:
        return 1 + self.window.n_channels * self.window.columns

    def buffer(self, state: np.ndarray) -> np.ndarray:
        return state[1:].reshape(self.window.n_channels, self.window.columns)

    def current(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N) of the window held in `state`, oldest sample first."""
        return self.window.window(self.buffer(state), int(state[0]))

    def push(self, state: np.ndarray, samples) -> None:
        """Append one sample per channel to the window held in `state`, in place."""
        state[0] = self.window.push(self.buffer(state), int(state[0]), samples)


def default_sliding_window(n_channels: int, length: int) -> SlidingWindow:
    """The layout the tactile event systems use: slack of SLACK_FRACTION of the window."""
    return SlidingWindow(n_channels, length, max(1, int(length * SLACK_FRACTION)))
