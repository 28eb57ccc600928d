"""The lockstep benchmark's parts: advancing several simulations in turn, its per-repeat
ratios and its report (no timing is asserted)."""

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, Sine

from benchmarks import lockstep
from benchmarks.lockstep import advance_in_lockstep, format_report


def _logged_sine():
    """(Simulator, logger) of a sine logged every 10 ms."""
    builder = DiagramBuilder()
    sine = builder.AddSystem(Sine(1.0, 1.0, 0.0, 1))
    logger = LogVectorOutput(sine.get_output_port(0), builder, 0.01)
    return Simulator(builder.Build()), logger


def test_every_simulation_reaches_the_end_and_is_timed_apart():
    simulators, loggers = zip(*(_logged_sine() for _ in range(2)))
    cpu = advance_in_lockstep(dict(zip(("a", "b"), simulators)), 0.123, stride_s=0.05)
    assert set(cpu) == {"a", "b"}
    assert all(seconds >= 0.0 for seconds in cpu.values())
    for simulator, logger in zip(simulators, loggers):
        assert simulator.get_context().get_time() == pytest.approx(0.123)
        log = logger.FindLog(simulator.get_context())
        np.testing.assert_allclose(log.sample_times()[-1], 0.12)  # the last 10 ms sample


def test_ratios_are_per_repeat_medians_and_the_report_shows_them(monkeypatch):
    # Fake lockstep runs of known CPU seconds (no simulation); 10 s simulated.
    runs = iter([{"floor": 4.0, "before": 10.0, "after": 8.0},
                 {"floor": 5.0, "before": 10.0, "after": 10.0},
                 {"floor": 4.0, "before": 12.0, "after": 6.0}])
    monkeypatch.setattr(lockstep, "record_plant_inputs",
                        lambda scenario: type("Inputs", (), {"times": np.array([0.0, 10.0])}))
    monkeypatch.setattr(lockstep, "build_plant_floor", lambda scenario, inputs: (None, None))
    monkeypatch.setattr(lockstep, "_trial_simulator", lambda scenario: None)
    monkeypatch.setattr(lockstep, "advance_in_lockstep", lambda simulators, end: next(runs))
    from tegrasp_drake.scenario.scenario import LoadScenario
    scenario = LoadScenario(overrides=["random_seed=600"])
    result = lockstep.compare_in_lockstep(scenario, scenario, repeats=3)
    assert result["cpu_per_sim_s"] == {"floor": 0.4, "before": 1.0, "after": 0.8}
    assert result["ratios"]["before_over_floor"] == pytest.approx(2.5)  # of 2.5, 2, 3
    assert result["ratios"]["after_over_floor"] == pytest.approx(2.0)  # of 2, 2, 1.5
    assert result["ratios"]["before_over_after"] == pytest.approx(1.25)  # of 1.25, 1, 2
    result["variant"] = ["vibration.pad_force_source=joint_forces"]
    result["python_systems"] = {"before": {"PadFilms": {"calls": 10, "own_ms_per_sim_s": 35.0}},
                                "after": {}}
    report = format_report(result)
    assert "before / after (CPU, per repeat, median): 1.250" in report
    assert "vibration.pad_force_source=joint_forces" in report
    assert "PadFilms" in report and "35 (10)" in report
