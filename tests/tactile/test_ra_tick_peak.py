"""Each film's peak |RA| over a controller tick (tactile/ra_tick_peak.py): a sample between
the controller's reads is seen at the next one, once."""

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource, VectorLogSink, ZeroOrderHold
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.tactile.ra_tick_peak import AddRaTickPeak, samples_per_tick


def test_samples_per_tick_at_the_film_and_controller_rates():
    assert samples_per_tick(1000.0, 0.005) == 5
    assert samples_per_tick(100.0, 0.005) == 1


def test_a_one_sample_ring_is_read_once_at_the_next_tick():
    """1 kHz samples, 5 ms ticks: a 9 m/s^2 sample at 8 ms and a -4 m/s^2 one at 13 ms,
    which a read of the latest sample at 5, 10, 15 ms never sees."""
    builder = DiagramBuilder()
    times = np.arange(0.0, 0.03, 0.001)
    values = np.zeros((2, len(times)))
    values[0, 7], values[1, 12] = 9.0, -4.0
    source = builder.AddSystem(TrajectorySource(PiecewisePolynomial.ZeroOrderHold(times,
                                                                                  values)))
    samples = builder.AddSystem(ZeroOrderHold(0.001, 2))
    builder.Connect(source.get_output_port(), samples.get_input_port())
    peak = AddRaTickPeak(builder, samples.get_output_port(), sample_rate_hz=1000.0,
                         tick_s=0.005)
    reads = builder.AddSystem(VectorLogSink(2, 0.005))
    latest = builder.AddSystem(VectorLogSink(2, 0.005))
    builder.Connect(peak, reads.get_input_port())
    builder.Connect(samples.get_output_port(), latest.get_input_port())
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(0.03)
    context = simulator.get_context()
    np.testing.assert_array_equal(reads.FindLog(context).data(),
                                  [[0, 0, 9, 0, 0, 0, 0], [0, 0, 0, 4, 0, 0, 0]])
    assert not latest.FindLog(context).data().any()
