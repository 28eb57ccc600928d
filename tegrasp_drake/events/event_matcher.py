"""EventMatcher: the paper's Fig. 3 comparison of the live tactile channels with the
expected memorized event: a WindowNormalizer's 0.5 s windows (Sec. III-A) scored by Eq. 3
(Sec. III-B) in the same update that takes each sample."""

import dataclasses
import math
from collections.abc import Iterable, Mapping

import numpy as np

from tegrasp_drake.rig.api_boundary import check_field_values, public_api, public_dataclass
from tegrasp_drake.rig.event_matching import SCORE_RANGE, EventMatchingConfig
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import (READ_PERIOD, SAMPLE_BLOCK, SAMPLE_RATE, Range, bounded,
                                      declared_field, number_problem, real_number, within)
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.events.correlation import template_is_flat
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.ra_envelope import ra_enveloped
from tegrasp_drake.events.ra_noise_floor import add_ra_noise_floor
from tegrasp_drake.events.streaming_correlation import SlidingCorrelation
from tegrasp_drake.events.transitions import NO_EVENT, transition_order
from tegrasp_drake.tactile.sample_block import block_samples
from tegrasp_drake.tactile.sampling import resample_window
from tegrasp_drake.tactile.window_normalizer import (
    ConnectWindowChannels, RateWindow, WindowNormalizer, WindowNormalizerConfig, window_layout)



@public_dataclass
@dataclasses.dataclass
class EventMatcherConfig:
    """Sec. III-B thresholds, live rates [Hz] and gates; the controller's settings are
    declared in rig/event_matching.EventMatchingConfig."""
    sa_threshold: float = declared_field(EventMatchingConfig, "sa_threshold")
    ra_threshold: float = declared_field(EventMatchingConfig, "ra_threshold")
    # {transition: (sa, ra)} per-event thresholds in place of the two above (taxel_aware)
    event_thresholds: Mapping[str, tuple[float, float]] = dataclasses.field(
        default_factory=dict)
    min_contrast: float = bounded(0.25, low=0.0, low_open=True, below="must be positive")
    flat_template_needs_flat_window: bool = declared_field(EventMatchingConfig,
                                                           "flat_template_needs_flat_window")
    sa_rate_hz: float = within(100.0, SAMPLE_RATE)  # the sensors' rates' range
    ra_rate_hz: float = within(1000.0, SAMPLE_RATE)
    # block [s] scored in one update (0: per sample); a match shows at most a block late
    block_s: float = within(0.0, SAMPLE_BLOCK)
    # the reader's tick [s] (tactile/read_batch.py); 0: read any time (so with an RA floor)
    read_period_s: float = within(0.0, READ_PERIOD)
    ra_envelope_hz: float = declared_field(EventMatchingConfig, "ra_envelope_hz")
    # RA noise floor m + k s over the first quiet seconds (events/ra_noise_floor.py)
    ra_noise_floor_sigmas: float = declared_field(EventMatchingConfig, "ra_noise_floor_sigmas")
    ra_noise_quiet_s: float = declared_field(EventMatchingConfig, "ra_noise_quiet_s")

    def __post_init__(self):
        check_field_values(self)  # a rate or block out of range: refused before it allocates


def check_matcher_config(config: EventMatcherConfig) -> None:
    """ConfigError or TypeError naming the first field or event threshold out of range."""
    check_field_values(config, "EventMatcher: config")
    score = Range(**SCORE_RANGE)
    for transition, pair in dict(config.event_thresholds).items():
        if (not isinstance(pair, (tuple, list)) or len(pair) != 2 or not all(
                number_problem(x) is None and score.contains(real_number(x)) for x in pair)):
            raise ConfigError(f"EventMatcher: config: field 'event_thresholds.{transition}' "
                              f"must be a pair (SA, RA) of numbers in [-1, 1] "
                              f"({SCORE_RANGE['why']}), got {pair!r}")


def event_templates(event: MemorizedEvent, channels: tuple[int, ...],
                     length: int) -> np.ndarray:
    """The event's windows of `channels`, resampled to `length` samples, max-normalised."""
    rows = [resample_window(event.channel(CHANNEL_NAMES[c]), length)[0] for c in channels]
    return normalize_by_max(np.array(rows))


