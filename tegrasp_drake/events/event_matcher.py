"""EventMatcher: the paper's Fig. 3 comparison of the live tactile channels with the
expected memorized event: the WindowNormalizer's 0.5 s windows (Sec. III-A) scored by Eq. 3
(Sec. III-B) in an EventScorer."""

import dataclasses
import functools
from collections.abc import Iterable, Mapping

import numpy as np
from pydrake.systems.framework import Diagram, DiagramBuilder, LeafSystem

from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.events.correlation import normalize_by_max, template_is_flat
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.streaming_correlation import SlidingCorrelation
from tegrasp_drake.events.transitions import NO_EVENT, transition_order
from tegrasp_drake.tactile.sampling import resample_window
from tegrasp_drake.tactile.sliding_window import SlidingWindowState
from tegrasp_drake.tactile.window_normalizer import (
    WindowNormalizer, WindowNormalizerConfig, entering_samples, window_layout)


@dataclasses.dataclass
class EventMatcherConfig:
    """Thresholds of Sec. III-B and the live sample rates [Hz].

    A channel passes when its score is greater than its threshold; min_contrast is the
    live contrast a channel needs for its score to count (correlation.py), > 0.
    """
    sa_threshold: float = 0.9
    ra_threshold: float = 0.7
    min_contrast: float = 0.25
    sa_rate_hz: float = 100.0
    ra_rate_hz: float = 1000.0


def event_templates(event: MemorizedEvent, channels: tuple[int, ...],
                     length: int) -> np.ndarray:
    """The event's windows of `channels`, resampled to `length` samples, max-normalised."""
    rows = [resample_window(event.channel(CHANNEL_NAMES[c]), length)[0] for c in channels]
    return normalize_by_max(np.array(rows))


def window_normalizer_config(events: Mapping[str, MemorizedEvent],
                             config: EventMatcherConfig) -> WindowNormalizerConfig:
    """The windows an EventMatcher scores: the events' window_s at the config's rates."""
    return WindowNormalizerConfig(window_s=next(iter(events.values())).window_s,
                                  sa_rate_hz=config.sa_rate_hz, ra_rate_hz=config.ra_rate_hz)


@dataclasses.dataclass(frozen=True)
class _RateGroup:
    """What one periodic update of the EventScorer works on."""
    state_index: object  # DiscreteStateIndex of the correlation's state
    correlation: SlidingCorrelation
    layout: SlidingWindowState  # the normaliser's layout of the window
    position_port: object  # input ports: the WindowNormalizer's window position ...
    buffer_port: object  # ... and buffer
    channels: slice  # the group's entries of the four channels


