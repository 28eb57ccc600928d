"""The trial benchmark's parts: per-system costs from a profile, the plant-alone floor."""

import cProfile
import pstats

import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from benchmarks.system_costs import eval_calls, system_costs


class _Counter(LeafSystem):
    """Counts its 10 Hz updates; its output reads the count (Evals the input)."""

    def __init__(self):
        super().__init__()
        self._input = self.DeclareVectorInputPort("u", 1)
        self._state = self.DeclareDiscreteState(1)
        self.DeclarePeriodicDiscreteUpdateEvent(0.1, 0.0, self._update)
        self.DeclareVectorOutputPort("count", 1, self._calc)

    def _update(self, context, state):
        state.get_mutable_vector(self._state).SetAtIndex(
            0, context.get_discrete_state(self._state).GetAtIndex(0) + 1.0)

    def _calc(self, context, output):
        output.SetAtIndex(0, self._input.Eval(context)[0]
                          + context.get_discrete_state(self._state).GetAtIndex(0))


def test_system_costs_count_the_calls_cpp_made_and_the_evals():
    builder = DiagramBuilder()
    counter = builder.AddSystem(_Counter())
    builder.ExportInput(counter.get_input_port())
    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    diagram.get_input_port().FixValue(context, [2.0])
    counter_context = counter.GetMyContextFromRoot(context)
    profiler = cProfile.Profile()
    profiler.enable()
    simulator.AdvanceTo(0.95)
    counter.get_output_port().Eval(counter_context)
    profiler.disable()
    stats = pstats.Stats(profiler)
    cost = system_costs(stats, [_Counter])["_Counter"]
    assert cost["calls"] == 10 + 1  # updates at 0, 0.1, ..., 0.9 and one output calculation
    assert cost["eval_calls"] == 1
    assert cost["own_s"] > 0.0 and cost["us_per_call"] > 0.0
    assert eval_calls(stats) == 1  # the calculation's input Eval


@pytest.mark.slow
def test_the_plant_alone_floor_replays_the_trial_to_the_same_object_pose():
    from benchmarks.plant_floor import (record_plant_inputs, run_plant_floor)
    from tegrasp_drake.scenario.scenario import LoadScenario
    scenario = LoadScenario()
    inputs = record_plant_inputs(scenario)
    assert inputs.arm_desired_state.shape == (12, inputs.times.size)
    run = run_plant_floor(scenario, inputs)
    assert run.sim_time_s == pytest.approx(inputs.times[-1])
    assert run.object_deviation_m < 1e-9  # the same contacts, step for step
