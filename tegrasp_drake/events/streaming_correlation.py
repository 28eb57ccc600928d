"""Exact streaming update of the Eq. 3 scores: O(lags) work per new sample.

C(n) = sum_k x[k+n] y[k] changes by two rank-one terms when the window slides one sample;
indexed by the buffer column where the template starts, both land on one contiguous slice
(two BLAS axpy calls per channel). All is recomputed by FFT when the expected event changes
or the buffer compacts (every `slack` samples), bounding round-off. A missing sample enters
as the channel's previous one and scores its channel 0 for N slides."""

import math
from collections.abc import Sequence

import numpy as np
from scipy.linalg.blas import daxpy

from tegrasp_drake.events.correlation import channel_score, template_is_flat
from tegrasp_drake.events.transitions import NO_EVENT
from tegrasp_drake.tactile.sliding_window import SlidingWindow, SlidingWindowState

_STATISTICS = 3  # high, low, energy


def slide_statistics(statistics: list[float], dropped_and_new: list[list[float]],
                     window: np.ndarray) -> list[float]:
    """[high, low, energy] per channel after one sample per channel left and one entered
    (dropped_and_new), from `statistics`; `window` (new included) is read only when an extreme
    left or round-off ate the energy."""
    updated = []
    for channel, (dropped, new) in enumerate(dropped_and_new):
        high, low, energy = statistics[_STATISTICS * channel:_STATISTICS * (channel + 1)]
        if new >= high:
            high = new
        elif dropped == high:
            high = float(window[channel].max())
        if new <= low:
            low = new
        elif dropped == low:
            low = float(window[channel].min())
        if high == 0.0 and low == 0.0:
            energy = 0.0
        else:
            energy += new * new - dropped * dropped
            if not energy > 0.0:  # round-off ate a tiny energy: recompute it
                energy = float(np.dot(window[channel], window[channel]))
        updated += [high, low, energy]
    return updated


def window_statistics(window: np.ndarray) -> list[float]:
    """[high, low, energy] per channel of `window` (channels, N), flattened by channel."""
    columns = zip(window.max(axis=1).tolist(), window.min(axis=1).tolist(),
                  np.einsum("ij,ij->i", window, window).tolist())
    return [value for channel in columns for value in channel]


def _as_templates(templates: Sequence[np.ndarray]) -> list[np.ndarray]:
    """The templates as (channels, N) float arrays, all of one shape."""
    templates = [np.atleast_2d(np.asarray(y, dtype=float)) for y in templates]
    if not templates:
        raise ValueError("at least one event template is needed")
    if any(y.shape != templates[0].shape for y in templates):
        raise ValueError("all templates must have the same (channels, samples) shape")
    return templates


