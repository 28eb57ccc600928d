"""Replay a logged (or synthetic) trial through the tactile event systems, offline.
`channels_trajectory` holds each logged value until the next and feeds an EventMatcher wired
as the grasp controller wires it; `replay_events_in_sequence` advances the expected event
as the state machine would, `replay_event_held` keeps one event expected throughout."""

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import Diagram, DiagramBuilder, EventStatus
from pydrake.systems.primitives import (ConstantVectorSource, LogVectorOutput, TrajectorySource,
                                         VectorLogSink)
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.rig.channels import RA_CHANNELS, TAXELS_PER_PAD
from tegrasp_drake.events.event_matcher import (
    EventMatcher, EventMatcherConfig, add_event_matcher)
from tegrasp_drake.events.event_sequencer import EventSequencer
from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS

# Each value becomes visible this much before its time stamp, so that a periodic update at
# the stamp's time sees it although k * period and the stamp may differ in the last bit.
TIME_STAMP_ALLOWANCE_S = 1e-9


def _hold(times: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    indices = np.searchsorted(times, at, side="right") - 1
    return values[np.maximum(indices, 0)]


def channels_trajectory(trial: TactileTrial) -> PiecewisePolynomial:
    """Zero-order hold of [sa_left, sa_right, ra_left, ra_right] over the trial's times."""
    breaks = np.union1d(trial.t_sa, trial.t_ra)
    samples = np.hstack([_hold(trial.t_sa, trial.sa, breaks),
                         _hold(trial.t_ra, trial.ra, breaks)])
    return PiecewisePolynomial.ZeroOrderHold(breaks - TIME_STAMP_ALLOWANCE_S, samples.T)


def tactile_trial_from_log(log, transition_times: Mapping[str, float] | None = None
                           ) -> TactileTrial:
    """The TrialLog's channels: SA (Eq. 1) at the taxel times, RA at the vibration times."""
    taxels = np.asarray(log.taxels)
    sa = np.column_stack([taxels[:, :TAXELS_PER_PAD].sum(axis=1),
                          taxels[:, TAXELS_PER_PAD:].sum(axis=1)])
    return TactileTrial(t_sa=log.t_sa, sa=sa, t_ra=log.t_ra, ra=log.ra,
                        transition_times=dict(transition_times or {}))


@dataclasses.dataclass(frozen=True)
class EventReplay:
    """The event systems' outputs over a replayed trial, one row per control tick (as they
    stood just before the tick's updates, so a match shows in the row of the sequencer's fire
    time).

    times (T,) [s]; scores (T, 4); match (T,) 0 or 1; expected_event (T,) index or -1;
    fire_times: {transition: time [s] the sequencer passed it, or None}. At each matching tick
    (sequence replays only): windows_at_match, the scored (sa, ra) windows; scores_at_match;
    ra_peaks_at_match, each RA channel's largest raw |value|; ra_floor_at_match (+inf: none)."""
    transitions: tuple[str, ...]
    times: np.ndarray
    scores: np.ndarray
    match: np.ndarray
    expected_event: np.ndarray
    fire_times: dict[str, float | None]
    windows_at_match: dict[str, tuple[np.ndarray, np.ndarray]]
    scores_at_match: dict[str, np.ndarray]
    ra_peaks_at_match: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)
    ra_floor_at_match: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)

    def match_rises(self) -> np.ndarray:
        """Times [s] of the rows where match turns on (from off, or in the first row)."""
        on = self.match > 0.5
        return self.times[on & ~np.concatenate([[False], on[:-1]])]


def live_matcher_config(events: Mapping[str, MemorizedEvent],
                        config: EventMatcherConfig | None = None) -> EventMatcherConfig:
    """`config` (default thresholds if None) at the events' sample rates."""
    event = next(iter(events.values()))
    return dataclasses.replace(config or EventMatcherConfig(), sa_rate_hz=event.sa_rate_hz,
                               ra_rate_hz=event.ra_rate_hz)


@dataclasses.dataclass(frozen=True)
class _ReplayDiagram:
    diagram: Diagram
    matcher: EventMatcher
    sequencer: EventSequencer | None
    loggers: dict[str, VectorLogSink]


def _build_replay_diagram(trial: TactileTrial, events: Mapping[str, MemorizedEvent], *,
                          sequence: Sequence[str] | None, held: str | None,
                          config: EventMatcherConfig, tick_s: float,
                          armed_from_s: Mapping[str, float] | None = None) -> _ReplayDiagram:
    """channels -> EventMatcher <-> EventSequencer (or a held event)."""
    builder = DiagramBuilder()
    source = builder.AddNamedSystem("channels", TrajectorySource(channels_trajectory(trial)))
    matcher = add_event_matcher(builder, events, config, channels=source.get_output_port())
    sequencer = None
    if sequence is not None:
        sequencer = builder.AddNamedSystem("event_sequencer", EventSequencer(
            [matcher.event_index(transition) for transition in sequence], period_s=tick_s,
            armed_from_s=[(armed_from_s or {}).get(transition, 0.0) for transition in sequence]))
        builder.Connect(matcher.GetOutputPort("match"), sequencer.GetInputPort("match"))
        expected = sequencer.GetOutputPort("expected_event")
    else:
        expected = builder.AddNamedSystem("held_event", ConstantVectorSource(
            [float(matcher.event_index(held))])).get_output_port()
    builder.Connect(expected, matcher.GetInputPort("expected_event"))
    loggers = {name: LogVectorOutput(port, builder, tick_s) for name, port in (
        ("scores", matcher.GetOutputPort("scores")), ("match", matcher.GetOutputPort("match")),
        ("expected_event", expected))}
    return _ReplayDiagram(builder.Build(), matcher, sequencer, loggers)


