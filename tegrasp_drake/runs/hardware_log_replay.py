"""The event matcher re-run offline on a hardware run's LCM log (`tegrasp replay LOG`):
the SA and RA channels computed from TEGRASP_TACTILE as the controller did, matched against
the object's memorized events two ways (per logged mode, and in grasp order; events/replay.py),
with the run's own matcher settings (TEGRASP_RUN_INFO), else the defaults; on each stretch of
the tactile stream between its silences (RunLog.tactile_segments), never through one."""

import dataclasses
import logging
import pathlib

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.control.controller_registry import controller_entry
from tegrasp_drake.control.grasp_controller import event_matcher_config
from tegrasp_drake.events.event_matcher import EventMatcherConfig, add_event_matcher
from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.events.event_file import INDEX_FILE, MemorizedEventError
from tegrasp_drake.events.events_folder import find_memorized_events
from tegrasp_drake.events.replay import (EventReplay, live_matcher_config,
                                         channels_trajectory, replay_events_in_sequence)
from tegrasp_drake.events.streaming_correlation import NO_EVENT
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS, transition_name
from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.files import one_line
from tegrasp_drake.runs.hardware_log_reader import (RunLog, RunLogError, TactileSegment,
                                                    read_run_log)
from tegrasp_drake.scenario.scenario import resolve_object, sample_rates_hz, scenario_from_yaml
from tegrasp_drake.scenario.scenario_events import check_events_object, check_recorded_runs

logger = logging.getLogger(__name__)


def expected_event_schedule(transitions: list[dict], event_index: dict[str, int]):
    """[(t_start, event index)]: while in the mode a logged transition left, the event of
    that transition (or -1 if none is memorized); from t = 0 on."""
    schedule, entered = [], 0.0
    for transition in transitions:
        schedule.append((entered, event_index.get(
            transition_name(transition["from"], transition["to"]), NO_EVENT)))
        entered = transition["t"]
    schedule.append((entered, NO_EVENT))
    return schedule


@dataclasses.dataclass
class ReplayedTransition:
    """One memorized transition of the log, and what the matcher made of it offline."""
    transition: str
    mode_entered: float        # [s] when the mode it leaves was entered
    logged_time: float         # [s] when the state machine made the transition
    match_time: float | None   # [s] first offline match while expected, None if none
    best_scores: list          # the four channels' scores at the match, or their maxima

    @property
    def delay(self) -> float | None:
        """match - transition [s] (negative: the matcher matched before the transition)."""
        return None if self.match_time is None else self.match_time - self.logged_time


def _shifted(trial: TactileTrial, origin: float) -> TactileTrial:
    """`trial` with its times moved `origin` [s] earlier (a replay starts at time 0)."""
    return dataclasses.replace(trial, t_sa=trial.t_sa - origin, t_ra=trial.t_ra - origin)


def _matcher_samples(segment: TactileSegment, transitions: list[dict], events, config):
    """(the expected event's schedule [(log time [s], event index)] of `transitions`, times
    [s, log time], match, scores) of an EventMatcher run over one segment from its origin,
    one row per ms."""
    origin, trial = segment.origin, _shifted(segment.trial, segment.origin)
    builder = DiagramBuilder()
    channels = builder.AddSystem(TrajectorySource(channels_trajectory(trial)))
    matcher = add_event_matcher(builder, events, config, channels=channels.get_output_port())
    index = {name: matcher.event_index(name) for name in matcher.transitions}
    schedule = expected_event_schedule(transitions, index)
    # transitions in one tick: the mode after the last one holds from that time on
    schedule = [entry for k, entry in enumerate(schedule)
                if k + 1 == len(schedule) or schedule[k + 1][0] > entry[0]]
    end = float(max(trial.t_sa[-1], trial.t_ra[-1]))
    # the event expected at the segment's start, then each change within it
    current = [entry for entry in schedule if entry[0] <= origin][-1:]
    inside = [(t - origin, event) for t, event in schedule if origin < t <= origin + end]
    steps = [(0.0, event) for _, event in current] + inside
    breaks = [t for t, _ in steps] + [max(end, steps[-1][0]) + 1.0]
    values = np.array([[float(i) for _, i in steps] + [float(NO_EVENT)]])
    expected = builder.AddSystem(TrajectorySource(
        PiecewisePolynomial.ZeroOrderHold(breaks, values)))
    builder.Connect(expected.get_output_port(), matcher.GetInputPort("expected_event"))
    period = 1e-3
    match_log = LogVectorOutput(matcher.GetOutputPort("match"), builder, period)
    score_log = LogVectorOutput(matcher.GetOutputPort("scores"), builder, period)
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(end)
    context = simulator.get_context()
    return (schedule, match_log.FindLog(context).sample_times() + origin,
            match_log.FindLog(context).data()[0] > 0.5, score_log.FindLog(context).data().T)