def window_normalizer_config(events: Mapping[str, MemorizedEvent],
                             config: EventMatcherConfig) -> WindowNormalizerConfig:
    """The windows an EventMatcher scores: the events' window_s at the config's rates."""
    return WindowNormalizerConfig(window_s=next(iter(events.values())).window_s,
                                  sa_rate_hz=config.sa_rate_hz, ra_rate_hz=config.ra_rate_hz,
                                  block_s=config.block_s, read_period_s=config.read_period_s)


class EventMatcher(WindowNormalizer):
    """The paper's Fig. 3 path: channels -> WindowNormalizer (last window_s, max-normalised)
    -> Eq. 3 against the expected event -> scores, match. Each rate's state holds its
    window, its SlidingCorrelation and a PassHistory; events are numbered in grasp order.

    .. pydrake_system::

        name: EventMatcher
        input_ports:
        - channels
        - sa_block (optional)
        - ra_block (optional)
        - expected_event
        - ra_floor (optional)
        output_ports:
        - sa_window
        - ra_window
        - scores
        - match
        - scored_event

    Ports:
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2); sa_block,
            ra_block: in blocks (ConnectWindowChannels).
        expected_event: [index] of the event to check, or -1 for none.
        ra_floor: [left, right] RA noise floor [m/s^2], with a floor or quiet template.
        sa_window, ra_window: the max-normalised windows that are scored.
        scores: the four scores in [-1, 1]; 0 with no event, a partial, too flat or
            below-floor window; 1 for a quiet template within its floor.
        match: [1.0] when every channel passes for the expected event (blocks: a block late).
        scored_event: [index] the scores refer to; -1 for none or while SA and RA disagree.
    """

    @public_api
    def __init__(self, events: Mapping[str, MemorizedEvent],
                 config: EventMatcherConfig | None = None):
        config = dataclasses.replace(config or EventMatcherConfig())
        check_matcher_config(config)
        ordered_events = self._ordered_events(events)
        normalizer_config = window_normalizer_config(events, config)
        correlations = {}
        templates_by_event = [{} for _ in ordered_events]
        for group in normalizer_config.rate_groups():
            templates = [event_templates(e, group.channels, group.window_length)
                         for e in ordered_events]
            for by_channel, of_event in zip(templates_by_event, templates):
                by_channel.update(zip(group.channels, of_event))
            correlations[group.name] = SlidingCorrelation(
                templates, min_contrast=config.min_contrast, window=window_layout(group).window,
                flat_needs_flat=config.flat_template_needs_flat_window)
        self._check_matchable(ordered_events, templates_by_event)
        reads_floor = config.ra_noise_floor_sigmas > 0 or any(
            template_is_flat(by_channel[c], config.min_contrast)[0]
            for by_channel in templates_by_event for c in RA_CHANNELS)
        if reads_floor:  # the floor is read at each sample: no read batches
            normalizer_config = dataclasses.replace(normalizer_config, read_period_s=0.0)
        block_span_s = max(block_samples(g.rate_hz, config.block_s) / g.rate_hz
                           for g in normalizer_config.rate_groups())
        self._histories = {}
        for group in normalizer_config.rate_groups():
            samples = block_samples(group.rate_hz, config.block_s)
            length = (samples if samples > 1
                      else 2 + math.ceil(2 * block_span_s * group.rate_hz))
            self._histories[group.name] = PassHistory(
                at=correlations[group.name].size, in_blocks=samples > 1, length=length)
        super().__init__(normalizer_config, window_states={
            name: np.concatenate([correlation.initial_state(),
                                  self._histories[name].initial_state()])
            for name, correlation in correlations.items()})
        self._correlations = correlations
        self._events = ordered_events
        self._transitions = tuple(e.transition for e in self._events)
        unknown = set(config.event_thresholds) - set(self._transitions)
        if unknown:
            raise ValueError(f"thresholds for transitions without an event: {sorted(unknown)}")
        self._thresholds = np.array([
            [sa] * len(SA_CHANNELS) + [ra] * len(RA_CHANNELS) for sa, ra in (
                config.event_thresholds.get(t, (config.sa_threshold, config.ra_threshold))
                for t in self._transitions)])
        self._group_thresholds = {window.group.name: [
            row[window.channels].tolist() for row in self._thresholds]
            for window in self.rate_windows}
        self._event_of_value = {float(event): event
                                for event in range(NO_EVENT, len(self._events))}
        self._expected_port = self.DeclareVectorInputPort("expected_event", 1)
        self._gate_events = config.ra_noise_floor_sigmas > 0
        self._floor_port = (self.DeclareVectorInputPort("ra_floor", len(RA_CHANNELS))
                            if reads_floor else None)
        scores_state = {self.discrete_state_ticket(window.state)
                        for window in self.rate_windows}
        self.DeclareVectorOutputPort(
            "scores", len(CHANNEL_NAMES), self._calc_scores,
            prerequisites_of_calc=scores_state)
        self._match_port = self.DeclareVectorOutputPort(
            "match", 1, self._calc_match, prerequisites_of_calc=scores_state | {
                self.input_port_ticket(self._expected_port.get_index())})
        self._scored_event_port = self.DeclareVectorOutputPort(
            "scored_event", 1, self._calc_scored_event, prerequisites_of_calc=scores_state)

    @staticmethod
    def transition_indices(transitions: Iterable[str]) -> dict[str, int]:
        """{transition: index} for a matcher built with events of these transitions."""
        return {name: index for index, name in
                enumerate(sorted(transitions, key=transition_order))}

    @property
    def has_ra_floor(self) -> bool:
        return self._floor_port is not None

    @property
    def transitions(self) -> tuple[str, ...]:
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

    @staticmethod
    def _check_matchable(events: list[MemorizedEvent],
                         templates_by_event: list[dict[int, np.ndarray]]) -> None:
        """Refuse events that Eq. 3 could never match (an all-zero channel)."""
        for event, by_channel in zip(events, templates_by_event):
            templates = [by_channel[c] for c in range(len(CHANNEL_NAMES))]
            zero = [CHANNEL_NAMES[c] for c, y in enumerate(templates) if not np.any(y)]
            if zero:
                raise ValueError(f"event '{event.transition}' of '{event.object_name}' has "
                                 f"all-zero channels {zero}: Eq. 3 could never match them")

    def _expected_event(self, context) -> int:
        value = self._expected_port.Eval(context)[0]
        event = self._event_of_value.get(value)  # None for NaN, fractions, out of range
        if event is None:
            raise ValueError(
                f"expected_event {number_text(value)} is not -1 or an event index "
                f"0..{len(self._events) - 1}"
                f" ({', '.join(f'{i}: {t}' for i, t in enumerate(self._transitions))})")
        return event

    def _after_push(self, window: RateWindow, state: np.ndarray,
                    pushed: tuple[np.ndarray, int, bool], missing: list[bool] | None,
                    context, sample_time: float) -> None:
        """Slides the rate's correlation by the pushed samples; records whether it passed."""
        rows, offset, full = pushed
        name = window.group.name
        expected = self._expected_event(context)
        scores = self._correlations[name].slide(state, rows, offset, full, expected, missing)
        if self._floor_port is not None and full and expected != NO_EVENT:
            floor = self._floor_port.Eval(context).tolist()
            scores = self._correlations[name].gate_below(state, [
                floor[RA_CHANNELS.index(c)] if c in RA_CHANNELS else None
                for c in window.group.channels], gate_events=self._gate_events)
        passed = (expected != NO_EVENT and full and all(
            score > threshold for score, threshold in
            zip(scores.tolist(), self._group_thresholds[name][expected])))
        self._histories[name].add(state, sample_time, expected, passed)

    def _correlation_states(self, context):
        """(window, its correlation, their state vector) per rate group."""
        for window in self.rate_windows:
            yield (window, self._correlations[window.group.name],
                   context.get_discrete_state(window.state).value())

    def _calc_scores(self, context, output):
        scores = np.empty(len(CHANNEL_NAMES))
        for window, correlation, state in self._correlation_states(context):
            scores[window.channels] = correlation.scores(state)
        output.SetFromVector(scores)

    def _scored_event(self, context) -> int:
        events = {correlation.active_event(state)
                  for _, correlation, state in self._correlation_states(context)}
        return events.pop() if len(events) == 1 else NO_EVENT

    def _calc_scored_event(self, context, output):
        output.SetAtIndex(0, self._scored_event(context))

    def _calc_match(self, context, output):
        expected = self._expected_event(context)
        matched = (expected != NO_EVENT and self._scored_event(context) == expected
                   and self._matched_at_a_sample(context, expected))
        output.SetAtIndex(0, 1.0 if matched else 0.0)

    def _matched_at_a_sample(self, context, expected: int) -> bool:
        """Whether every rate passed for `expected` at one instant (a sample of a blocked
        rate's last block, or else the latest samples)."""
        entries = {window.group.name: self._histories[window.group.name].entries(state)
                   for window, _, state in self._correlation_states(context)}
        if not all(entries.values()):
            return False  # a rate has taken no sample yet
        blocked = [name for name, history in self._histories.items() if history.in_blocks]
        instants = ([time for name in blocked for time, _, _ in entries[name]] if blocked
                    else [max(rows[-1][0] for rows in entries.values())])
        return any(all(passed_at(rows, instant, expected) for rows in entries.values())
                   for instant in instants)


