"""EventSequencer: expects memorized events one after another, in grasp order (one armed
from a time on, as Place-Unload only in Place), for offline replays (replay.py)."""

import math
from collections.abc import Sequence

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.events.transitions import NO_EVENT
from tegrasp_drake.rig.number_text import number_text

DEFAULT_PERIOD_S = 1e-3  # one control tick at 1 kHz


def next_sequence_step(step: int, matched: bool, n_events: int) -> int:
    """The step after a tick: the next event once the expected one matched."""
    return step + 1 if matched and step < n_events else step


class EventSequencer(LeafSystem):
    """Expects `event_indices` in turn; advances on each match and records when. A periodic
    update every `period_s` reads `match`, so a fire time comes one period after its match, and
    the outputs depend only on the state (no algebraic loop with the matcher).

    .. pydrake_system::

        name: EventSequencer
        input_ports:
        - match
        output_ports:
        - expected_event
        - fire_times

    Ports:
        match: [1.0] when the expected event matched (EventMatcher's `match`), else [0.0].
        expected_event: [index] of the event now expected, -1 before it is armed and after
            the last.
        fire_times: one time [s] per event of the sequence, NaN until it fires.
    """

    def __init__(self, event_indices: Sequence[int], *, period_s: float = DEFAULT_PERIOD_S,
                 armed_from_s: Sequence[float] | None = None):
        super().__init__()
        indices = [int(index) for index in event_indices]
        if not indices or any(index < 0 or index != value
                              for index, value in zip(indices, event_indices)):
            raise ValueError(f"event_indices {list(event_indices)} must be one or more "
                             "event indices >= 0")
        if not period_s > 0.0:
            raise ValueError(f"period_s {number_text(period_s)} must be positive")
        self._event_indices = tuple(indices)
        armed = [0.0] * len(indices) if armed_from_s is None else [float(t) for t in armed_from_s]
        if len(armed) != len(indices) or not all(math.isfinite(t) for t in armed):
            raise ValueError(f"armed_from_s {number_text(armed_from_s)} must give one finite "
                             "time [s] per event of the sequence")
        self._armed_from_s = tuple(armed)
        self._match_port = self.DeclareVectorInputPort("match", 1)
        self._state_index = self.DeclareDiscreteState(
            np.concatenate([[0.0], np.full(len(indices), np.nan)]))
        self.DeclarePeriodicDiscreteUpdateEvent(period_s, 0.0, self._update)
        state = {self.discrete_state_ticket(self._state_index)}
        self._expected_port = self.DeclareVectorOutputPort(
            "expected_event", 1, self._calc_expected_event,
            prerequisites_of_calc=state | {self.time_ticket()})
        self._fire_times_port = self.DeclareVectorOutputPort(
            "fire_times", len(indices), self._calc_fire_times, prerequisites_of_calc=state)

    @property
    def event_indices(self) -> tuple[int, ...]:
        return self._event_indices

    def _state(self, context) -> np.ndarray:
        return context.get_discrete_state(self._state_index).value()

    def _armed(self, step: int, context) -> bool:
        """True when the sequence has an event at `step` and its arming time has come."""
        return step < len(self._event_indices) and \
            context.get_time() >= self._armed_from_s[step]

    def _update(self, context, discrete_state):
        state = discrete_state.get_mutable_value(self._state_index)
        step = int(state[0])
        matched = self._armed(step, context) and self._match_port.Eval(context)[0] > 0.5
        new_step = next_sequence_step(step, matched, len(self._event_indices))
        if new_step != step:
            state[0] = new_step
            state[1 + step] = context.get_time()

    def _calc_expected_event(self, context, output):
        step = int(self._state(context)[0])
        output.SetAtIndex(0, self._event_indices[step] if self._armed(step, context)
                          else NO_EVENT)

    def _calc_fire_times(self, context, output):
        output.SetFromVector(self._state(context)[1:])

    def fire_times(self, context) -> list[float | None]:
        """Fire time [s] of each event of the sequence, None if it has not fired."""
        return [None if math.isnan(t) else float(t) for t in self._state(context)[1:]]
