"""The ideal open-loop grasp as a runnable trial (Sec. III-A): the grasp diagram with the
scripted grasp (control/scripted_grasp.py), simulated to the script's end and a little beyond."""

import dataclasses
import logging
import time
from collections.abc import Callable
from typing import Annotated

from pydrake.systems.framework import EventStatus
from pydrake.geometry import Meshcat

from tegrasp_drake.control.controller_config import OpenLoopControllerConfig
from tegrasp_drake.control.scripted_grasp import PHASES, plan_duration
from tegrasp_drake.scenario.grasp_diagram import (MakeGraspDiagram, MakeSimulatedStation,
                                                  MakeSimulator, simulated_duration_range)
from tegrasp_drake.scenario.trial_log_writer import collect_trial_log
from tegrasp_drake.scenario.scenario import Scenario, rechecked
from tegrasp_drake.rig.api_boundary import check_argument, public_api
from tegrasp_drake.rig.ranges import SIMULATED_DURATION

CONTROLLER_NAME = OpenLoopControllerConfig.name
END_MARGIN_S = 0.5  # simulated after the script ends, to see the object settle
PROGRESS_PERIOD_S = 0.25  # [s] of simulated time between calls of `progress`

logger = logging.getLogger(__name__)


def MakeIdealGraspDiagram(scenario, *, meshcat=None):
    """The GraspDiagram of the scripted grasp around the simulated station."""
    scripted = scripted_scenario(scenario)
    return MakeGraspDiagram(scripted, station=MakeSimulatedStation(scripted, meshcat=meshcat))


def scripted_scenario(scenario: Scenario) -> Scenario:
    """`scenario` with the open-loop controller: the scripted grasp alone."""
    return dataclasses.replace(scenario, controller=OpenLoopControllerConfig())


def progress_monitor(progress, end_time: float):
    """A Simulator monitor that calls progress(t, end_time) every PROGRESS_PERIOD_S."""
    next_call = [0.0]

    def monitor(root_context) -> EventStatus:
        t = root_context.get_time()
        if t >= next_call[0]:
            next_call[0] = t + PROGRESS_PERIOD_S
            progress(t, end_time)
        return EventStatus.DidNothing()
    return monitor


@public_api
def run_ideal_grasp(scenario: Scenario, *, meshcat: Meshcat | None = None,
                    duration: Annotated[float | None, SIMULATED_DURATION] = None,
                    progress: Callable | None = None):
    """Simulates the ideal grasp for `duration` [s] (default: the plan's plus END_MARGIN_S; at
    most the scenario's time limit, as run_trial's max_time); returns (TrialLog, wall time
    [s]). progress: progress(t, end) [s, simulated]."""
    scripted = rechecked(scripted_scenario(scenario), "run_ideal_grasp: scenario")
    check_argument("run_ideal_grasp", "duration", duration, simulated_duration_range(scripted))
    grasp = MakeIdealGraspDiagram(scenario, meshcat=meshcat)
    segments = grasp.controller.segments
    simulator = MakeSimulator(grasp.diagram, scenario)
    context = simulator.get_mutable_context()
    end_time = duration if duration is not None else plan_duration(segments) + END_MARGIN_S
    if progress is not None:
        simulator.set_monitor(progress_monitor(progress, end_time))
    logger.info("ideal grasp of %s: simulating %.1f s", scenario.object.name, end_time)
    if meshcat is not None:
        meshcat.StartRecording()
    start = time.perf_counter()
    simulator.Initialize()
    simulator.AdvanceTo(end_time)
    wall = time.perf_counter() - start
    if progress is not None:
        progress(end_time, end_time)
    if meshcat is not None:
        meshcat.StopRecording()
        meshcat.PublishRecording()
    # The phases this run reached: a shorter `duration` ends before the plan's later ones, and
    # a trial log's times lie within the log (trial_log_file.meta_problem).
    # The script's end starts its last phase, "done", which no segment is.
    starts = {s.phase: s.t_start for s in segments if s.t_start <= end_time}
    if plan_duration(segments) <= end_time:
        starts[PHASES[-1]] = plan_duration(segments)
    meta = {"controller": CONTROLLER_NAME, "phases": list(PHASES), "phase_starts": starts,
            "grip_force": scenario.grasp.grip_force, "wall_time_s": wall,
            "sim_time_s": end_time}
    return collect_trial_log(grasp.loggers, context, scenario=scenario, meta=meta), wall
