"""EventSequencer through its ports."""

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.events.event_sequencer import EventSequencer, next_sequence_step


class Harness:
    """EventSequencer with `match` fixed by the test."""

    def __init__(self, event_indices=(0, 1, 3), armed_from_s=None):
        builder = DiagramBuilder()
        self.sequencer = builder.AddSystem(EventSequencer(event_indices,
                                                          armed_from_s=armed_from_s))
        builder.ExportInput(self.sequencer.GetInputPort("match"), "match")
        self.diagram = builder.Build()
        self.simulator = Simulator(self.diagram)
        self.set_match(0.0)

    @property
    def context(self):
        return self.sequencer.GetMyContextFromRoot(self.simulator.get_context())

    def set_match(self, value):
        self.diagram.get_input_port(0).FixValue(self.simulator.get_mutable_context(), [value])

    def output(self, name):
        return self.sequencer.GetOutputPort(name).Eval(self.context).copy()

    def match_at(self, time):
        """A match seen by the tick at `time` only (the test steps between ticks)."""
        self.simulator.AdvanceTo(time - 0.0005)
        self.set_match(1.0)
        self.simulator.AdvanceTo(time + 0.0005)
        self.set_match(0.0)


def test_ports_have_stable_names_and_sizes():
    sequencer = EventSequencer([0, 1, 3])
    assert [(port.get_name(), port.size()) for port in
            (sequencer.get_input_port(i) for i in range(sequencer.num_input_ports()))] == [
                ("match", 1)]
    assert [(port.get_name(), port.size()) for port in
            (sequencer.get_output_port(i) for i in range(sequencer.num_output_ports()))] == [
                ("expected_event", 1), ("fire_times", 3)]


def test_outputs_do_not_depend_directly_on_match():
    sequencer = EventSequencer([0, 1])
    assert not any(sequencer.HasDirectFeedthrough(0, output)
                   for output in range(sequencer.num_output_ports()))


def test_each_match_advances_to_the_next_event_and_records_its_time():
    harness = Harness()
    harness.simulator.AdvanceTo(0.0505)
    assert harness.output("expected_event")[0] == 0
    assert np.all(np.isnan(harness.output("fire_times")))
    harness.match_at(0.1)
    assert harness.output("expected_event")[0] == 1
    harness.match_at(0.2)
    assert harness.output("expected_event")[0] == 3
    harness.match_at(0.35)
    assert harness.output("expected_event")[0] == -1
    harness.match_at(0.4)  # nothing left to expect
    np.testing.assert_allclose(harness.output("fire_times"), [0.1, 0.2, 0.35], atol=1e-12)
    assert harness.sequencer.fire_times(harness.context) == pytest.approx([0.1, 0.2, 0.35])


def test_a_match_held_on_advances_one_event_per_tick():
    harness = Harness()
    harness.simulator.AdvanceTo(0.0105)
    harness.set_match(1.0)
    harness.simulator.AdvanceTo(0.0125)
    assert harness.output("expected_event")[0] == 3
    np.testing.assert_allclose(harness.output("fire_times")[:2], [0.011, 0.012], atol=1e-12)
    assert np.isnan(harness.output("fire_times")[2])


@pytest.mark.parametrize("step, matched, expected", [
    (0, False, 0), (0, True, 1), (2, True, 3), (3, True, 3), (3, False, 3)])
def test_next_sequence_step(step, matched, expected):
    assert next_sequence_step(step, matched, n_events=3) == expected


@pytest.mark.parametrize("event_indices", [[], [0, -1], [0.5]])
def test_invalid_event_indices_are_refused(event_indices):
    with pytest.raises(ValueError, match="event_indices"):
        EventSequencer(event_indices)


def test_an_event_is_neither_expected_nor_fired_before_it_is_armed():
    harness = Harness(event_indices=(0, 2), armed_from_s=(0.0, 0.0105))
    harness.set_match(1.0)  # the matcher reports a match at every tick
    harness.simulator.AdvanceTo(0.0045)
    assert harness.output("expected_event")[0] == -1  # event 0 fired; event 2 not armed
    times = harness.output("fire_times")
    assert times[0] == pytest.approx(0.0) and np.isnan(times[1])
    harness.simulator.AdvanceTo(0.0125)
    assert harness.output("fire_times")[1] == pytest.approx(0.011)  # first tick armed


def test_arming_times_must_match_the_sequence():
    with pytest.raises(ValueError, match="one finite time"):
        EventSequencer((0, 1), armed_from_s=(0.0,))
    with pytest.raises(ValueError, match="one finite time"):
        EventSequencer((0, 1), armed_from_s=(0.0, float("nan")))
