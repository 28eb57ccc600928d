"""The run-log reader's checks of TEGRASP_TACTILE messages, taken over columns at once, keep
exactly the messages a message-by-message check keeps."""

import numpy as np

from tegrasp_drake.runs.hardware_log_reader import (MAX_TIME_OUTLIER_S, TIME_NEIGHBOURS,
                                                    tactile_time_check)


def _kept_one_by_one(utime, wall_us, values_ok) -> np.ndarray:
    """The time check message by message: a message whose values are real is kept unless its
    time is before the last kept one's, or both its time and its time less its receive time
    lie more than MAX_TIME_OUTLIER_S from their neighbours' medians."""
    times = np.array([u * 1e-6 for u in utime])
    offsets = times - np.array([w * 1e-6 for w in wall_us])

    def outlier(values, k) -> bool:
        neighbours = values[max(0, k - TIME_NEIGHBOURS):k + TIME_NEIGHBOURS + 1]
        return abs(values[k] - np.median(neighbours)) > MAX_TIME_OUTLIER_S

    kept, last = np.zeros(len(times), bool), -np.inf
    for k in range(len(times)):
        if not values_ok[k]:
            continue
        if times[k] < last or (outlier(times, k) and outlier(offsets, k)):
            continue
        kept[k], last = True, times[k]
    return kept


def _stream(n: int, seed: int):
    """utime, wall_us [us] and values_ok of `n` 1 kHz messages with forged and stepped-back
    times, a silence that moves both clocks, and refused values."""
    rng = np.random.default_rng(seed)
    utime = np.arange(1, n + 1, dtype=np.int64) * 1000
    wall_us = utime + 1_700_000_000_000_000
    forged = rng.random(n) < 0.03
    utime[forged] += rng.choice([-3_000_000, -2_000, 5_000_000, 10**12], forged.sum())
    silence = n // 2
    utime[silence:] += 4_000_000
    wall_us[silence:] += 4_000_000
    values_ok = rng.random(n) > 0.05
    return utime, wall_us, values_ok


def test_the_time_check_keeps_what_a_message_by_message_check_keeps():
    for n, seed in [(0, 0), (1, 1), (4, 2), (10, 3), (11, 4), (12, 5), (3000, 6),
                    (70_000, 7)]:
        utime, wall_us, values_ok = _stream(n, seed)
        kept = tactile_time_check(utime, wall_us, values_ok)
        assert np.array_equal(kept, _kept_one_by_one(utime, wall_us, values_ok)), (n, seed)
        if n > 100:
            assert 0 < np.count_nonzero(values_ok & ~kept) < n // 10
