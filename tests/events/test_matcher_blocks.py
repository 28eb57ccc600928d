"""The EventMatcher in 10 ms blocks (EventMatcherConfig.block_s) against the same matcher
taking one sample per update, fed the same synthetic grasps."""

import dataclasses

import numpy as np
import pytest
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, TrajectorySource

from tegrasp_drake.events.event_matcher import EventMatcher, EventMatcherConfig
from tegrasp_drake.events.extraction import extract_memorized_events
from tegrasp_drake.events.replay import channels_trajectory
from tegrasp_drake.events.synthetic import SyntheticGraspConfig, synthetic_grasp
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.tactile.window_normalizer import ConnectWindowChannels

from tests.sample_stream import outputs_after_updates
from tests.events.test_matcher import NOISY, run_grasp_sequence

BLOCK_S = 0.01
TICK_S = 0.001
OUTPUTS = ("sa_window", "ra_window", "scores", "match", "scored_event")


def events_at(sa_rate_hz: float):
    return extract_memorized_events(synthetic_grasp(SyntheticGraspConfig(),
                                                    sa_rate_hz=sa_rate_hz),
                                    object_name="box", sa_rate_hz=sa_rate_hz,
                                    ra_rate_hz=1000.0, package_versions={})


def per_sample_and_in_blocks(live: SyntheticGraspConfig, sa_rate_hz: float, event: str):
    """Every output of both matchers, expecting `event` throughout, just after every tick:
    {name: (per-sample array, in-blocks array)} (ticks x port size)."""
    events = events_at(sa_rate_hz)
    builder = DiagramBuilder()
    source = builder.AddSystem(TrajectorySource(channels_trajectory(
        synthetic_grasp(live, sa_rate_hz=sa_rate_hz))))
    matchers = []
    for block_s in (0.0, BLOCK_S):
        matcher = builder.AddSystem(EventMatcher(events, EventMatcherConfig(
            sa_rate_hz=sa_rate_hz, block_s=block_s)))
        ConnectWindowChannels(builder, matcher, source.get_output_port())
        expected = builder.AddSystem(ConstantVectorSource([matcher.event_index(event)]))
        builder.Connect(expected.get_output_port(), matcher.GetInputPort("expected_event"))
        matchers.append(matcher)
    ticks = np.arange(int(round(live.duration_s / TICK_S)) - 1) * TICK_S
    values = outputs_after_updates(builder.Build(), [
        m.GetOutputPort(name) for name in OUTPUTS for m in matchers], ticks, period_s=TICK_S)
    return {name: (values[2 * k], values[2 * k + 1]) for k, name in enumerate(OUTPUTS)}


@pytest.mark.parametrize("sa_rate_hz", [100.0, 1000.0])
@pytest.mark.parametrize("event", REQUIRED_TRANSITIONS)
def test_blocks_equal_the_per_sample_matcher_at_every_block_boundary(sa_rate_hz, event):
    both = per_sample_and_in_blocks(NOISY, sa_rate_hz, event)
    per_tick_match = both["match"][0][:, 0]
    assert per_tick_match.any()  # the event is matched at some ticks
    block = int(round(BLOCK_S / TICK_S))
    ends = np.arange(0, len(per_tick_match), block)  # ticks that end a block
    for name in ("sa_window", "ra_window", "scores", "scored_event"):
        # The same pushes and slides in the same order: the same floats.
        per_sample, in_blocks = both[name]
        np.testing.assert_array_equal(in_blocks[ends], per_sample[ends], err_msg=name)
    # At a block's end the block matcher reports a match exactly when the per-sample
    # matcher matched after any of the block's ticks (with SA at 100 Hz, as the SA channels
    # passed at that tick), and holds it until the next block's end.
    matched_in_block = [per_tick_match[max(0, end - block + 1):end + 1].any()
                        for end in ends]
    in_blocks_match = both["match"][1][:, 0]
    np.testing.assert_array_equal(in_blocks_match[ends], matched_in_block)
    for end in ends[:-1]:
        assert np.all(in_blocks_match[end:end + block] == in_blocks_match[end])


@pytest.mark.parametrize("sa_rate_hz", [100.0, 1000.0])
@pytest.mark.parametrize("live", [NOISY, dataclasses.replace(
    NOISY, contact_s=1.3, place_s=3.3, duration_s=4.5,
    sensors=dataclasses.replace(NOISY.sensors, ra_delay_s=0.03, right_delay_s=0.02))],
    ids=["noisy", "shifted"])
def test_blocks_match_each_event_at_most_one_block_after_the_per_sample_matcher(
        sa_rate_hz, live):
    def match_times(block_s):
        return run_grasp_sequence(
            TrajectorySource(channels_trajectory(synthetic_grasp(live, sa_rate_hz=sa_rate_hz))),
            EventMatcherConfig(sa_rate_hz=sa_rate_hz, block_s=block_s),
            t_end=live.duration_s - 0.2)
    per_sample, in_blocks = match_times(0.0), match_times(BLOCK_S)
    assert list(per_sample) == list(in_blocks) == list(REQUIRED_TRANSITIONS)
    for transition, time in per_sample.items():
        # Both are read half a tick after a tick; the block adds at most block - 1 ticks.
        assert time - 1e-9 <= in_blocks[transition] <= time + BLOCK_S - TICK_S + 1e-9, \
            transition
