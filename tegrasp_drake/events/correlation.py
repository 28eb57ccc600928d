"""Eq. 3 of the paper: the maximum over lags n = -(N-1)..N-1 of the normalised
cross-correlation R_XY(n) / sqrt(R_XX(0) R_YY(0)), R_XY(n) = sum_k x[k+n] y[k], no mean
removed (as the paper); an all-zero window scores 0. A channel scores only when its window's
contrast reaches `min_contrast` (docs/controller.md, "The contrast gate"). The reference
here uses numpy.correlate; streaming_correlation.py the loop's update."""

import math

import numpy as np





def contrast(high: float, low: float) -> float:
    """(high - low) / max(|high|, |low|) of a window with extremes high, low; 0 if all zero."""
    peak = max(abs(high), abs(low))
    return (high - low) / peak if peak > 0.0 else 0.0


def window_contrast(window: np.ndarray) -> np.ndarray:
    """`contrast` of each channel of `window` (time along the last axis)."""
    window = np.atleast_2d(np.asarray(window, dtype=float))
    return np.array([contrast(high, low)
                     for high, low in zip(window.max(axis=-1), window.min(axis=-1))])


def template_is_flat(templates: np.ndarray, min_contrast: float) -> np.ndarray:
    """True for each template channel whose contrast is below `min_contrast`."""
    return window_contrast(templates) < min_contrast


def channel_score(peak_correlation: float, live_energy: float, template_norm: float,
                  live_high: float, live_low: float, template_flat: bool,
                  min_contrast: float, flat_needs_flat: bool = False) -> float:
    """A channel's gated score from its window statistics: peak_correlation (max over lags
    of R_XY), live_energy R_XX(0), template_norm sqrt(R_YY(0)), the live window's extremes;
    flat_needs_flat: a flat template scores only a flat window."""
    denominator = math.sqrt(live_energy) * template_norm
    if not denominator > 0.0:
        return 0.0
    live_flat = contrast(live_high, live_low) < min_contrast
    if not template_flat and live_flat:
        return 0.0
    if template_flat and flat_needs_flat and not live_flat:
        return 0.0
    return peak_correlation / denominator


def max_normalized_xcorr_reference(live: np.ndarray, template: np.ndarray) -> float:
    """Ungated Eq. 3 of two 1-D windows, from the definition; 0.0 if either is all zero."""
    live = np.asarray(live, dtype=float)
    template = np.asarray(template, dtype=float)
    denominator = math.sqrt(np.dot(live, live)) * math.sqrt(np.dot(template, template))
    if not denominator > 0.0:
        return 0.0
    return float(np.correlate(live, template, mode="full").max() / denominator)


def event_scores_reference(live, templates, min_contrast: float,
                           flat_needs_flat: bool = False) -> np.ndarray:
    """Gated Eq. 3 scores, one per channel in [-1, 1], of live windows against templates
    (sequences of 1-D windows; a channel's pair shares a sample rate)."""
    live = [np.asarray(x, dtype=float) for x in live]
    templates = [np.asarray(y, dtype=float) for y in templates]
    if len(live) != len(templates):
        raise ValueError(f"{len(live)} live windows but {len(templates)} templates")
    scores = []
    for x, y in zip(live, templates):
        scores.append(channel_score(
            peak_correlation=float(np.correlate(x, y, mode="full").max()),
            live_energy=float(np.dot(x, x)),
            template_norm=math.sqrt(np.dot(y, y)),
            live_high=float(x.max()), live_low=float(x.min()),
            template_flat=bool(contrast(y.max(), y.min()) < min_contrast),
            min_contrast=min_contrast, flat_needs_flat=flat_needs_flat))
    return np.array(scores)