class EventScorer(LeafSystem):
    """Eq. 3 scores of the WindowNormalizer's windows against the expected memorized event;
    its match. The EventMatcher diagram wires the two; see there for the ports' meaning.

    It keeps no samples, only each rate's streaming correlations (SlidingCorrelation) in
    the Context. Every tick of a rate, the normaliser takes one sample into its window and
    this system slides the correlations by the same sample. Both are discrete updates at
    the same ticks, and Drake computes every update of a tick from the state before it: at
    the tick, the normaliser's `*_window_position` (offset, samples held, oldest samples)
    still describes the window before the sample. The update takes the entering sample from
    `channels` (entering_samples, as the normaliser does) and the leaving one from the
    position; it reads the normaliser's buffer (`*_window_buffer`) only to recompute the
    correlations or when an extreme left the window, and then pushes the sample into a copy
    of it. So the scores after a tick are those of the window the normaliser holds after
    that tick.

    .. pydrake_system::

        name: EventScorer
        input_ports:
        - channels
        - expected_event
        - sa_window_position
        - sa_window_buffer
        - ra_window_position
        - ra_window_buffer
        output_ports:
        - scores
        - match
        - scored_event

    (one `sa_ra_window_position`, `sa_ra_window_buffer` pair when the rates match).
    """

    def __init__(self, events: Mapping[str, MemorizedEvent],
                 config: EventMatcherConfig | None = None):
        super().__init__()
        config = dataclasses.replace(config or EventMatcherConfig())
        self._config = config
        if not 0.0 < config.min_contrast:
            raise ValueError(f"min_contrast {config.min_contrast} must be positive")
        self._events = self._ordered_events(events)
        self._transitions = tuple(e.transition for e in self._events)
        self._thresholds = np.array(
            [config.sa_threshold] * len(SA_CHANNELS) + [config.ra_threshold] * len(RA_CHANNELS))
        # expected_event values accepted, as the port holds them -> event index.
        self._event_of_value = {float(event): event
                                for event in range(NO_EVENT, len(self._events))}
        self._channels_port = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._expected_port = self.DeclareVectorInputPort("expected_event", 1)
        # One correlation, state group, window input and periodic update per sample rate.
        self._groups = []
        templates_by_event = [{} for _ in self._events]
        for group in window_normalizer_config(events, config).rate_groups():
            templates = [event_templates(e, group.channels, group.window_length)
                         for e in self._events]
            for by_channel, of_event in zip(templates_by_event, templates):
                by_channel.update(zip(group.channels, of_event))
            layout = window_layout(group)
            correlation = SlidingCorrelation(templates, min_contrast=config.min_contrast,
                                             window=layout.window)
            rate_group = _RateGroup(
                self.DeclareDiscreteState(correlation.initial_state()), correlation, layout,
                self.DeclareVectorInputPort(f"{group.name}_window_position",
                                            layout.position_size),
                self.DeclareVectorInputPort(f"{group.name}_window_buffer",
                                            layout.buffer_size),
                slice(group.channels[0], group.channels[-1] + 1))
            self.DeclarePeriodicDiscreteUpdateEvent(
                1.0 / group.rate_hz, 0.0, functools.partial(self._update, rate_group))
            self._groups.append(rate_group)
        self._check_matchable(templates_by_event)
        state = {self.xd_ticket()}
        self._scores_port = self.DeclareVectorOutputPort(
            "scores", len(CHANNEL_NAMES), self._calc_scores, prerequisites_of_calc=state)
        self._match_port = self.DeclareVectorOutputPort(
            "match", 1, self._calc_match, prerequisites_of_calc=state | {
                self.input_port_ticket(self._expected_port.get_index())})
        self._scored_event_port = self.DeclareVectorOutputPort(
            "scored_event", 1, self._calc_scored_event, prerequisites_of_calc=state)

    @staticmethod
    def transition_indices(transitions: Iterable[str]) -> dict[str, int]:
        """{transition: index} for a matcher built with events of these transitions."""
        return {name: index for index, name in
                enumerate(sorted(transitions, key=transition_order))}

    @property
    def transitions(self) -> tuple[str, ...]:
        """The events' transitions, by index."""
        return self._transitions

    def event_index(self, transition: str) -> int:
        """Index to put on `expected_event` to check the event of `transition`."""
        if transition not in self._transitions:
            raise ValueError(f"no memorized event for '{transition}'; the matcher has "
                             f"{list(self._transitions)}")
        return self._transitions.index(transition)

    @staticmethod
    def _ordered_events(events: Mapping[str, MemorizedEvent]) -> list[MemorizedEvent]:
        if not events:
            raise ValueError("the matcher needs at least one memorized event")
        for transition, event in events.items():
            if transition != event.transition:
                raise ValueError(f"events['{transition}'] is the event of "
                                 f"'{event.transition}'")
        ordered = sorted(events.values(), key=lambda e: transition_order(e.transition))
        for attribute in ("object_name", "window_s"):
            values = {getattr(e, attribute) for e in ordered}
            if len(values) != 1:
                raise ValueError(f"the events differ in {attribute}: {sorted(values)}")
        return ordered

    def _check_matchable(self, templates_by_event: list[dict[int, np.ndarray]]) -> None:
        """Refuse events that Eq. 3 could never match, or that a flat window would."""
        for event, by_channel in zip(self._events, templates_by_event):
            templates = [by_channel[c] for c in range(len(CHANNEL_NAMES))]
            zero = [CHANNEL_NAMES[c] for c, y in enumerate(templates) if not np.any(y)]
            if zero:
                raise ValueError(f"event '{event.transition}' of '{event.object_name}' has "
                                 f"all-zero channels {zero}: Eq. 3 could never match them")
            if all(template_is_flat(y, self._config.min_contrast)[0] for y in templates):
                raise ValueError(
                    f"event '{event.transition}' of '{event.object_name}' is flat on every "
                    f"channel (contrast below {self._config.min_contrast}): it carries no "
                    "event and a steady signal would match it")

    def _expected_event(self, context) -> int:
        value = self._expected_port.Eval(context)[0]
        event = self._event_of_value.get(value)  # None for NaN, fractions, out of range
        if event is None:
            raise ValueError(
                f"expected_event {value} is not -1 or an event index 0..{len(self._events) - 1}"
                f" ({', '.join(f'{i}: {t}' for i, t in enumerate(self._transitions))})")
        return event

    def _update(self, group, context, discrete_state):
        position = group.position_port.Eval(context)  # the window before this tick's sample
        samples, missing = entering_samples(
            self._channels_port.Eval(context), group.channels,
            lambda: group.layout.newest_in(position, group.buffer_port.Eval(context)))
        group.correlation.slide(
            discrete_state.get_mutable_value(group.state_index), position, samples,
            lambda: group.layout.window_after(position, group.buffer_port.Eval(context),
                                              samples),
            self._expected_event(context), missing)

    def _group_states(self, context):
        for group in self._groups:
            yield group, context.get_discrete_state(group.state_index).value()

    def _calc_scores(self, context, output):
        scores = np.empty(len(CHANNEL_NAMES))
        for group, state in self._group_states(context):
            scores[group.channels] = group.correlation.scores(state)
        output.SetFromVector(scores)

    def _scored_event(self, context) -> int:
        events = {group.correlation.active_event(state)
                  for group, state in self._group_states(context)}
        return events.pop() if len(events) == 1 else NO_EVENT

    def _calc_scored_event(self, context, output):
        output.SetAtIndex(0, self._scored_event(context))

    def _calc_match(self, context, output):
        expected = self._expected_event(context)
        scores = self._scores_port.Eval(context)
        matched = (expected != NO_EVENT and self._scored_event(context) == expected
                   and bool(np.all(scores > self._thresholds)))
        output.SetAtIndex(0, 1.0 if matched else 0.0)