def replay_matcher(segments: list[TactileSegment], transitions: list[dict], events, *,
                   config: EventMatcherConfig | None = None) -> list[ReplayedTransition]:
    """Runs an EventMatcher over each of `segments` (RunLog.tactile_segments), wired as the
    live controller wires it, with the expected event scheduled by `transitions`, restarted
    at each segment (its windows fill again); one result per memorized transition."""
    samples = [_matcher_samples(segment, transitions, events, config) for segment in segments]
    schedule = samples[0][0]
    times = np.concatenate([t for _, t, _, _ in samples])
    match = np.concatenate([m for _, _, m, _ in samples])
    scores = np.concatenate([x for _, _, _, x in samples])
    results = []
    for (entered, event), transition in zip(schedule, transitions):
        if event == NO_EVENT:
            continue
        window = (times >= entered) & (times <= transition["t"])
        hits = np.flatnonzero(window & match)
        if hits.size:
            match_time, best = float(times[hits[0]]), scores[hits[0]]
        else:
            match_time = None
            best = scores[window].max(axis=0) if window.any() else np.zeros(4)
        name = transition_name(transition["from"], transition["to"])
        results.append(ReplayedTransition(name, entered, transition["t"], match_time,
                                          [float(x) for x in best]))
    return results


def replay_in_sequence(segments: list[TactileSegment], events, *,
                       config: EventMatcherConfig | None = None) -> EventReplay:
    """replay_events_in_sequence over each of `segments` from its origin, the sequencer taking
    up in each the events the ones before did not pass; its rows and times in log time."""
    replays, fire_times = [], {transition: None for transition in REQUIRED_TRANSITIONS}
    for segment in segments:
        remaining = [name for name, fired in fire_times.items() if fired is None]
        if not remaining:
            break
        replay = replay_events_in_sequence(_shifted(segment.trial, segment.origin), events,
                                           remaining, config=config)
        fire_times.update({name: None if fired is None else fired + segment.origin
                           for name, fired in replay.fire_times.items()})
        replays.append(dataclasses.replace(replay, times=replay.times + segment.origin))
    first = replays[0]
    return dataclasses.replace(
        first, times=np.concatenate([r.times for r in replays]),
        scores=np.concatenate([r.scores for r in replays]),
        match=np.concatenate([r.match for r in replays]),
        expected_event=np.concatenate([r.expected_event for r in replays]),
        fire_times=fire_times,
        **{field: {k: v for r in replays for k, v in getattr(r, field).items()}
           for field in ("windows_at_match", "scores_at_match", "ra_peaks_at_match",
                         "ra_floor_at_match")})


def matcher_config_of_run(run_info, events, source: str = "the run's scenario", *,
                          scenario=None) -> EventMatcherConfig:
    """The live matcher of an event-triggered run; else the defaults at the events' rates.
    `scenario`: the run's Scenario when the caller has read it already (RunLog.scenario), so
    it is not parsed again; else it is read from run_info, a bad one refused naming `source`."""
    if scenario is None and run_info is not None and run_info.scenario_yaml:
        scenario = scenario_from_yaml(run_info.scenario_yaml, source)
    if scenario is not None and controller_entry(scenario.controller).event_triggered:
        return event_matcher_config(scenario.controller, gripper_model=scenario.gripper.model,
                                    rates_hz=sample_rates_hz(scenario))
    return live_matcher_config(events, EventMatcherConfig())


@dataclasses.dataclass
class RunLogReplay:
    """A run's log and the matcher re-run on it offline, both ways (module docstring)."""
    log: RunLog
    object_name: str
    events_dir: str
    transitions: list[ReplayedTransition]   # expecting the logged transitions' events
    in_sequence: EventReplay                # expecting the events in grasp order

    def summary(self) -> dict:
        """What the log holds and what the replays found, as JSON-able data."""
        log, info = self.log, self.log.run_info
        return {
            "log": str(log.path), "controller": info.controller if info else None,
            "object": self.object_name, "events": self.events_dir,
            "messages": log.message_counts,
            "tactile_s": float(log.tactile["t"][-1] - log.tactile["t"][0])
            if len(log.tactile["t"]) else 0.0,
            "stale_ticks": int(log.tactile["stale"].sum()),
            "transitions": log.transitions,
            "faults": [{"t": f.utime * 1e-6, "device": f.device, "kind": f.kind,
                        "code": f.code, "description": f.description,
                        "since": f.since_utime * 1e-6}
                       for f in log.faults],
            "replay": [{"transition": r.transition, "mode_entered": r.mode_entered,
                        "logged_time": r.logged_time, "match_time": r.match_time,
                        "scores": r.best_scores} for r in self.transitions],
            "sequence_fire_times": self.in_sequence.fire_times}


