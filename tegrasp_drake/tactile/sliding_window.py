"""The last N samples of a few channels, kept in a buffer inside a Context's state.

The buffer has N + slack columns per channel (row-major). The window is the contiguous
slice buffer[:, offset:offset + N], oldest sample first, so reading it copies nothing. A
push writes one column and advances the offset; when the offset reaches `slack`, the newest
N - 1 samples move back to the buffer's start (one copy every `slack` pushes instead of a
roll every push). A zero buffer with offset 0 is an all-zero window.

Beside the buffer, a short `position` vector holds the offset, the number of samples held
and the window's oldest samples (those the next push drops), so that a system following the
window push by push (the EventMatcher's scorer) reads a few numbers per tick, not the buffer.
"""

import dataclasses

import numpy as np

# Pushes between two compactions, as a fraction of the window length: each compaction
# copies N - 1 samples (and makes the matcher recompute its correlations), while each
# column of slack lengthens the state that Drake copies at every update.
SLACK_FRACTION = 0.2

_OLDEST = 2  # position: [offset, held, oldest sample of each channel]


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

    def next_offset(self, offset: int) -> int:
        """The offset after a push at `offset`: 0 exactly when the push compacts."""
        return 0 if offset == self.slack else offset + 1

    def push(self, buffer: np.ndarray, offset: int, samples) -> int:
        """Append one sample per channel to `buffer` in place; returns the new offset.

        buffer: (channels, >= N + slack) array; only its first N + slack columns are used.
        """
        if offset == self.slack:
            buffer[:, :self.length - 1] = buffer[:, offset + 1:offset + self.length]
            buffer[:, self.length - 1] = samples
        else:
            buffer[:, offset + self.length] = samples
        return self.next_offset(offset)


@dataclasses.dataclass(frozen=True)
class SlidingWindowState:
    """A SlidingWindow in flat vectors: a position and a buffer,

        position: [offset, held, oldest sample of each channel]
        buffer: channels x (N + slack), row-major

    either as two vectors (two state groups of a Context) or as one, [position | buffer].
    `held` counts the samples pushed, up to N: the window is full once it holds N. While it
    is not, its older part (and so its oldest sample) is zero.
    """
    window: SlidingWindow

    @property
    def position_size(self) -> int:
        return _OLDEST + self.window.n_channels

    @property
    def buffer_size(self) -> int:
        return self.window.n_channels * self.window.columns

    @property
    def size(self) -> int:
        """Length of the one-vector form, [position | buffer]."""
        return self.position_size + self.buffer_size

    def split(self, state: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Views (position, buffer) of the one-vector form."""
        return state[:self.position_size], state[self.position_size:]

    def unpack(self, position: np.ndarray) -> tuple[int, float, list[float]]:
        """(offset, held, oldest sample of each channel), as Python numbers."""
        offset, held, *oldest = position.tolist()
        return int(offset), held, oldest

    def window_in(self, position: np.ndarray, buffer: np.ndarray) -> np.ndarray:
        """View (channels, N) of the window, oldest sample first."""
        rows = buffer.reshape(self.window.n_channels, self.window.columns)
        return self.window.window(rows, int(position[0]))

    def newest_in(self, position: np.ndarray, buffer: np.ndarray) -> np.ndarray:
        """The window's newest sample of each channel (0 while the window is empty)."""
        return self.window_in(position, buffer)[:, -1].copy()

    def push_into(self, position: np.ndarray, buffer: np.ndarray, samples) -> None:
        """Append one sample per channel to the window, in place."""
        window = self.window
        offset, held, *_ = position.tolist()
        rows = buffer.reshape(window.n_channels, window.columns)
        offset = window.push(rows, int(offset), samples)
        position[:] = [offset, held + 1.0 if held < window.length else held] + rows[
            :, offset].tolist()

    def window_after(self, position: np.ndarray, buffer: np.ndarray, samples) -> np.ndarray:
        """The window (channels, N) once `samples` are pushed, computed on copies:
        position and buffer stay as they are."""
        position, buffer = position.copy(), buffer.copy()
        self.push_into(position, buffer, samples)
        return self.window_in(position, buffer)

    def current(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N) of the window held in the one-vector `state`."""
        return self.window_in(*self.split(state))

    def push(self, state: np.ndarray, samples) -> None:
        """Append one sample per channel to the window held in the one-vector `state`."""
        self.push_into(*self.split(state), samples)


def default_sliding_window(n_channels: int, length: int) -> SlidingWindow:
    """The layout the tactile event systems use: slack of SLACK_FRACTION of the window."""
    return SlidingWindow(n_channels, length, max(1, int(length * SLACK_FRACTION)))
