"""Exact streaming update of the Eq. 3 scores: O(lags) work per new sample.

For a live window x of N samples and a template y, the full cross-correlation
C(n) = sum_k x[k+n] y[k], n = -(N-1)..N-1, changes by two rank-one terms when the window
slides by one sample: the dropped sample's products leave and the new sample's enter.
Indexing C by the buffer column where the template starts (instead of by lag) makes both
terms land on one contiguous slice of 2N entries per channel: the dropped sample's N
products on its first half, the new one's on its second half; two in-place BLAS axpy calls
on the state vector per channel apply them (numpy's temporaries and broadcasting cost
several times the arithmetic at this size). The window's extremes are kept exactly (a new
extreme replaces the old; the window is searched again only when its extreme leaves it),
its energy by a running sum that is reset to exactly 0 when the window is all zero (so an
all-zero window scores 0, never NaN). Correlations, extremes and energies are recomputed
exactly (the correlations by FFT, with the templates' spectra cached) whenever the
expected event changes or the sliding buffer compacts, every `slack` samples; that bounds
the round-off of the running sums: the scores equal the reference's to about 1e-16 times
the signal's dynamic range over the last `slack` samples.

Until N samples have been pushed the window is not full (its older part is zero padding,
which would make a few noise samples look like an onset): the scores stay 0.

Missing samples: a NaN or infinite sample (a sensor glitch, a lost frame) is missing. It
enters the window as the channel's previous sample (so the running sums stay finite and
exact), and the channel's score is 0 until N samples have followed it, i.e. until it has
left the window: the channel recovers within one window and is never poisoned.

All history is in one flat float vector (a Context's discrete state):

    [active_event, offset, samples_pushed (saturating at N), scores (channels),
     [high, low, energy] per channel, clean samples in a row per channel (saturating at N),
     rows: channels x (window buffer (N + slack) | correlation buffer (2N - 1 + slack))]

Correlation column j of a row holds the lag n = j - (N + slack) - offset - (N - 1).
"""

from collections.abc import Sequence

import numpy as np
from scipy.linalg.blas import daxpy

from tegrasp_drake.events.correlation import channel_score, template_is_flat
from tegrasp_drake.events.transitions import NO_EVENT
from tegrasp_drake.tactile.sliding_window import SlidingWindow

_HEADER = 3  # active_event, offset, samples_pushed
_STATISTICS = 3  # high, low, energy


def slide_statistics(statistics: list[float], dropped_and_new: list[list[float]],
                     window: np.ndarray) -> list[float]:
    """[high, low, energy] per channel of `window` after one sample per channel left it
    and one entered, from their values before (statistics, flattened by channel).

    dropped_and_new: [[dropped, new], ...] per channel; window: (channels, N), new included.
    """
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