class SlidingCorrelation:
    """Gated Eq. 3 scores of a sliding window of channels sharing one rate, against one event
    chosen per slide. State, after the window's: [active_event, scores, [high, low, energy]
    per channel, missing slides (sum, per channel), rows: channels x (2N - 1 + slack)];
    column j holds lag j - offset - (N - 1).

    Args:
        templates: one (channels, N) array per event, at the live sample rate.
        min_contrast: live contrast a channel needs for its score to count (correlation.py).
        window: the sliding window's layout (its channels and N must be the templates').
        flat_needs_flat: a flat template channel needs a flat live window (correlation.py)."""

    def __init__(self, templates: Sequence[np.ndarray], *, min_contrast: float,
                 window: SlidingWindow, flat_needs_flat: bool = False):
        templates = _as_templates(templates)
        n_channels, length = templates[0].shape
        if (window.n_channels, window.length) != (n_channels, length):
            raise ValueError(f"templates of {n_channels} x {length} samples do not fit "
                             f"{window}")
        self._n_channels = n_channels
        self._length = length
        self._fft_length = 1 << (2 * length - 2).bit_length()  # power of two >= 2N - 1
        self._spectra = [np.conj(np.fft.rfft(y, self._fft_length)) for y in templates]
        self._min_contrast = min_contrast
        self._flat_needs_flat = flat_needs_flat
        self._event_at = SlidingWindowState(window).size  # the window comes first
        self._scores_at = self._event_at + 1
        self._statistics_at = self._scores_at + n_channels
        self._missing_at = self._statistics_at + _STATISTICS * n_channels
        self._rows_at = self._missing_at + 1 + n_channels
        self._row_length = 2 * length - 1 + window.slack
        self._size = self._rows_at + n_channels * self._row_length
        # Per event and channel: its buffer's start, the template reversed (the contiguous axpy
        # operand), its norm, whether it is flat.
        correlation_starts = [self._rows_at + channel * self._row_length
                              for channel in range(n_channels)]
        self._channel_terms = [
            list(zip(correlation_starts, [np.ascontiguousarray(row[::-1]) for row in y],
                     np.sqrt(np.einsum("ij,ij->i", y, y)).tolist(),
                     template_is_flat(y, min_contrast).tolist()))
            for y in templates]

    @property
    def n_events(self) -> int:
        return len(self._channel_terms)

    @property
    def size(self) -> int:
        """Length of the flat state vector, window included."""
        return self._size

    def initial_state(self) -> np.ndarray:
        """An all-zero window, no active event, scores 0."""
        state = np.zeros(self._size)
        state[self._event_at] = NO_EVENT
        return state

    def active_event(self, state: np.ndarray) -> int:
        """The event the scores in `state` refer to (NO_EVENT for none)."""
        return int(state[self._event_at])

    def scores(self, state: np.ndarray) -> np.ndarray:
        """View of the channels' scores held in `state`."""
        return state[self._scores_at:self._statistics_at]

    def check_event(self, event: int) -> None:
        """Raises ValueError unless `event` is NO_EVENT or an event index."""
        if not NO_EVENT <= event < len(self._channel_terms):
            raise ValueError(
                f"event index {event} is outside -1..{len(self._channel_terms) - 1}")

    def slide(self, state: np.ndarray, rows: np.ndarray, offset: int, full: bool,
              event: int, missing: list[bool] | None = None) -> np.ndarray:
        """Slides the correlations by the window's new samples and scores the window against
        `event` (index or NO_EVENT), in place. state: C-contiguous float64 (BLAS writes into it);
        rows, offset, full: the window after SlidingWindowState.push; missing: per channel (it then
        scores 0 for N slides). Returns the scores view, 0 until the window is full."""
        length = self._length
        left = None  # slides left per channel, read only while a missing sample is around
        if missing is not None or state.item(self._missing_at):
            missing = missing or [False] * self._n_channels
            left = [float(length) if is_missing else max(n - 1.0, 0.0) for n, is_missing
                    in zip(state[self._missing_at + 1:self._rows_at].tolist(), missing)]
            state[self._missing_at:self._rows_at] = [sum(left)] + left
        if event == NO_EVENT or not full:
            state[self._event_at:self._statistics_at] = [NO_EVENT] + [0.0] * self._n_channels
            return state[self._scores_at:self._statistics_at]
        window = rows[:, offset:offset + length]
        terms = self._channel_terms[event]
        if offset == 0 or event != state.item(self._event_at):
            self._recompute(state, window, offset, event)
            statistics = window_statistics(window)
        else:
            # The dropped sample (the column before the window) and the new one, N columns
            # later, add their products to the 2N correlation columns that end at lag N - 1.
            dropped_and_new = rows[:, offset - 1:offset + length:length].tolist()
            for (start, reversed_template, _, _), (dropped, new) in zip(terms,
                                                                         dropped_and_new):
                at = start + offset - 1
                if daxpy(reversed_template, state, length, -dropped, 0, 1, at, 1) is not state:
                    raise ValueError("the state must be a C-contiguous float64 vector")
                daxpy(reversed_template, state, length, new, 0, 1, at + length, 1)
            statistics = slide_statistics(
                state[self._statistics_at:self._missing_at].tolist(), dropped_and_new, window)
        scores = []
        for i, (start, _, template_norm, template_flat) in enumerate(terms):
            if left and left[i]:  # a missing sample is in this channel's window
                scores.append(0.0)
                continue
            lags = state[start + offset:start + offset + 2 * length - 1]
            high, low, energy = statistics[_STATISTICS * i:_STATISTICS * (i + 1)]
            # argmax is several times cheaper than max here, and finds the same peak.
            scores.append(channel_score(lags.item(lags.argmax()), energy, template_norm,
                                        high, low, template_flat, self._min_contrast,
                                        self._flat_needs_flat))
        state[self._event_at:self._missing_at] = [event] + scores + statistics
        return state[self._scores_at:self._statistics_at]

    def gate_below(self, state: np.ndarray, floors: list[float | None], *,
                   gate_events: bool = True) -> np.ndarray:
        """Scores, after `slide` and in place, each channel with a finite floor whose window peak is
        not above it as noise: 1 for a flat template, else 0. Returns the scores view."""
        event = int(state[self._event_at])
        if event != NO_EVENT:
            statistics = state[self._statistics_at:self._missing_at].tolist()
            for i, (floor, terms) in enumerate(zip(floors, self._channel_terms[event])):
                if floor is None:
                    continue
                high, low = statistics[_STATISTICS * i:_STATISTICS * i + 2]
                quiet = max(abs(high), abs(low)) <= floor
                if terms[3]:
                    if quiet and floor < math.inf:
                        state[self._scores_at + i] = 1.0
                elif gate_events and quiet:
                    state[self._scores_at + i] = 0.0
        return state[self._scores_at:self._statistics_at]

    def _recompute(self, state: np.ndarray, window: np.ndarray, offset: int,
                   event: int) -> None:
        """Exact cross-correlation of window and event templates by FFT; later lags zeroed."""
        length = self._length
        rows = state[self._rows_at:self._size].reshape(self._n_channels, self._row_length)
        circular = np.fft.irfft(np.fft.rfft(window, self._fft_length) * self._spectra[event],
                                self._fft_length)
        rows[:] = 0.0
        rows[:, offset:offset + length - 1] = circular[:, self._fft_length - length + 1:]
        rows[:, offset + length - 1:offset + 2 * length - 1] = circular[:, :length]


