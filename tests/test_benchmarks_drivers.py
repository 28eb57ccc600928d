"""The driver benchmark runs and measures something."""

import numpy as np
import pytest

from benchmarks.drivers import Percentiles, run_driver_benchmark


def test_percentiles_of_known_values():
    stats = Percentiles.of(np.arange(1, 101) * 1e-6)
    assert (stats.median, stats.max, stats.count) == pytest.approx((50.5, 100.0, 100))


def test_short_benchmark_measures_latency_and_periods(capsys):
    # What it measures depends on how busy the host is (that is what it is for): only that
    # it measured is asserted, never a figure a loaded CPU could miss.
    result = run_driver_benchmark(0.3)
    assert 0 < result.frames_seen_at_port <= result.frames_sent
    assert result.tactile_latency.count == result.frames_seen_at_port
    assert 0 < result.tactile_latency.median
    assert 0 < result.loop_period_bare.median and result.loop_period_bare.count > 0
    assert 0 < result.loop_period_with_tactile.median
    assert "tactile frame write -> receiver output port" in capsys.readouterr().out
