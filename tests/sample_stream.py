"""A fixed stream of samples played into a diagram, for tests that compare a system run per
sample with the same system run in blocks (tactile/sample_block.py)."""

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial


def AddSampleStream(builder, samples: np.ndarray, period_s: float):
    """A TrajectorySource that holds row k of `samples` (n x size) over [k T, (k + 1) T);
    returns its output port."""
    samples = np.asarray(samples, dtype=float)
    breaks = np.arange(len(samples) + 1) * period_s
    values = np.vstack([samples, samples[-1:]]).T
    source = builder.AddSystem(TrajectorySource(PiecewisePolynomial.ZeroOrderHold(breaks,
                                                                                 values)))
    return source.get_output_port()


def outputs_after_updates(diagram, ports, times_s, *, period_s: float) -> list[np.ndarray]:
    """For each time in times_s (on the sample grid), each of `ports` (output ports of
    diagram's subsystems) evaluated just after the updates at that time (half a sample
    later): an array (times x port size) per port."""
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    values = [[] for _ in ports]
    for t in times_s:
        simulator.AdvanceTo(t + 0.5 * period_s)
        for port, column in zip(ports, values):
            system_context = port.get_system().GetMyContextFromRoot(context)
            column.append(port.Eval(system_context).copy())
    return [np.array(column) for column in values]