def _check_events_felt_on_the_runs_object(scenario, folder, events: dict, path) -> None:
    """MemorizedEventError when the run's object's events were felt on another object than
    the one the run grasped (its logged scenario's, resolved as the run resolved it), as a
    trial's and a hardware run's events are checked (load_controller_events)."""
    grasped = resolve_object(scenario.object, f"run log '{path}': its {RUN_INFO_CHANNEL} "
                             "scenario", loaded=True)
    check_events_object(dataclasses.replace(scenario, object=grasped), folder, events)


PATH_MAX_CHARS = 4096  # Linux's PATH_MAX: no folder a run used is named by a longer path

# What to do when the events folder a run log names cannot be replayed with.
REPLAY_EVENTS_ADVICE = ("Give --events DIR, a folder holding the object's events, to replay "
                        "with those")


def _recorded_folder_words(path, folder: str) -> str:
    """How a refusal names the events folder a run's log recorded (never one the user gave):
    whole, as the user must find it (up to a path's longest, 4096 bytes), control characters
    escaped."""
    return (f"run log '{path}' recorded the events folder its run used, "
            f"'{one_line(shorten(folder, PATH_MAX_CHARS))}' "
            f"({RUN_INFO_CHANNEL} events_dir), which the replay reads when no --events is "
            "given")


def replay_run_log(path, *, object_name: str | None = None,
                   events_dir: str | None = None) -> RunLogReplay:
    """Reads a run's log and re-runs the matcher on it both ways, with the events of
    `object_name` (default the run's) from `events_dir` (default the run's folder, which must
    still be there, else the user's, then the package's). RunLogError, MemorizedEventError
    or ValueError naming what is wrong."""
    log = read_run_log(path)
    logger.info(f"replay: read {path}: " + ", ".join(
        f"{channel} {count}" for channel, count in sorted(log.message_counts.items())))
    info = log.run_info
    object_name = object_name or log.object_name
    if not object_name and log.message_counts.get(RUN_INFO_CHANNEL):  # there, undecodable
        raise RunLogError(f"run log '{path}': its {RUN_INFO_CHANNEL} message is corrupt (it "
                          "does not decode as lcmt_tegrasp_run_info), so the run's object is "
                          "not known: give --object")
    if not object_name:
        raise RunLogError(f"run log '{path}' has no {RUN_INFO_CHANNEL}: give --object")
    recorded = None  # the events folder the log names, read for want of --events
    if not events_dir and info and info.events_dir:
        # the events the run used; gone, another folder's would be a different replay, so
        # it is refused as a missing --events DIR is (docs/user-guide.md, "events")
        recorded = _recorded_folder_words(path, info.events_dir)
        if not pathlib.Path(info.events_dir).is_dir():
            raise RunLogError(f"{recorded}: it is not a folder here. {REPLAY_EVENTS_ADVICE}")
        events_dir = info.events_dir
    try:
        folder, events = find_memorized_events(paths.events_search_path(events_dir),
                                               object_name)
        check_recorded_runs(folder, events)
        if log.scenario is not None and object_name == log.scenario.object.name:
            _check_events_felt_on_the_runs_object(log.scenario, folder, events, path)
    except MemorizedEventError as error:
        if recorded is None:
            raise
        at = "" if error.path.name == INDEX_FILE else f"{error.path}: "  # a file: named
        refused = MemorizedEventError(error.path, error.problem, object_name,
                                      remedy=REPLAY_EVENTS_ADVICE)
        refused.args = (one_line(f"{recorded}: {at}{error.problem}. {REPLAY_EVENTS_ADVICE}"),)
        raise refused from None
    events_dir = str(folder)
    # a scenario_yaml that does not read is damage (RunLog.damage): the defaults are used
    config = matcher_config_of_run(None if log.scenario_problem else info, events,
                                   f"run log '{path}': its TEGRASP_RUN_INFO scenario",
                                   scenario=log.scenario)
    segments = log.tactile_segments()
    logger.debug(f"replay: the run's controller "
                 f"{info.controller if info and info.controller else 'not logged'}; the "
                 f"matcher's settings {config}")
    logger.info(f"replay: the matcher re-run on {sum(len(s.trial.t_ra) for s in segments)} "
                f"tactile samples in {len(segments)} stretch(es) and {len(log.transitions)} "
                f"logged transitions with the events of {object_name} from {events_dir}")
    return RunLogReplay(
        log=log, object_name=object_name, events_dir=events_dir,
        transitions=replay_matcher(segments, log.transitions, events, config=config),
        in_sequence=replay_in_sequence(segments, events, config=config))
