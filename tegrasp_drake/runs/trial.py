"""One closed-loop grasp trial: build the station and controller, simulate until the state
machine ends or time runs out, log, and judge it against the ground truth
(scenario/trial_judge.py, which a trial log's reader re-runs). `run_trial` returns a
TrialResult (a sweep's trial function: sweep/trial_function.py)."""

import logging
import time
from collections.abc import Callable
from typing import Annotated

from pydrake.geometry import Meshcat

from tegrasp_drake.control.grasp_modes import TERMINAL_MODES, Mode
from tegrasp_drake.scenario.grasp_diagram import (MakeGraspDiagram, MakeSimulatedStation,
                                                  MakeSimulator, simulated_duration_range)
from tegrasp_drake.scenario.trial_judge import judge_trial
from tegrasp_drake.scenario.trial_result import TrialResult
from tegrasp_drake.scenario.trial_log_writer import collect_trial_log
from tegrasp_drake.scenario.scenario import Scenario, rechecked
from tegrasp_drake.rig.ranges import SIMULATED_DURATION
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.rig.api_boundary import check_argument, public_api

class SimulationFailedError(ConfigError):
    """Drake could not step a trial's physics (a singular mass matrix, a non-finite pose): the
    scenario's settings are the likely cause, since each lies in its range but together they
    can ask for physics the model does not handle. One line naming the time and Drake's words."""


END_MARGIN_S = 0.5  # simulated after the machine ends, to see the object settle
CHECK_PERIOD_S = 0.25  # how often the run checks whether the machine has ended

logger = logging.getLogger(__name__)


def _step(advance: Callable, context) -> None:
    """Runs `advance`; Drake's RuntimeError while it steps becomes SimulationFailedError (the
    one boundary between a trial's simulation and its caller)."""
    try:
        advance()
    except RuntimeError as error:
        from tegrasp_drake.rig.files import interrupt_received, one_line
        if interrupt_received():  # a Ctrl-C Drake wrapped: the command line's to report
            raise
        words = one_line(str(error).strip().split(". ")[0]) or type(error).__name__
        raise SimulationFailedError(
            f"the simulation stopped at t = {context.get_time():.3f} s: Drake: "
            f"{shorten(words, 200)}; a setting far from the built-in scenario's is the likely "
            "cause (check the values you set with --set or in the scenario file; if you set "
            "none, please report it)") from None


@public_api
def run_trial(scenario: Scenario, *, meshcat: Meshcat | None = None, events: dict | None = None,
              corrective_events: dict | None = None,
              max_time: Annotated[float | None, SIMULATED_DURATION] = None,
              progress: Callable | None = None) -> TrialResult:
    """Simulates one trial of `scenario` with its controller; returns its TrialResult.
    max_time: [s] simulated at most, up to the scenario's time limit (the default; the
    grasp diagram's time_limit); events, corrective_events: default MakeGraspDiagram's;
    progress: progress(t, end) [s, simulated]."""
    scenario = rechecked(scenario, "run_trial: scenario")  # changed after loading?
    check_argument("run_trial", "max_time", max_time, simulated_duration_range(scenario))
    grasp = MakeGraspDiagram(scenario, station=MakeSimulatedStation(scenario, meshcat=meshcat),
                                events=events, corrective_events=corrective_events)
    controller, loggers = grasp.controller, grasp.loggers
    simulator = MakeSimulator(grasp.diagram, scenario)
    context = simulator.get_mutable_context()
    limit = max_time if max_time is not None else grasp.time_limit
    logger.info("trial: %s at offset %s m, controller %s, seed %d; simulating up to %.1f s",
                scenario.object.name, list(scenario.placement.offset), controller.name,
                scenario.random_seed, limit)
    if logger.isEnabledFor(logging.DEBUG):
        from tegrasp_drake.scenario.scenario import scenario_to_yaml
        logger.debug("the trial's scenario:\n%s", scenario_to_yaml(scenario))
    if meshcat is not None:
        meshcat.StartRecording()
    start, start_cpu = time.perf_counter(), time.process_time()
    _step(simulator.Initialize, context)
    ended_at = None
    reported = 0
    while context.get_time() < limit - 1e-9:
        _step(lambda: simulator.AdvanceTo(min(context.get_time() + CHECK_PERIOD_S, limit)),
              context)
        if logger.isEnabledFor(logging.INFO):
            transitions = controller.transitions(context)
            for transition in transitions[reported:]:
                logger.info("%7.3f s  %s -> %s [%s] %s", transition.t,
                            transition.from_mode.label, transition.to_mode.label,
                            transition.trigger.value, transition.reason)
            reported = len(transitions)
        if ended_at is None and controller.current_mode(context) in TERMINAL_MODES:
            ended_at = context.get_time()
            limit = min(limit, ended_at + END_MARGIN_S)
        if progress is not None:
            progress(context.get_time(), limit)
    wall, cpu = time.perf_counter() - start, time.process_time() - start_cpu
    if meshcat is not None:
        meshcat.StopRecording()
        meshcat.PublishRecording()
    transitions = controller.transitions(context)
    timeline = [transition.as_dict() for transition in transitions]
    sim_time = context.get_time()
    meta = {"controller": controller.name, "transitions": timeline,
            "mode_names": [m.label for m in Mode], "grip_force": scenario.grasp.grip_force,
            "wall_time_s": wall, "sim_time_s": sim_time}
    log = collect_trial_log(loggers, context, scenario=scenario, meta=meta)
    log.phase = controller.logged_modes(log.phase)  # the Modes meta 'mode_names' names
    judged = judge_trial(log, transitions, scenario)
    judged["final_mode"] = Mode.from_label(judged["final_mode"])
    result = TrialResult(
        object=scenario.object.name, offset_m=list(scenario.placement.offset),
        controller=controller.name, seed=scenario.random_seed, transitions=tuple(transitions),
        **judged, sim_time_s=sim_time, wall_time_s=wall, cpu_time_s=cpu,
        real_time_factor=sim_time / wall if wall > 0 else None, log=log)
    log.meta["result"] = result.to_dict()
    # For the Fig. 5a-b plot (figures.py): when each state began, and the physical events.
    log.meta["phase_starts"] = {e.to_mode.label: e.t for e in reversed(transitions)}
    log.meta["events"] = result.physical_events
    logger.info("trial: simulated %.2f s in %.2f s wall; hold %s, unload %s", sim_time, wall,
                result.hold_success, result.unload_success)
    return result
