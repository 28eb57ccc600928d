"""The trial benchmark's parts: per-system costs from a profile, the plant-alone floor, the
trial-to-floor ratios and their report."""

import cProfile
import pstats

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from benchmarks.system_costs import eval_calls, system_costs
from tests.cheap_contact import CHEAP_CONTACT


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
@pytest.mark.parametrize("arm", ["jaco2", "carriage"])
def test_the_plant_alone_floor_replays_the_trial_to_the_same_object_pose(arm):
    from benchmarks.plant_floor import record_plant_inputs, run_plant_floor
    from tegrasp_drake.scenario.scenario import LoadScenario
    # The carriage in the cheap contact: the claim is that the floor replays this arm's
    # inputs step for step; the default contact's replay is the JACO2's case.
    contact = list(CHEAP_CONTACT) if arm == "carriage" else []
    scenario = LoadScenario(overrides=[f"station.arm={arm}", "random_seed=600", *contact])
    inputs = record_plant_inputs(scenario)
    assert inputs.arm_desired_state.shape == (12, inputs.times.size)
    run = run_plant_floor(scenario, inputs)
    assert run.sim_time_s == pytest.approx(inputs.times[-1])
    assert run.object_deviation_m < 1e-9  # the same contacts, step for step


def test_trial_to_floor_ratios_are_per_repeat_and_the_report_shows_them(monkeypatch):
    # Fake runs of known times (no simulation): the comparison must give each variant its
    # medians, and each controller the median over repeats of its CPU (wall) time per
    # simulated second over the floor's in the same repeat. The trials take 12 s of
    # simulated time, the floor 10 s.
    from benchmarks import trial as benchmark
    from benchmarks.trial import format_report
    from benchmarks.plant_floor import FloorRun
    from tegrasp_drake.scenario.scenario import LoadScenario
    trial_cpu = {"memorized": iter([24.0, 36.0, 30.0]), "open_loop": iter([12.0, 12.0, 18.0])}
    floor_cpu = iter([5.0, 10.0, 6.0])
    monkeypatch.setattr(benchmark, "record_plant_inputs", lambda scenario: None)
    monkeypatch.setattr(benchmark, "time_trial", lambda scenario: benchmark._factors(
        12.0, 2.0 * (cpu := next(trial_cpu[scenario.controller.name])), cpu))
    monkeypatch.setattr(benchmark, "run_plant_floor", lambda scenario, inputs: FloorRun(
        10.0, 2.0 * (cpu := next(floor_cpu)), cpu, 1e-12))
    result = benchmark.compare_trials_with_floor(LoadScenario(), repeats=3,
                                                 controllers=("memorized", "open_loop"))
    # Per repeat, cost over floor = (trial cpu / 12) / (floor cpu / 10):
    # memorized 4.0, 3.0, 4.1667 -> median 4.0; open_loop 2.0, 1.0, 2.5 -> median 2.0.
    assert result["memorized"]["cost_over_floor_cpu"] == pytest.approx(4.0, rel=1e-12)
    assert result["open_loop"]["cost_over_floor_cpu"] == pytest.approx(2.0, rel=1e-12)
    for name in ("memorized", "open_loop"):  # wall = 2 cpu in every run: the same ratio
        assert result[name]["cost_over_floor_wall"] == pytest.approx(
            result[name]["cost_over_floor_cpu"], rel=1e-12)
    assert result["memorized"]["cpu_time_s"] == 30.0  # median of 24, 36, 30
    assert result["memorized"]["rtf_cpu"] == pytest.approx(12.0 / 30.0, rel=1e-12)
    assert result["plant_alone"]["rtf_wall"] == pytest.approx(10.0 / 12.0, rel=1e-12)
    assert result["plant_alone"]["object_deviation_from_trial_m"] == 1e-12
    report = format_report({"object": "box", "repeats": 3, "trials": result})
    # Rows: variant, rtf wall, rtf cpu, cost/floor cpu, cost/floor wall (printed rounded).
    rows = {line.split()[0]: [float(x) for x in line.split()[1:]]
            for line in report.splitlines()[2:5]}
    assert rows.keys() == {"memorized", "open_loop", "plant_alone"}
    np.testing.assert_allclose(rows["memorized"], [0.2, 0.4, 4.0, 4.0], atol=0.01)
    np.testing.assert_allclose(rows["open_loop"], [0.5, 1.0, 2.0, 2.0], atol=0.01)
    np.testing.assert_allclose(rows["plant_alone"], [10 / 12, 10 / 6], atol=0.01)
def test_the_station_benchmark_splits_a_timeline_into_phase_spans():
    from benchmarks.station_costs import _phase_sim, _phase_spans
    timeline = [(0.0, "reach"), (3.6, "close"), (3.9, "lift"), (5.4, "hold")]
    assert _phase_spans(timeline, 5.0) == [("reach", 0.0, 3.6), ("close", 3.6, 3.9),
                                           ("lift", 3.9, 5.0)]
    sim = _phase_sim(timeline, 6.0)
    assert sim["reach"] == pytest.approx(3.6) and sim["hold"] == pytest.approx(0.6)
    assert sim["place"] == 0.0


def test_the_station_benchmark_counts_a_touching_reach_as_closing():
    from tegrasp_drake.control.grasp_modes import Mode
    from benchmarks.station_costs import _phase
    assert _phase(Mode.REACH, touched=False) == "reach"
    assert _phase(Mode.REACH, touched=True) == "close"
    assert _phase(Mode.LOAD, touched=True) == "close"
    assert _phase(Mode.AVOID, touched=True) == "hold"
