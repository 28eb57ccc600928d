"""The matcher benchmark runs and reports every figure (its values are machine dependent),
each one the wall time of a measured stretch divided by the ticks or calls in it."""

import math

import pytest

from benchmarks import matcher
from benchmarks.matcher import run_matcher_benchmark

FIGURES = {"core_tick_sa100_us", "reference_tick_sa100_us", "system_tick_sa100_us",
           "system_blocks_tick_sa100_us", "core_tick_sa1k_us", "reference_tick_sa1k_us",
           "system_tick_sa1k_us", "system_blocks_tick_sa1k_us",
           "fft_rebuild_ra_us", "framework_tick_us", "window_normalizer_tick_us"}


def test_benchmark_reports_positive_tick_costs():
    results = run_matcher_benchmark(repeats=1, ticks=20)
    assert set(results) == FIGURES
    assert all(math.isfinite(value) and value > 0.0 for value in results.values())


class _SteppingClock:
    """A perf_counter for measurements that read it twice (start, end): the stretches
    between the two readings last 10, 20 and 60 ms in turn, so that any three repeats of a
    measurement have a median of 20 ms (their mean or maximum would differ)."""

    STRETCHES_S = (0.01, 0.02, 0.06)

    def __init__(self):
        self._now, self._readings = 0.0, 0

    def perf_counter(self) -> float:
        self._readings += 1
        if self._readings % 2:  # a start: the time between measurements does not count
            self._now += 1.0
        else:
            self._now += self.STRETCHES_S[(self._readings // 2 - 1) % 3]
        return self._now


def test_each_figure_is_the_median_stretch_over_the_ticks_or_calls_in_it(monkeypatch):
    # The median stretch, 20 ms: a tick figure over 20 ticks is 1000 us; the reference
    # scoring and the FFT rebuild time 50 calls per stretch: 400 us.
    monkeypatch.setattr(matcher, "time", _SteppingClock())
    results = run_matcher_benchmark(repeats=3, ticks=20)
    per_call = {"reference_tick_sa100_us", "reference_tick_sa1k_us", "fft_rebuild_ra_us"}
    for name in FIGURES:
        assert results[name] == pytest.approx(400.0 if name in per_call else 1000.0,
                                              rel=1e-9), name
