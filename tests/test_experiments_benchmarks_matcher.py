"""The matcher benchmark runs and reports every figure (its values are machine dependent),
each one the wall time of a measured stretch divided by the ticks or calls in it."""

import math

import pytest

from tegrasp_drake.experiments.benchmarks import matcher
from tegrasp_drake.experiments.benchmarks.matcher import run_matcher_benchmark

FIGURES = {"core_tick_sa100_us", "reference_tick_sa100_us", "system_tick_sa100_us",
           "core_tick_sa1k_us", "reference_tick_sa1k_us", "system_tick_sa1k_us",
           "fft_rebuild_ra_us", "framework_tick_us", "window_normalizer_tick_us"}


def test_benchmark_reports_positive_tick_costs():
    results = run_matcher_benchmark(repeats=1, ticks=20)
    assert set(results) == FIGURES
    assert all(math.isfinite(value) and value > 0.0 for value in results.values())


class _SteppingClock:
    """A perf_counter that advances by `step` [s] at every reading: each measured stretch
    (a reading before and one after) lasts exactly `step`."""

    def __init__(self, step: float):
        self._now, self._step = 0.0, step

    def perf_counter(self) -> float:
        self._now += self._step
        return self._now


def test_each_figure_is_its_stretch_divided_by_the_ticks_or_calls_in_it(monkeypatch):
    # Every stretch lasts 20 ms. A tick figure over 20 ticks is then 1000 us; the reference
    # scoring and the FFT rebuild time 50 calls per stretch: 400 us.
    monkeypatch.setattr(matcher, "time", _SteppingClock(0.02))
    results = run_matcher_benchmark(repeats=3, ticks=20)
    per_call = {"reference_tick_sa100_us", "reference_tick_sa1k_us", "fft_rebuild_ra_us"}
    for name in FIGURES:
        assert results[name] == pytest.approx(400.0 if name in per_call else 1000.0,
                                              rel=1e-9), name
