"""TactilePads' noise generator: the stream of np.random.default_rng((seed, stream, sample))."""

import numpy as np
import pytest

from tegrasp_drake.simulation.tactile_pads import _uint32_words, noise_generator

# Seeds and sample indices on both sides of numpy's 32-bit word boundaries.
SEEDS = (0, 600, 2**32 - 1, 2**32, 2**64 + 7)
SAMPLES = (0, 1, 1323, 2**32 + 1)


@pytest.mark.parametrize("seed", SEEDS)
def test_noise_generator_draws_default_rngs_stream(seed):
    for sample in SAMPLES:
        expected = np.random.default_rng((seed, 7001, sample)).normal(0.0, 0.005, 24)
        words = _uint32_words(seed) + _uint32_words(7001) + _uint32_words(sample)
        drawn = noise_generator(words).normal(0.0, 0.005, 24)
        assert drawn.tobytes() == expected.tobytes()


def test_words_are_least_significant_first():
    assert _uint32_words(0) == [0]
    assert _uint32_words(2**32 + 5) == [5, 1]


def test_a_negative_seed_is_refused():
    with pytest.raises(ValueError, match="non-negative"):
        _uint32_words(-1)
