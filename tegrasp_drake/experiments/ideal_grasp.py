"""The ideal open-loop grasp as a runnable trial: build, simulate, log (Sec. III-A).

The grasp diagram with the open-loop controller (the scripted grasp of
control/scripted_grasp.py), simulated to the end of the script and a little beyond.
"""

import time

from tegrasp_drake.control.scripted_grasp import PHASES, plan_duration
from tegrasp_drake.experiments.grasp_diagram import MakeGraspDiagram, MakeSimulator
from tegrasp_drake.experiments.trial_logging import collect_trial_log
from tegrasp_drake.simulation.station import MakeGraspStation

CONTROLLER_NAME = "open_loop"
END_MARGIN_S = 0.5  # simulated after the script ends, to see the object settle


def MakeIdealGraspDiagram(scenario, *, meshcat=None):
    """The GraspDiagram of the scripted grasp around the simulated station."""
    return MakeGraspDiagram(scenario, station=MakeGraspStation(scenario, meshcat=meshcat),
                               controller=CONTROLLER_NAME)


def run_ideal_grasp(scenario, *, meshcat=None, duration=None):
    """Simulates the ideal grasp; returns (TrialLog, wall time [s])."""
    grasp = MakeIdealGraspDiagram(scenario, meshcat=meshcat)
    segments = grasp.controller.segments
    simulator = MakeSimulator(grasp.diagram, scenario)
    context = simulator.get_mutable_context()
    end_time = duration if duration is not None else plan_duration(segments) + END_MARGIN_S
    if meshcat is not None:
        meshcat.StartRecording()
    start = time.perf_counter()
    simulator.Initialize()
    simulator.AdvanceTo(end_time)
    wall = time.perf_counter() - start
    if meshcat is not None:
        meshcat.StopRecording()
        meshcat.PublishRecording()
    meta = {"controller": CONTROLLER_NAME, "phases": list(PHASES),
            "phase_starts": {s.phase: s.t_start for s in segments},
            "grip_force": scenario.grasp.grip_force, "wall_time_s": wall,
            "sim_time_s": end_time}
    return collect_trial_log(grasp.loggers, context, scenario=scenario, meta=meta), wall
