"""The matcher benchmark runs and reports every figure (its values are machine dependent)."""

import math

from tegrasp_drake.experiments.benchmarks.matcher import run_matcher_benchmark


def test_benchmark_reports_positive_tick_costs():
    results = run_matcher_benchmark(repeats=1, ticks=20)
    assert set(results) == {
        "core_tick_sa100_us", "reference_tick_sa100_us", "system_tick_sa100_us",
        "system_blocks_tick_sa100_us", "core_tick_sa1k_us", "reference_tick_sa1k_us",
        "system_tick_sa1k_us", "system_blocks_tick_sa1k_us",
        "fft_rebuild_ra_us", "framework_tick_us", "window_normalizer_tick_us"}
    assert all(math.isfinite(value) and value > 0.0 for value in results.values())
