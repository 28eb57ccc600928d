"""The driver benchmark runs and measures something."""

import numpy as np
import pytest

from benchmarks.drivers import TICK_PERIOD, Percentiles, run_driver_benchmark, synthetic_trial


def test_percentiles_of_known_values():
    stats = Percentiles.of(np.arange(1, 101) * 1e-6)
    assert (stats.median, stats.p99, stats.max, stats.count) == pytest.approx(
        (50.5, 99.01, 100.0, 100))  # numpy's linear interpolation: 99 + 0.01


def test_short_benchmark_measures_latency_and_periods(capsys):
    # What it measures depends on how busy the host is (that is what it is for): only that
    # it measured, and relations its figures obey whatever the load, are asserted, never a
    # figure a loaded CPU could miss.
    duration = 0.3
    result = run_driver_benchmark(duration)
    assert 0 < result.frames_seen_at_port <= result.frames_sent
    # Every frame of the trial was sent (after the emulator's lead-in frames).
    assert result.frames_sent >= len(synthetic_trial(duration).force_times)
    assert result.tactile_latency.count == result.frames_seen_at_port
    assert 0 < result.tactile_latency.median
    for stats in (result.tactile_latency, result.loop_period_bare,
                  result.loop_period_with_tactile):
        assert stats.median <= stats.p99 <= stats.max  # order statistics
    # One tick per simulated millisecond, whatever the pacing: the periods between them,
    # less the first ten skipped as start-up (the last tick may fall either side of the end).
    assert abs(result.loop_period_bare.count - (duration / TICK_PERIOD - 10)) <= 1
    assert "tactile frame write -> receiver output port" in capsys.readouterr().out
