"""The paper's window normalisation (Sec. III-A): each channel divided by its maximum."""

import numpy as np

def normalize_by_max(window: np.ndarray) -> np.ndarray:
    """Each channel (time along the last axis) divided by its largest |value|; zeros stay zero."""
    window = np.asarray(window, dtype=float)
    peak = np.max(np.abs(window), axis=-1, keepdims=True)
    return np.divide(window, peak, out=np.zeros_like(window), where=peak > 0.0)
