"""Read batches (tactile/read_batch.py): how many samples a tick takes, the held register of
C++ systems, and the EventMatcher in read batches against the same matcher taking one
sample per update, both read by a stand-in for the state machine at its tick."""

import numpy as np
import pytest
from pydrake.common.value import AbstractValue
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import TrajectorySource

from tegrasp_drake.events.event_matcher import EventMatcher, EventMatcherConfig
from tegrasp_drake.events.replay import channels_trajectory
from tegrasp_drake.events.synthetic import synthetic_grasp
from tegrasp_drake.events.transitions import NO_EVENT
from tegrasp_drake.tactile.read_batch import (AddHeldSampleRegister, batch_first_sample,
                                              batch_update_offset, samples_per_read)
from tegrasp_drake.tactile.window_normalizer import ConnectWindowChannels

from tests.sample_stream import AddSampleStream
from tests.events.test_matcher import EVENTS, NOISY

RA_PERIOD_S = 0.001
TICK_S = 0.005  # the state machine's default tick
OUTPUTS = ("sa_window", "ra_window", "scores", "match", "scored_event")


def test_a_tick_of_five_ms_takes_five_1khz_samples_and_none_of_the_taxels():
    assert samples_per_read(1000.0, 0.005) == 5
    assert samples_per_read(1000.0, 0.010) == 10
    assert samples_per_read(108.0, 0.005) == 1  # less than one taxel sample a tick
    assert samples_per_read(1000.0, 0.0) == 1  # no reader's tick
    assert samples_per_read(1000.0, 0.0025) == 1  # not a whole number of samples


def test_the_batch_update_falls_just_before_each_tick_and_starts_at_its_first():
    offset = batch_update_offset(1000.0, TICK_S)
    assert offset == pytest.approx(TICK_S - 0.00025)
    for k in range(4):
        assert batch_first_sample(offset + k * TICK_S, 1000.0, TICK_S, 5) == 5 * k


def test_the_held_register_holds_the_last_samples_oldest_first_between_sample_times():
    stream = np.arange(40.0).reshape(20, 2) * [1.0, -1.0]  # row k: the sample at k T
    builder = DiagramBuilder()
    port = AddSampleStream(builder, np.hstack([np.zeros((20, 1)), stream]), RA_PERIOD_S)
    register = AddHeldSampleRegister(builder, port, samples=3, sample_period_s=RA_PERIOD_S,
                                     entries=[1, 2], name="register")
    diagram = builder.Build()
    simulator = Simulator(diagram)
    for k in range(2, 15):
        simulator.AdvanceTo((k + 0.5) * RA_PERIOD_S)  # between the samples at k and k + 1
        held = register.Eval(register.get_system().GetMyContextFromRoot(
            simulator.get_context()))
        np.testing.assert_array_equal(held, stream[k - 2:k + 1].ravel())


class TickedExpectation(LeafSystem):
    """A stand-in for the grasp state machine: at each tick, in an unrestricted update as
    the machine's, it reads the matcher's match and expects the next event after a match or
    after `patience` ticks (the events in turn, then none, then again). It records, per
    tick, what it read."""

    def __init__(self, n_events: int, patience: int):
        super().__init__()
        self._order = list(range(n_events)) + [NO_EVENT]
        self._patience = patience
        self._match = self.DeclareVectorInputPort("match", 1)
        self._scores = self.DeclareVectorInputPort("scores", 4)
        self._state = self.DeclareAbstractState(AbstractValue.Make((0, 0, ())))
        self.DeclarePeriodicUnrestrictedUpdateEvent(TICK_S, 0.0, self._tick)
        self.DeclareVectorOutputPort(
            "expected_event", 1,
            lambda context, output: output.SetAtIndex(0, self._order[self._now(context)[0]]),
            prerequisites_of_calc={self.abstract_state_ticket(self._state)})

    def _now(self, context):
        return context.get_abstract_state(self._state).get_value()

    def readings(self, context):
        return self._now(context)[2]

    def _tick(self, context, state):
        position, ticks, read = self._now(context)
        match = self._match.Eval(context)[0]
        read = read + ((context.get_time(), match, tuple(self._scores.Eval(context))),)
        ticks += 1
        if match or ticks >= self._patience:
            position, ticks = (position + 1) % len(self._order), 0
        state.get_mutable_abstract_state(self._state).set_value((position, ticks, read))


def matcher_read_by_ticks(read_period_s: float, patience: int, t_end: float):
    """One matcher (read_period_s) fed the noisy synthetic grasp, read by a
    TickedExpectation: (what the stand-in read at every tick, every output of the matcher
    just before each tick)."""
    builder = DiagramBuilder()
    source = builder.AddSystem(TrajectorySource(channels_trajectory(synthetic_grasp(NOISY))))
    matcher = builder.AddSystem(EventMatcher(EVENTS, EventMatcherConfig(
        read_period_s=read_period_s)))
    ConnectWindowChannels(builder, matcher, source.get_output_port())
    machine = builder.AddSystem(TickedExpectation(len(EVENTS), patience))
    builder.Connect(matcher.GetOutputPort("match"), machine.GetInputPort("match"))
    builder.Connect(matcher.GetOutputPort("scores"), machine.GetInputPort("scores"))
    builder.Connect(machine.get_output_port(), matcher.GetInputPort("expected_event"))
    simulator = Simulator(builder.Build())
    root = simulator.get_mutable_context()
    outputs = []
    for k in range(1, int(round(t_end / TICK_S))):
        simulator.AdvanceTo(k * TICK_S - 0.1 * RA_PERIOD_S)  # the state the tick reads
        context = matcher.GetMyContextFromRoot(root)
        outputs.append([matcher.GetOutputPort(name).Eval(context).copy() for name in OUTPUTS])
    return machine.readings(machine.GetMyContextFromRoot(root)), outputs


@pytest.mark.parametrize("patience", [40, 300])
def test_read_batches_give_the_state_machine_what_the_per_sample_matcher_gives(patience):
    per_sample_reads, per_sample = matcher_read_by_ticks(0.0, patience, 3.6)
    batched_reads, batched = matcher_read_by_ticks(TICK_S, patience, 3.6)
    assert any(match for _, match, _ in per_sample_reads)  # it matched some events
    assert batched_reads == per_sample_reads  # the same floats at every tick
    for k, (expected, got) in enumerate(zip(per_sample, batched)):
        for name, a, b in zip(OUTPUTS, expected, got):
            np.testing.assert_array_equal(b, a, err_msg=f"{name} before tick {k + 1}")


def test_a_matcher_in_read_batches_takes_its_1khz_samples_in_one_update_per_tick():
    batched = EventMatcher(EVENTS, EventMatcherConfig(read_period_s=TICK_S))
    per_sample = EventMatcher(EVENTS, EventMatcherConfig())
    ra_batched, ra_per_sample = (next(w for w in m.rate_windows if w.group.name == "ra")
                                 for m in (batched, per_sample))
    assert ra_batched.before_read and ra_batched.block_samples == 5
    assert not ra_per_sample.before_read and ra_per_sample.block_samples == 1
    sa = next(w for w in batched.rate_windows if w.group.name == "sa")
    assert not sa.before_read  # 100 Hz: less than one sample per tick
