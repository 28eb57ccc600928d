"""The heuristic controller's triggers, hand-set thresholds in the style of Romano et al.
2011 behind the EventMatcher's ports: reach_load, each SA above contact_force_n; load_lift,
each SA above grip_fraction of the grip force; place_unload, either RA above place_ra_mps2."""

import numpy as np
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.events.transitions import NO_EVENT, REQUIRED_TRANSITIONS
from tegrasp_drake.rig.channels import CHANNEL_NAMES


class HeuristicEventDetector(LeafSystem):
    """Threshold triggers for the expected transition; load_lift compares with the
    initial `grip_force_n` [N] (a Lift-Load's raised force passes too).

    .. pydrake_system::

        name: HeuristicEventDetector
        input_ports:
        - channels
        - expected_event
        output_ports:
        - scores
        - match
        - scored_event

    channels: [sa_l, sa_r, ra_l, ra_r] [N, N, m/s^2, m/s^2]; expected_event and
    scored_event: index into REQUIRED_TRANSITIONS (-1 none); scores: each channel over its
    threshold (0 when ignored); match: [1] when the expected rule holds.
    """

    def __init__(self, config, *, grip_force_n: float):
        super().__init__()
        self._config = config
        self._grip_force = float(grip_force_n)
        self._channels = self.DeclareVectorInputPort("channels", len(CHANNEL_NAMES))
        self._expected = self.DeclareVectorInputPort("expected_event", 1)
        self.DeclareVectorOutputPort("scores", len(CHANNEL_NAMES), self._calc_scores)
        self.DeclareVectorOutputPort("match", 1, self._calc_match)
        self.DeclareVectorOutputPort(
            "scored_event", 1, lambda context, output: output.SetAtIndex(
                0, self._expected_index(context)))

    @property
    def transitions(self) -> tuple[str, ...]:
        return REQUIRED_TRANSITIONS

    def event_index(self, transition: str) -> int:
        return REQUIRED_TRANSITIONS.index(transition)

    def _expected_index(self, context) -> int:
        value = int(self._expected.Eval(context)[0])
        if not NO_EVENT <= value < len(REQUIRED_TRANSITIONS):
            raise ValueError(f"expected_event {value} is not -1 or "
                             f"0..{len(REQUIRED_TRANSITIONS) - 1}")
        return value

    def thresholds(self, transition: str) -> np.ndarray:
        """Per-channel thresholds of a transition's rule; inf for an ignored channel."""
        c = self._config
        if transition == "reach_load":
            return np.array([c.contact_force_n, c.contact_force_n, np.inf, np.inf])
        if transition == "load_lift":
            level = c.grip_fraction * self._grip_force
            return np.array([level, level, np.inf, np.inf])
        return np.array([np.inf, np.inf, c.place_ra_mps2, c.place_ra_mps2])

    def _ratios(self, index: int, context) -> np.ndarray:
        if index == NO_EVENT:
            return np.zeros(len(CHANNEL_NAMES))
        return self._channels.Eval(context) / self.thresholds(REQUIRED_TRANSITIONS[index])

    def _calc_scores(self, context, output):
        output.SetFromVector(self._ratios(self._expected_index(context), context))

    def _calc_match(self, context, output):
        index = self._expected_index(context)
        ratios = self._ratios(index, context)
        if index == NO_EVENT:
            matched = False
        elif REQUIRED_TRANSITIONS[index] == "place_unload":
            matched = bool(np.any(ratios[2:] > 1.0))
        else:
            matched = bool(np.all(ratios[:2] > 1.0))
        output.SetAtIndex(0, 1.0 if matched else 0.0)
