"""The paper's window normalisation (Sec. III-A): each channel divided by its maximum."""

import numpy as np

def normalize_by_max(window: np.ndarray) -> np.ndarray:
    """Divide each channel (time along the last axis) by its largest |value|.

    For the non-negative SA and RA signals this is the paper's "normalised by the maximum
    signal value in the window"; using |value| keeps the sign of a window that noise pushed
    below zero. An all-zero channel stays zero.
    """
    window = np.asarray(window, dtype=float)
    peak = np.max(np.abs(window), axis=-1, keepdims=True)
    return np.divide(window, peak, out=np.zeros_like(window), where=peak > 0.0)
