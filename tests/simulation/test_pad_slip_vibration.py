"""The slip texture's pure functions."""

import numpy as np

from tegrasp_drake.simulation.pad_slip_vibration import cross_product


def test_cross_product_is_numpys_bit_for_bit():
    # The films' inputs must not change when the fast form replaces np.cross.
    rng = np.random.default_rng(3)
    for _ in range(2000):
        a = rng.normal(size=3) * 10.0 ** rng.uniform(-6, 3)
        b = rng.normal(size=3) * 10.0 ** rng.uniform(-6, 3)
        assert np.array_equal(cross_product(a, b), np.cross(a, b))
