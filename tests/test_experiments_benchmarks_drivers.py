"""The driver benchmark runs and measures something."""

import numpy as np
import pytest

from tegrasp_drake.experiments.benchmarks.drivers import Percentiles, run_driver_benchmark


def test_percentiles_of_known_values():
    stats = Percentiles.of(np.arange(1, 101) * 1e-6)
    assert (stats.median, stats.max, stats.count) == pytest.approx((50.5, 100.0, 100))


def test_short_benchmark_measures_latency_and_periods(capsys):
    result = run_driver_benchmark(0.3)
    assert result.frames_seen_at_port > 100
    # Figures, not targets: a busy host stretches and bunches the real-time loop's periods
    # (a catching-up simulator takes several short steps), so only their presence is checked.
    assert 0 < result.tactile_latency.median < 10e6  # [us]
    assert result.loop_period_bare.median > 0
    assert result.loop_period_with_tactile.median > 0
    assert "tactile frame write -> receiver output port" in capsys.readouterr().out
