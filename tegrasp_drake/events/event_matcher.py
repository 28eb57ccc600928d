"""EventMatcher: compares the live tactile channels with the expected memorized event."""

import dataclasses
import functools
from collections.abc import Iterable, Mapping

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.events.correlation import normalize_by_max, template_is_flat
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.tactile.sampling import rate_groups, resample_window
from tegrasp_drake.tactile.sliding_window import SLACK_FRACTION
from tegrasp_drake.events.streaming_correlation import StreamingCorrelator
from tegrasp_drake.events.transitions import NO_EVENT, transition_order


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


def _event_templates(event: MemorizedEvent, channels: tuple[int, ...],
                     length: int) -> np.ndarray:
    """The event's windows of `channels`, resampled to `length` samples, max-normalised."""
    rows = [resample_window(event.channel(CHANNEL_NAMES[c]), length)[0] for c in channels]
    return normalize_by_max(np.array(rows))


class EventMatcher(LeafSystem):
    """Eq. 3 scores of the live channels against the expected memorized event; its match.

    Constructed with one object's memorized events; their grasp order (transitions.py)
    numbers them 0, 1, ... (see `transition_indices`). Every tick of a channel's rate, the
    channel's live window of the events' window_s slides by one sample and is scored, by
    an exact streaming update held in the Context, against the event selected by
    `expected_event`; only that event is checked. When the expected event changes, the
    correlations are rebuilt from the stored windows at the next tick of each rate.

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
        # One streaming correlator, state group and periodic update per sample rate.
        self._groups = []
        templates_by_event = [{} for _ in self._events]
        for group in rate_groups(sa_rate_hz=config.sa_rate_hz, ra_rate_hz=config.ra_rate_hz,
                                 window_s=self._events[0].window_s):
            templates = [_event_templates(e, group.channels, group.window_length)
                         for e in self._events]
            for by_channel, event_templates in zip(templates_by_event, templates):
                by_channel.update(zip(group.channels, event_templates))
            correlator = StreamingCorrelator(
                templates, min_contrast=config.min_contrast,
                slack=max(1, int(group.window_length * SLACK_FRACTION)))
            index = self.DeclareDiscreteState(correlator.initial_state())
            channels = slice(group.channels[0], group.channels[-1] + 1)
            self.DeclarePeriodicDiscreteUpdateEvent(
                1.0 / group.rate_hz, 0.0,
                functools.partial(self._update, index, correlator, channels))
            self._groups.append((index, correlator, list(group.channels)))
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

    def _update(self, index, correlator, channels, context, discrete_state):
        correlator.push(discrete_state.get_mutable_value(index),
                        self._channels_port.Eval(context)[channels],
                        self._expected_event(context))

    def _group_states(self, context):
        for index, correlator, channels in self._groups:
            yield correlator, context.get_discrete_state(index).value(), channels

    def _calc_scores(self, context, output):
        scores = np.empty(len(CHANNEL_NAMES))
        for correlator, state, channels in self._group_states(context):
            scores[channels] = correlator.scores(state)
        output.SetFromVector(scores)

    def _scored_event(self, context) -> int:
        events = {correlator.active_event(state)
                  for correlator, state, _ in self._group_states(context)}
        return events.pop() if len(events) == 1 else NO_EVENT

    def _calc_scored_event(self, context, output):
        output.SetAtIndex(0, self._scored_event(context))

    def _calc_match(self, context, output):
        expected = self._expected_event(context)
        scores = self._scores_port.Eval(context)
        matched = (expected != NO_EVENT and self._scored_event(context) == expected
                   and bool(np.all(scores > self._thresholds)))
        output.SetAtIndex(0, 1.0 if matched else 0.0)
