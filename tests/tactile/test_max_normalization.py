"""The paper's window normalisation: each channel divided by its largest |value|."""

import numpy as np

from tegrasp_drake.tactile.max_normalization import normalize_by_max


def test_each_channel_is_divided_by_its_own_peak_magnitude():
    window = np.array([[0.0, 2.0, 4.0, 1.0],
                       [-0.5, 0.25, 0.1, 0.0],   # noise pushed it below zero: sign kept
                       [0.0, 0.0, 0.0, 0.0]])    # all zero stays zero, no division by 0
    np.testing.assert_allclose(normalize_by_max(window),
                               [[0.0, 0.5, 1.0, 0.25], [-1.0, 0.5, 0.2, 0.0],
                                [0.0, 0.0, 0.0, 0.0]], rtol=1e-15, atol=0)


def test_normalisation_is_along_the_last_axis_of_any_stack_and_scale_free():
    rng = np.random.default_rng(600)
    windows = rng.normal(size=(3, 4, 50))
    normalized = normalize_by_max(windows)
    np.testing.assert_allclose(np.abs(normalized).max(axis=-1), 1.0, rtol=1e-15)
    np.testing.assert_allclose(normalize_by_max(7.5 * windows), normalized, rtol=1e-14)