def _replay(trial: TactileTrial, events: Mapping[str, MemorizedEvent], *,
            sequence: Sequence[str] | None, held: str | None,
            config: EventMatcherConfig | None, t_end: float | None,
            armed_from_s: Mapping[str, float] | None = None) -> EventReplay:
    config = live_matcher_config(events, config)
    tick_s = 1.0 / max(config.sa_rate_hz, config.ra_rate_hz)
    systems = _build_replay_diagram(trial, events, sequence=sequence, held=held,
                                    config=config, tick_s=tick_s, armed_from_s=armed_from_s)
    simulator = Simulator(systems.diagram)
    root = simulator.get_mutable_context()
    matcher = systems.matcher
    matcher_context = matcher.GetMyContextFromRoot(root)
    match_port, scores_port = matcher.GetOutputPort("match"), matcher.GetOutputPort("scores")
    expected_port = matcher.GetInputPort("expected_event")
    window_ports = {kind: matcher.GetOutputPort(f"{kind}_window") for kind in ("sa", "ra")}
    windows_at_match, scores_at_match, ra_peaks_at_match, ra_floor_at_match = {}, {}, {}, {}
    ra_window = next(window for window in matcher.rate_windows
                     if RA_CHANNELS[0] in window.group.channels)
    ra_rows = [ra_window.group.channels.index(c) for c in RA_CHANNELS]

    def capture_windows_at_match(context):
        # Called after each step, with the outputs of the tick before the step's end.
        if systems.sequencer is not None and match_port.Eval(matcher_context)[0]:
            transition = matcher.transitions[int(expected_port.Eval(matcher_context)[0])]
            windows_at_match[transition] = tuple(
                port.Eval(matcher_context).reshape(2, matcher.window_length(kind))
                for kind, port in window_ports.items())
            scores_at_match[transition] = scores_port.Eval(matcher_context).copy()
            raw = ra_window.layout.current(
                matcher_context.get_discrete_state(ra_window.state).value())
            ra_peaks_at_match[transition] = np.abs(raw[ra_rows]).max(axis=1)
            # The floor is fixed once its quiet period is over (ra_noise_floor.py), so its
            # value after this tick's update is the one the matcher read at it.
            ra_floor_at_match[transition] = (
                matcher.GetInputPort("ra_floor").Eval(matcher_context).copy()
                if matcher.has_ra_floor else np.full(len(RA_CHANNELS), np.inf))
        return EventStatus.Succeeded()

    simulator.set_monitor(capture_windows_at_match)
    simulator.AdvanceTo(t_end if t_end is not None else float(trial.t_ra[-1]))
    logs = {name: logger.FindLog(root) for name, logger in systems.loggers.items()}
    fire_times = {}
    if systems.sequencer is not None:
        fire_times = dict(zip(sequence, systems.sequencer.fire_times(
            systems.sequencer.GetMyContextFromRoot(root))))
    return EventReplay(
        transitions=matcher.transitions, times=logs["match"].sample_times().copy(),
        scores=logs["scores"].data().T.copy(), match=logs["match"].data()[0].copy(),
        expected_event=logs["expected_event"].data()[0].copy(), fire_times=fire_times,
        windows_at_match=windows_at_match, scores_at_match=scores_at_match,
        ra_peaks_at_match=ra_peaks_at_match, ra_floor_at_match=ra_floor_at_match)


def replay_events_in_sequence(
        trial: TactileTrial, events: Mapping[str, MemorizedEvent],
        sequence: Sequence[str] = REQUIRED_TRANSITIONS, *,
        config: EventMatcherConfig | None = None, t_end: float | None = None,
        armed_from_s: Mapping[str, float] | None = None) -> EventReplay:
    """Replays `trial`, expecting the events of `sequence` one after another. events: one
    object's {transition: event}; config: the matcher's thresholds; armed_from_s: {transition:
    time [s]} before which it is not looked for."""
    return _replay(trial, events, sequence=tuple(sequence), held=None, config=config,
                   t_end=t_end, armed_from_s=armed_from_s)


def replay_event_held(
        trial: TactileTrial, events: Mapping[str, MemorizedEvent], transition: str, *,
        config: EventMatcherConfig | None = None, t_end: float | None = None) -> EventReplay:
    """Replays `trial` with the event of `transition` expected throughout."""
    return _replay(trial, events, sequence=None, held=transition, config=config,
                   t_end=t_end)
