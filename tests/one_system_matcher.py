"""The event matcher as one system, as it was before the WindowNormalizer fed it (up to
commit ae03fd0): each rate's StreamingCorrelator keeps its own window and scores it in one
periodic update. Tests run it beside the live EventMatcher (which scores its
WindowNormalizer's windows) and compare the two tick by tick.

It keeps the live matcher's quiet-template rule (events/ra_noise_floor.py), written out here
on its own window: an RA channel whose template of the expected event is flat scores 1
while its full window's largest |value| stays within the channel's known noise floor (its
own RaNoiseFloor on the same channels)."""

import dataclasses
import functools

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import LogVectorOutput, TrajectorySource

from tegrasp_drake.events import (
    NO_EVENT, REQUIRED_TRANSITIONS, EventMatcherConfig, EventSequencer, StreamingCorrelator,
    add_event_matcher, channels_trajectory, event_templates)
from tegrasp_drake.events.correlation import template_is_flat
from tegrasp_drake.events.event_matcher import window_normalizer_config
from tegrasp_drake.events.ra_noise_floor import RaNoiseFloor, rule_sigmas
from tegrasp_drake.events.transitions import transition_order
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.tactile.sliding_window import SLACK_FRACTION


class OneSystemMatcher(LeafSystem):
    """channels, expected_event -> scores, match, with its own windows (no normaliser)."""

    def __init__(self, events, config: EventMatcherConfig):
        super().__init__()
        ordered = sorted(events.values(), key=lambda e: transition_order(e.transition))
        self._thresholds = np.array([config.sa_threshold if c in SA_CHANNELS
                                     else config.ra_threshold
                                     for c in range(len(CHANNEL_NAMES))])
        self._channels = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._expected = self.DeclareVectorInputPort("expected_event", 1)
        self._groups = []
        quiet_rows = []  # per group, per event: [(row, RA channel index)] of flat RA templates
        for group in window_normalizer_config(events, config).rate_groups():
            templates = [event_templates(e, group.channels, group.window_length)
                         for e in ordered]
            quiet_rows.append([
                [(row, RA_CHANNELS.index(c)) for row, (c, flat) in enumerate(zip(
                    group.channels, template_is_flat(t, config.min_contrast)))
                 if flat and c in RA_CHANNELS] for t in templates])
            correlator = StreamingCorrelator(
                templates, min_contrast=config.min_contrast,
                slack=max(1, int(group.window_length * SLACK_FRACTION)))
            index = self.DeclareDiscreteState(correlator.initial_state())
            channels = slice(group.channels[0], group.channels[-1] + 1)
            self.DeclarePeriodicDiscreteUpdateEvent(
                1.0 / group.rate_hz, 0.0, functools.partial(
                    self._update, index, correlator, channels, quiet_rows[-1],
                    group.rate_hz, group.window_length))
            self._groups.append((index, correlator, channels))
        self._floor = (self.DeclareVectorInputPort("ra_floor", len(RA_CHANNELS))
                       if any(rows for by_event in quiet_rows for rows in by_event) else None)
        self.DeclareVectorOutputPort("scores", len(CHANNEL_NAMES), self._calc_scores)
        self.DeclareVectorOutputPort("match", 1, self._calc_match)

    def _update(self, index, correlator, channels, quiet_rows, rate_hz, window_length,
                context, discrete_state):
        state = discrete_state.get_mutable_value(index)
        expected = int(self._expected.Eval(context)[0])
        scores = correlator.push(state, self._channels.Eval(context)[channels], expected)
        pushed = int(round(context.get_time() * rate_hz)) + 1  # samples so far
        if self._floor is None or expected == NO_EVENT or pushed < window_length:
            return
        floor = self._floor.Eval(context)
        window = correlator.window(state)
        for row, ra in quiet_rows[expected]:
            if np.abs(window[row]).max() <= floor[ra] < np.inf:
                scores[row] = 1.0

    def _calc_scores(self, context, output):
        scores = np.empty(len(CHANNEL_NAMES))
        for index, correlator, channels in self._groups:
            scores[channels] = correlator.scores(context.get_discrete_state(index).value())
        output.SetFromVector(scores)

    def _calc_match(self, context, output):
        expected = int(self._expected.Eval(context)[0])
        scored = {correlator.active_event(context.get_discrete_state(index).value())
                  for index, correlator, _ in self._groups}
        scores = self.GetOutputPort("scores").Eval(context)
        output.SetAtIndex(0, float(expected != NO_EVENT and scored == {expected}
                                   and bool(np.all(scores > self._thresholds))))


@dataclasses.dataclass(frozen=True)
class TickByTick:
    """Both matchers' outputs at every 1 kHz tick of a replay."""
    fire_times: list  # when the sequencer (driven by the live matcher) advanced
    scores: np.ndarray  # (ticks, 4), the live matcher's
    match: np.ndarray  # (ticks,)
    one_system_scores: np.ndarray
    one_system_match: np.ndarray


def replay_both(trial, events, config: EventMatcherConfig, *,
                sequence=REQUIRED_TRANSITIONS) -> TickByTick:
    """Replays `trial` through the live matcher and the one-system matcher; an
    EventSequencer on the live matcher's match sets the expected event of both."""
    builder = DiagramBuilder()
    source = builder.AddSystem(TrajectorySource(channels_trajectory(trial)))
    live = add_event_matcher(builder, events, config, channels=source.get_output_port())
    old = builder.AddSystem(OneSystemMatcher(events, config))
    builder.Connect(source.get_output_port(), old.GetInputPort("channels"))
    if old.HasInputPort("ra_floor"):
        floor = builder.AddNamedSystem("one_system_ra_floor", RaNoiseFloor(
            sigmas=config.ra_noise_floor_sigmas or rule_sigmas(config.ra_rate_hz),
            quiet_s=config.ra_noise_quiet_s, ra_rate_hz=config.ra_rate_hz,
            envelope_hz=config.ra_envelope_hz))
        builder.Connect(source.get_output_port(), floor.GetInputPort("channels"))
        builder.Connect(floor.GetOutputPort("ra_floor"), old.GetInputPort("ra_floor"))
    tick_s = 1.0 / max(config.sa_rate_hz, config.ra_rate_hz)
    sequencer = builder.AddSystem(EventSequencer(
        [live.event_index(t) for t in sequence], period_s=tick_s))
    builder.Connect(live.GetOutputPort("match"), sequencer.GetInputPort("match"))
    for matcher in (live, old):
        builder.Connect(sequencer.GetOutputPort("expected_event"),
                        matcher.GetInputPort("expected_event"))
    logs = [LogVectorOutput(matcher.GetOutputPort(name), builder, tick_s)
            for matcher in (live, old) for name in ("scores", "match")]
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(float(trial.t_ra[-1]))
    root = simulator.get_context()
    data = [log.FindLog(root).data().T for log in logs]
    return TickByTick(
        fire_times=list(sequencer.fire_times(sequencer.GetMyContextFromRoot(root))),
        scores=data[0], match=data[1][:, 0], one_system_scores=data[2],
        one_system_match=data[3][:, 0])
