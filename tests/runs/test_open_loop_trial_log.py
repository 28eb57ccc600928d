"""An open-loop trial's log holds, in 'phase', the Modes its metadata names ('mode_names'),
each sample the mode of the timeline's last transition at or before it."""

import dataclasses

import numpy as np

from tegrasp_drake.control.controller_config import OpenLoopControllerConfig
from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario.trial_log_file import load_trial_log

# A short script: Settle and Reach (Reach) to 0.85 s, Load to 0.95 s, then Lift.
SHORT_SCRIPT = ["grasp.settle_s=0.05", "grasp.reach_s=0.8", "grasp.load_s=0.1",
                "grasp.lift_s=0.6"]


def test_an_open_loop_trial_logs_the_modes_of_its_timeline(tmp_path):
    scenario = dataclasses.replace(LoadScenario(overrides=SHORT_SCRIPT),
                                   controller=OpenLoopControllerConfig())
    log = run_trial(scenario, max_time=1.0).log
    assert log.meta["mode_names"] == [mode.label for mode in Mode]
    transitions = log.meta["transitions"]
    assert [(e["from"], e["to"]) for e in transitions] == [("Reach", "Load"), ("Load", "Lift")]
    expected = np.full(len(log.t_slow), float(Mode.REACH))
    for entry in transitions:
        expected[log.t_slow > entry["t"]] = float(Mode.from_label(entry["to"]))
    # a sample at a transition's time (to float rounding) may show either mode
    times = np.array([entry["t"] for entry in transitions])
    away = np.all(np.abs(log.t_slow[:, None] - times[None, :]) > 1e-9, axis=1)
    assert np.array_equal(log.phase[away], expected[away]), (log.phase, expected)
    assert np.array_equal(load_trial_log(log.save(tmp_path / "trial.npz")).phase, log.phase)


def test_an_open_loop_script_that_holds_no_time_passes_from_lift_to_place(tmp_path):
    """grasp.hold_s = 0 (within its range) is a Hold phase of no time: the script passes over
    it, so the timeline has no Hold and its log can be saved (one transition per time)."""
    overrides = SHORT_SCRIPT[:3] + ["grasp.lift_s=0.6", "grasp.hold_s=0", "grasp.place_s=0.6"]
    scenario = dataclasses.replace(LoadScenario(overrides=overrides),
                                   controller=OpenLoopControllerConfig())
    log = run_trial(scenario, max_time=1.7).log
    transitions = log.meta["transitions"]
    assert [(e["from"], e["to"]) for e in transitions] == [
        ("Reach", "Load"), ("Load", "Lift"), ("Lift", "Place")]
    assert transitions[-1]["t"] > transitions[-2]["t"]
    assert np.array_equal(load_trial_log(log.save(tmp_path / "trial.npz")).phase, log.phase)
