"""Fixed-input tests of the benchmarks' probe systems: LoopTick appends one wall-clock
reading per period, _InputReader copies its input into its state every millisecond,
BarePythonOutput passes its first two inputs, PythonPadStatics gives the pad statics'."""

import numpy as np
from pydrake.systems.analysis import Simulator

from benchmarks.drivers import LoopTick
from benchmarks.matcher import _InputReader
from benchmarks.per_step_python import BarePythonOutput, PythonPadStatics, linkage_pad_statics


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


def test_bare_python_output_passes_its_first_two_inputs():
    system = BarePythonOutput(4)
    context = system.CreateDefaultContext()
    system.get_input_port().FixValue(context, [1.5, -2.0, 3.0, 4.0])
    np.testing.assert_array_equal(system.get_output_port().Eval(context), [1.5, -2.0])


def test_python_pad_statics_outputs_the_statics_forces_of_its_input():
    statics = linkage_pad_statics()
    system = PythonPadStatics(statics)
    context = system.CreateDefaultContext()
    values = np.linspace(-0.5, 0.7, statics.velocities + statics.states)
    system.get_input_port().FixValue(context, values)
    expected = statics.normal_forces(values[:statics.velocities].tolist(),
                                     values[statics.velocities:].tolist())
    assert np.all(np.abs(expected) > 0.0)
    np.testing.assert_array_equal(system.get_output_port().Eval(context), expected)