class StreamingCorrelator:
    """A sliding window and its SlidingCorrelation in one flat vector, outside a Diagram (tests,
    benchmarks): push a sample, get the scores. slack: samples between exact recomputations."""

    def __init__(self, templates: Sequence[np.ndarray], *, min_contrast: float, slack: int,
                 flat_needs_flat: bool = False):
        templates = _as_templates(templates)
        self._window = SlidingWindowState(SlidingWindow(*templates[0].shape, slack))
        self._correlation = SlidingCorrelation(templates, min_contrast=min_contrast,
                                               window=self._window.window,
                                               flat_needs_flat=flat_needs_flat)

    @property
    def n_events(self) -> int:
        return self._correlation.n_events

    @property
    def size(self) -> int:
        return self._correlation.size

    def initial_state(self) -> np.ndarray:
        return self._correlation.initial_state()

    def active_event(self, state: np.ndarray) -> int:
        return self._correlation.active_event(state)

    def scores(self, state: np.ndarray) -> np.ndarray:
        return self._correlation.scores(state)

    def window(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N) of the live window, oldest first, not normalised."""
        return self._window.current(state)

    def push(self, state: np.ndarray, samples, event: int) -> np.ndarray:
        """Appends one sample per channel and scores the window against `event` (or NO_EVENT),
        in place in `state` (C-contiguous float64); returns the scores view, 0 until full."""
        self._correlation.check_event(event)
        samples, missing = self._window.entering_samples(
            state, np.asarray(samples, dtype=float))
        rows, offset, full = self._window.push(state, samples)
        return self._correlation.slide(state, rows, offset, full, event, missing)