class StreamingCorrelator:
    """Gated Eq. 3 scores of channels sharing one rate, against one event chosen per push.

    Args:
        templates: one (channels, N) array per event, at the live sample rate.
        min_contrast: live contrast a channel needs for its score to count (correlation.py).
        slack: samples between two exact recomputations of the correlation buffer.
    """

    def __init__(self, templates: Sequence[np.ndarray], *, min_contrast: float, slack: int):
        templates = [np.atleast_2d(np.asarray(y, dtype=float)) for y in templates]
        if not templates:
            raise ValueError("at least one event template is needed")
        n_channels, length = templates[0].shape
        if any(y.shape != (n_channels, length) for y in templates):
            raise ValueError("all templates must have the same (channels, samples) shape")
        self._n_channels = n_channels
        self._length = length
        self._window = SlidingWindow(n_channels, length, slack)
        self._fft_length = 1 << (2 * length - 2).bit_length()  # power of two >= 2N - 1
        self._spectra = [np.conj(np.fft.rfft(y, self._fft_length)) for y in templates]
        self._min_contrast = min_contrast
        self._statistics_at = _HEADER + n_channels
        self._clean_at = self._statistics_at + _STATISTICS * n_channels
        self._rows_at = self._clean_at + n_channels
        self._correlation_at = self._window.columns  # first correlation column of a row
        self._row_length = self._window.columns + 2 * length - 1 + slack
        self._size = self._rows_at + n_channels * self._row_length
        # Per event and channel, what a push needs: where the channel's correlation buffer
        # starts in the state, its template reversed (contiguous: the axpy operand), the
        # template's norm and whether it is flat.
        correlation_starts = [self._rows_at + channel * self._row_length + self._correlation_at
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
        """Length of the flat state vector."""
        return self._size

    def initial_state(self) -> np.ndarray:
        """An all-zero window, no active event, scores 0; the zero padding counts as clean
        (a window is scored only once full anyway)."""
        state = np.zeros(self._size)
        state[0] = NO_EVENT
        state[self._clean_at:self._rows_at] = self._length
        return state

    def active_event(self, state: np.ndarray) -> int:
        """The event the scores in `state` refer to (NO_EVENT for none)."""
        return int(state[0])

    def scores(self, state: np.ndarray) -> np.ndarray:
        """View of the channels' scores held in `state`."""
        return state[_HEADER:self._statistics_at]

    def window(self, state: np.ndarray) -> np.ndarray:
        """View (channels, N) of the live window, oldest first, not normalised."""
        rows = state[self._rows_at:].reshape(self._n_channels, self._row_length)
        return self._window.window(rows, int(state[1]))

    def push(self, state: np.ndarray, samples, event: int) -> np.ndarray:
        """Append one sample per channel and score the window against `event`, in place.

        state: a C-contiguous float64 vector (the BLAS calls write into it directly).
        event: index of the expected event, or NO_EVENT (scores 0). Returns the scores view,
        all 0 until the window is full.
        """
        if not NO_EVENT <= event < len(self._channel_terms):
            raise ValueError(
                f"event index {event} is outside -1..{len(self._channel_terms) - 1}")
        length = self._length
        rows = state[self._rows_at:].reshape(self._n_channels, self._row_length)
        active, offset, pushed = state[:_HEADER].tolist()
        samples = np.asarray(samples, dtype=float)
        finite = np.isfinite(samples)
        clean = state[self._clean_at:self._rows_at]
        if not finite.all():
            # Missing: hold the channel's newest sample; score it 0 for one window.
            newest = self._window.window(rows, int(offset))[:, -1]
            samples = np.where(finite, samples, newest)
        clean[:] = np.where(finite, np.minimum(clean + 1.0, length), 0.0)
        offset = self._window.push(rows, int(offset), samples)
        if pushed < length:
            pushed += 1.0
        if event == NO_EVENT or pushed < length:
            state[:self._statistics_at] = [NO_EVENT, offset, pushed] + [0.0] * self._n_channels
            return state[_HEADER:self._statistics_at]
        window = rows[:, offset:offset + length]
        terms = self._channel_terms[event]
        if offset == 0 or event != active:
            self._recompute(rows, offset, event)
            statistics = window_statistics(window)
        else:
            # The dropped sample (column offset - 1) and the new one (N columns later) add
            # their products to the 2N correlation columns that end at lag N - 1.
            dropped_and_new = rows[:, offset - 1:offset + length:length].tolist()
            for (start, reversed_template, _, _), (dropped, new) in zip(terms,
                                                                         dropped_and_new):
                at = start + offset - 1
                if daxpy(reversed_template, state, length, -dropped, 0, 1, at, 1) is not state:
                    raise ValueError("the state must be a C-contiguous float64 vector")
                daxpy(reversed_template, state, length, new, 0, 1, at + length, 1)
            statistics = slide_statistics(
                state[self._statistics_at:self._clean_at].tolist(), dropped_and_new, window)
        scores = []
        complete = (clean >= length).tolist()
        for i, (start, _, template_norm, template_flat) in enumerate(terms):
            lags = state[start + offset:start + offset + 2 * length - 1]
            high, low, energy = statistics[_STATISTICS * i:_STATISTICS * (i + 1)]
            # argmax is several times cheaper than max here, and finds the same peak.
            scores.append(channel_score(lags.item(lags.argmax()), energy, template_norm,
                                        high, low, template_flat, self._min_contrast)
                          if complete[i] else 0.0)
        state[:self._clean_at] = [event, offset, pushed] + scores + statistics
        return state[_HEADER:self._statistics_at]

    def _recompute(self, rows: np.ndarray, offset: int, event: int) -> None:
        """Exact full cross-correlation of the window with the event's templates, by FFT.

        Columns after the valid lags are zeroed: later pushes start new lags there.
        """
        length = self._length
        window = rows[:, offset:offset + length]
        circular = np.fft.irfft(np.fft.rfft(window, self._fft_length) * self._spectra[event],
                                self._fft_length)
        lags_at = self._correlation_at + offset
        rows[:, self._correlation_at:] = 0.0
        rows[:, lags_at:lags_at + length - 1] = circular[:, self._fft_length - length + 1:]
        rows[:, lags_at + length - 1:lags_at + 2 * length - 1] = circular[:, :length]
