"""Fixed-input tests of the benchmarks' probe systems: LoopTick appends one wall-clock
reading per period, _InputReader copies its input into its state every millisecond."""

import numpy as np
from pydrake.systems.analysis import Simulator

from benchmarks.drivers import LoopTick
from benchmarks.matcher import _InputReader


def test_loop_tick_appends_one_increasing_reading_per_period():
    readings = []
    simulator = Simulator(LoopTick(readings, period=0.002))
    simulator.AdvanceTo(0.0101)  # publishes at 0, 2, 4, 6, 8 and 10 ms
    assert len(readings) == 6
    assert np.all(np.diff(readings) >= 0.0)  # perf_counter never runs backwards


def test_input_reader_holds_the_input_it_read_at_its_last_tick():
    reader = _InputReader()
    context = reader.CreateDefaultContext()
    reader.get_input_port().FixValue(context, [1.0, 2.0, 3.0, 4.0])
    simulator = Simulator(reader, context)
    simulator.AdvanceTo(0.0015)
    np.testing.assert_array_equal(context.get_discrete_state_vector().value(),
                                  [1.0, 2.0, 3.0, 4.0])
    reader.get_input_port().FixValue(context, [-1.0, 0.5, 0.0, 9.0])
    np.testing.assert_array_equal(context.get_discrete_state_vector().value(),
                                  [1.0, 2.0, 3.0, 4.0])  # not before the next tick
    simulator.AdvanceTo(0.0025)
    np.testing.assert_array_equal(context.get_discrete_state_vector().value(),
                                  [-1.0, 0.5, 0.0, 9.0])