@dataclasses.dataclass(frozen=True)
class EventMatcherSystems:
    """An event matcher's two systems in a diagram (add_event_matcher)."""
    normalizer: WindowNormalizer
    scorer: EventScorer


def add_event_matcher(builder, events: Mapping[str, MemorizedEvent],
                      config: EventMatcherConfig | None = None, *,
                      channels=None) -> EventMatcherSystems:
    """Adds the paper's Fig. 3 comparison to `builder`: a WindowNormalizer
    (`window_normalizer`) whose windows an EventScorer (`event_scorer`) scores.

    channels: an output port of the four channels, connected to both (else the caller
    connects their `channels` inputs). The scorer's `expected_event` input and its
    `scores`, `match` and `scored_event` outputs are the caller's to connect.
    """
    config = dataclasses.replace(config or EventMatcherConfig())
    scorer = builder.AddNamedSystem("event_scorer", EventScorer(events, config))
    normalizer = builder.AddNamedSystem(
        "window_normalizer", WindowNormalizer(window_normalizer_config(events, config)))
    for group in normalizer.config.rate_groups():
        for part in ("position", "buffer"):
            name = f"{group.name}_window_{part}"
            builder.Connect(normalizer.GetOutputPort(name), scorer.GetInputPort(name))
    if channels is not None:
        builder.Connect(channels, normalizer.GetInputPort("channels"))
        builder.Connect(channels, scorer.GetInputPort("channels"))
    return EventMatcherSystems(normalizer, scorer)


class EventMatcher(Diagram):
    """Eq. 3 scores of the live channels' windows against the expected memorized event; its
    match: the paper's Fig. 3 path from the channels to the state machine as one system,

        channels -> WindowNormalizer (`window_normalizer`: the last window_s of each
                    channel, the one copy of the live windows, held in its Context)
                 -> EventScorer (`event_scorer`: Eq. 3 against the expected event).

    (`add_event_matcher` adds the two to a diagram of one's own, as the grasp controller
    does.) Constructed with one object's memorized events; their grasp order
    (transitions.py) numbers them 0, 1, ... (see `transition_indices`). Every tick of a
    channel's rate, the channel's live window of the events' window_s slides by one sample
    and is scored, by an exact streaming update held in the Context, against the event
    selected by `expected_event`; only that event is checked. When the expected event
    changes, the correlations are rebuilt from the window at the next tick of each rate.

    .. pydrake_system::

        name: EventMatcher
        input_ports:
        - channels
        - expected_event
        output_ports:
        - scores
        - match
        - scored_event

    Ports:
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2), sampled at
            config.sa_rate_hz (SA) and config.ra_rate_hz (RA).
        expected_event: [index] of the event to check, or -1 for none.
        scores: the four channels' scores in [-1, 1]; 0 when no event is expected, before
            a full window has been sampled, or for a channel whose live window is too flat
            to carry an event.
        match: [1.0] when every channel's score exceeds its threshold and the scores are
            for the event now expected, else [0.0]. It depends directly on expected_event,
            so one tick after the expected event changes it cannot report the old event.
        scored_event: [index] of the event the scores refer to, -1 for none or while the
            SA and RA scores refer to different events.

    The normaliser's max-normalised windows (`sa_window`, `ra_window`) are read from
    `normalizer`, with its own context (`normalizer.GetMyContextFromRoot`).
    """

    def __init__(self, events: Mapping[str, MemorizedEvent],
                 config: EventMatcherConfig | None = None):
        super().__init__()
        builder = DiagramBuilder()
        systems = add_event_matcher(builder, events, config)
        builder.ExportInput(systems.normalizer.GetInputPort("channels"), "channels")
        builder.ConnectInput("channels", systems.scorer.GetInputPort("channels"))
        builder.ExportInput(systems.scorer.GetInputPort("expected_event"), "expected_event")
        for name in ("scores", "match", "scored_event"):
            builder.ExportOutput(systems.scorer.GetOutputPort(name), name)
        builder.BuildInto(self)
        self._systems = systems

    transition_indices = staticmethod(EventScorer.transition_indices)

    @property
    def normalizer(self) -> WindowNormalizer:
        """The WindowNormalizer whose windows are scored."""
        return self._systems.normalizer

    @property
    def scorer(self) -> EventScorer:
        return self._systems.scorer

    @property
    def transitions(self) -> tuple[str, ...]:
        """The events' transitions, by index."""
        return self._systems.scorer.transitions

    def event_index(self, transition: str) -> int:
        """Index to put on `expected_event` to check the event of `transition`."""
        return self._systems.scorer.event_index(transition)