@dataclasses.dataclass(frozen=True)
class PassHistory:
    """The last `length` samples' [time [s], expected event, passed] in a rate's state from
    entry `at`, oldest first; in_blocks: the history is the rate's last block."""
    at: int
    in_blocks: bool
    length: int

    def initial_state(self) -> np.ndarray:
        return np.tile([-math.inf, float(NO_EVENT), 0.0], self.length)

    def add(self, state: np.ndarray, time: float, event: int, passed: bool) -> None:
        rows = state[self.at:self.at + 3 * self.length].reshape(self.length, 3)
        rows[:-1] = rows[1:]
        rows[-1] = (time, event, 1.0 if passed else 0.0)

    def entries(self, state: np.ndarray) -> list[tuple[float, int, bool]]:
        """The history's (time, event, passed), oldest first, samples taken only."""
        rows = state[self.at:self.at + 3 * self.length].reshape(self.length, 3).tolist()
        return [(t, int(e), p > 0.0) for t, e, p in rows if t > -math.inf]


# coinciding sample times of two rates, computed apart, are equal within this [s]
_SAME_INSTANT_S = 1e-7


def passed_at(entries, instant: float, event: int) -> bool:
    """Whether the latest entry at or before `instant` [s] passed for `event`."""
    latest = None
    for time, scored, passed in entries:
        if time <= instant + _SAME_INSTANT_S:
            latest = (scored, passed)
    return latest is not None and latest[0] == event and latest[1]


def add_event_matcher(builder, events: Mapping[str, MemorizedEvent],
                      config: EventMatcherConfig | None = None, *,
                      channels=None) -> EventMatcher:
    """Adds the paper's Fig. 3 comparison to `builder`: an EventMatcher (`event_matcher`).

    channels: the four channels' output port, or None (the caller connects them); needed
    for an RA envelope (filters events and channels) and a noise floor (feeds `ra_floor`)."""
    raw_channels = channels
    if config is not None and config.ra_envelope_hz:
        events, channels = ra_enveloped(builder, events, channels, config)
    matcher = builder.AddNamedSystem("event_matcher", EventMatcher(events, config))
    if channels is not None:
        ConnectWindowChannels(builder, matcher, channels)
    if matcher.has_ra_floor:
        if raw_channels is None:
            raise ValueError("the RA noise floor needs the channels' output port to measure "
                             "(add_event_matcher(..., channels=PORT))")
        floor = add_ra_noise_floor(builder, raw_channels, config or EventMatcherConfig())
        builder.Connect(floor, matcher.GetInputPort("ra_floor"))
    return matcher
