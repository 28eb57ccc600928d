"""EventMatcher through its ports, fed with synthetic grasps through a `channels` source."""

import dataclasses

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.event_matcher import EventMatcher, EventMatcherConfig
from tegrasp_drake.events.extraction import extract_memorized_events
from tegrasp_drake.events.replay import channels_trajectory
from tegrasp_drake.events.synthetic import (SyntheticGraspConfig, SyntheticSensorsConfig,
                                             synthetic_grasp)
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.tactile.window_normalizer import ConnectWindowChannels

from tests.one_system_matcher import replay_both

IDEAL = SyntheticGraspConfig()
# N, m/s^2 per axis
NOISY = SyntheticGraspConfig(sensors=SyntheticSensorsConfig(sa_noise_n=0.05, ra_noise=0.2, seed=7))
EVENTS = extract_memorized_events(synthetic_grasp(IDEAL), object_name="box",
                                  sa_rate_hz=100.0, ra_rate_hz=1000.0,
                                  package_versions={})


class Harness:
    """source -> EventMatcher, with expected_event fixed by the test."""

    def __init__(self, source, config=EventMatcherConfig(), events=EVENTS):
        builder = DiagramBuilder()
        source = builder.AddSystem(source)
        self.matcher = builder.AddSystem(EventMatcher(events, config))
        ConnectWindowChannels(builder, self.matcher, source.get_output_port())
        builder.ExportInput(self.matcher.GetInputPort("expected_event"), "expected_event")
        self.diagram = builder.Build()
        self.simulator = Simulator(self.diagram)
        self.expect(-1)

    @property
    def context(self):
        return self.matcher.GetMyContextFromRoot(self.simulator.get_context())

    def expect(self, event):
        index = event if isinstance(event, int) else self.matcher.event_index(event)
        self.diagram.get_input_port(0).FixValue(self.simulator.get_mutable_context(), [index])

    def output(self, name):
        return self.matcher.GetOutputPort(name).Eval(self.context).copy()

    def run(self, t_end, step=0.001):
        """Advance to t_end by steps, halfway between 1 kHz ticks, so that each step's
        outputs follow the updates of every tick before it; yields (time, scores, match)."""
        k = int(np.floor(self.simulator.get_context().get_time() / step - 0.5 + 1e-9)) + 1
        while (k + 0.5) * step <= t_end + 1e-12:
            time = (k + 0.5) * step
            self.simulator.AdvanceTo(time)
            yield time, self.output("scores"), self.output("match")[0]
            k += 1


def replay(config, **options):
    return TrajectorySource(channels_trajectory(synthetic_grasp(config, **options)))


@pytest.mark.parametrize("block_s, ra_block", [(0.0, 1), (0.01, 10)])
def test_ports_have_stable_names_and_sizes(block_s, ra_block):
    matcher = EventMatcher(EVENTS, EventMatcherConfig(block_s=block_s))
    assert [(matcher.get_input_port(i).get_name(), matcher.get_input_port(i).size())
            for i in range(matcher.num_input_ports())] == [
                ("channels", 4), ("sa_block", 2), ("ra_block", 2 * ra_block),
                ("expected_event", 1)]
    assert [(matcher.get_output_port(i).get_name(), matcher.get_output_port(i).size())
            for i in range(matcher.num_output_ports())] == [
                ("sa_window", 2 * 50), ("ra_window", 2 * 500), ("scores", 4), ("match", 1),
                ("scored_event", 1)]


def test_events_are_numbered_in_grasp_order():
    expected = {"reach_load": 0, "load_lift": 1, "lift_hold": 2, "place_unload": 3}
    assert EventMatcher.transition_indices(reversed(list(EVENTS))) == expected
    matcher = EventMatcher(EVENTS)
    assert {t: matcher.event_index(t) for t in matcher.transitions} == expected
    with pytest.raises(ValueError, match="no memorized event for 'unload_open'"):
        matcher.event_index("unload_open")


def run_grasp_sequence(source, config=EventMatcherConfig(), t_end=3.6):
    """Expect the paper's three events in turn, as the state machine would: {event: time}."""
    harness = Harness(source, config)
    remaining = list(REQUIRED_TRANSITIONS)
    harness.expect(remaining[0])
    matched = {}
    for time, _, match in harness.run(t_end):
        if match and remaining:
            matched[remaining.pop(0)] = time
            harness.expect(remaining[0] if remaining else -1)
    return matched


LIVE_VARIANTS = {
    "sensor noise": (NOISY, 100.0),
    "time shifted, RA 30 ms late, right finger 20 ms late": (
        dataclasses.replace(NOISY, contact_s=1.3, place_s=3.3, duration_s=4.5,
                            sensors=dataclasses.replace(NOISY.sensors, ra_delay_s=0.03,
                                                        right_delay_s=0.02)), 100.0),
    "scaled": (dataclasses.replace(NOISY, sensors=dataclasses.replace(
        NOISY.sensors, sa_scale=2.5, ra_scale=0.4)), 100.0),
    "SA at 1 kHz against 100 Hz templates": (NOISY, 1000.0),
}


@pytest.mark.parametrize("variant", LIVE_VARIANTS)
def test_each_event_matches_within_half_a_second_of_its_physical_event(variant):
    live, sa_rate_hz = LIVE_VARIANTS[variant]
    matched = run_grasp_sequence(replay(live, sa_rate_hz=sa_rate_hz),
                                 EventMatcherConfig(sa_rate_hz=sa_rate_hz),
                                 t_end=live.duration_s - 0.2)
    physical = live.transition_times()
    assert list(matched) == list(REQUIRED_TRANSITIONS)
    for transition, time in matched.items():
        assert physical[transition] < time <= physical[transition] + 0.5, transition


def test_a_contact_without_impact_does_not_match_first_contact():
    harness = Harness(replay(dataclasses.replace(
        NOISY, signals=dataclasses.replace(NOISY.signals, contact_burst=0.0))))
    harness.expect("reach_load")
    scores = np.array([s for _, s, match in harness.run(1.5) if not match])
    assert len(scores) == 1500  # never matched
    assert scores[:, :2].max() > 0.9  # the force rise alone looks like contact ...
    assert scores[:, 2:].max() < 0.5  # ... but there is no impact on the RA channels


def test_holding_steady_does_not_match_first_contact():
    harness = Harness(replay(NOISY))
    for _ in harness.run(2.3):
        pass
    harness.expect("reach_load")
    steps = list(harness.run(2.95))
    assert not any(match for _, _, match in steps)
    np.testing.assert_array_equal([s[:2] for _, s, _ in steps], 0.0)  # SA too flat


@pytest.mark.parametrize("level", [[0.0, 0.0, 0.0, 0.0], [3.0, 3.0, 0.5, 0.5]])
def test_a_constant_signal_never_matches_and_gives_no_nan(level):
    harness = Harness(ConstantVectorSource(level))
    for event in range(len(EVENTS)):
        harness.expect(event)
        steps = list(harness.run(0.6 * (event + 1)))
        assert not any(match for _, _, match in steps)
        scores = np.array([s for _, s, _ in steps])
        assert np.all(np.isfinite(scores))
        assert np.all(scores[:, 2:] == 0.0)  # every template has a contrasted RA channel


def test_no_expected_event_gives_zero_scores_and_no_match():
    harness = Harness(replay(NOISY))
    steps = list(harness.run(1.3))
    np.testing.assert_array_equal([s for _, s, _ in steps], 0.0)
    assert not any(match for _, _, match in steps)
    assert harness.output("scored_event")[0] == -1


def test_match_is_reported_only_for_the_event_now_expected():
    harness = Harness(replay(NOISY))
    harness.expect("reach_load")
    next(time for time, _, match in harness.run(1.3) if match)
    harness.expect("load_lift")
    assert harness.output("match")[0] == 0.0  # the scores are still for reach_load
    assert harness.output("scored_event")[0] == 0
    list(harness.run(harness.simulator.get_context().get_time() + 0.011))
    assert harness.output("scored_event")[0] == 1


def test_scores_equal_the_reference_on_the_live_windows():
    trajectory = channels_trajectory(synthetic_grasp(NOISY))
    harness = Harness(TrajectorySource(trajectory))
    harness.expect("reach_load")
    for t_end in (0.9505, 1.0005, 1.2005):
        list(harness.run(t_end))
        windows = []
        for rows, rate, length in (((0, 1), 100.0, 50), ((2, 3), 1000.0, 500)):
            ticks = (np.floor(t_end * rate) - np.arange(length)[::-1]) / rate
            windows += list(np.array([trajectory.value(t)[rows, 0] for t in ticks]).T)
        event = EVENTS["reach_load"]
        expected = event_scores_reference(windows, list(event.sa) + list(event.ra), 0.25)
        np.testing.assert_allclose(harness.output("scores"), expected, atol=1e-9)


@pytest.mark.parametrize("value", [4.0, 0.5, np.nan])
def test_an_invalid_expected_event_is_refused(value):
    harness = Harness(replay(NOISY))
    harness.expect(0)
    harness.diagram.get_input_port(0).FixValue(harness.simulator.get_mutable_context(),
                                               [value])
    with pytest.raises(ValueError, match="expected_event"):
        harness.simulator.AdvanceTo(0.01)


def test_an_event_flat_on_every_channel_is_judged_against_the_noise_floor():
    # Its flat RA channels are quiet templates (events/ra_noise_floor.py): the matcher
    # reads the RA noise floor, so a live event above the floor fails them.
    flat = dataclasses.replace(EVENTS["lift_hold"], ra=np.ones((2, 500)))
    assert EventMatcher({"lift_hold": flat}).has_ra_floor


def test_an_all_zero_template_channel_is_refused():
    event = EVENTS["reach_load"]
    silent = dataclasses.replace(event, ra=np.vstack([event.ra[0], np.zeros(500)]))
    with pytest.raises(ValueError, match=r"all-zero channels \['ra_right'\]"):
        EventMatcher({"reach_load": silent})


def test_scores_are_eq3_of_the_normalizer_windows_at_every_tick():
    harness = Harness(replay(NOISY))
    normalizer = harness.matcher  # a WindowNormalizer: the windows it scores
    compared = 0
    for event, (t_start, t_end) in (("reach_load", (0.6, 1.3)), ("load_lift", (1.3, 1.9))):
        harness.expect(event)
        for _, scores, _ in harness.run(t_end):
            if harness.simulator.get_context().get_time() < t_start or (
                    harness.output("scored_event")[0] != harness.matcher.event_index(event)):
                continue  # the window is not yet full, or the SA scores are the old event's
            context = normalizer.GetMyContextFromRoot(harness.simulator.get_context())
            windows = [normalizer.GetOutputPort(f"{kind}_window").Eval(context).reshape(
                2, normalizer.window_length(kind)) for kind in ("sa", "ra")]
            template = EVENTS[event]
            expected = event_scores_reference(list(windows[0]) + list(windows[1]),
                                              list(template.sa) + list(template.ra), 0.25)
            np.testing.assert_allclose(scores, expected, rtol=0, atol=1e-9)
            compared += 1
    assert compared > 1200


@pytest.mark.parametrize("sa_rate_hz", [100.0, 1000.0])
def test_scores_and_match_equal_the_one_system_matcher_tick_by_tick(sa_rate_hz):
    events = extract_memorized_events(synthetic_grasp(IDEAL, sa_rate_hz=sa_rate_hz),
                                      object_name="box", sa_rate_hz=sa_rate_hz,
                                      ra_rate_hz=1000.0, package_versions={})
    both = replay_both(synthetic_grasp(NOISY, sa_rate_hz=sa_rate_hz), events,
                       EventMatcherConfig(sa_rate_hz=sa_rate_hz))
    assert not np.isnan(both.fire_times).any()  # every event matched: the scores moved on
    np.testing.assert_allclose(both.scores, both.one_system_scores, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(both.match, both.one_system_match)


def glitched_and_held(glitches):
    """The NOISY replay with a non-finite value at each (channel, tick time, value) of
    `glitches`, and the same replay with each of them replaced by the channel's previous
    sample (what a missing sample enters the window as)."""
    trajectory = channels_trajectory(synthetic_grasp(NOISY))
    breaks = np.array(trajectory.get_segment_times())
    samples = np.hstack([trajectory.value(t) for t in breaks])
    glitched, held = samples.copy(), samples.copy()
    for channel, time, value in glitches:
        # The tick at `time` reads the segment that starts just before it (the breaks are
        # the union of the SA and RA sample times, so a segment is one RA tick long).
        segment = int(np.searchsorted(breaks, time, side="right")) - 1
        glitched[channel, segment] = value
        held[channel, segment] = samples[channel, segment - 1]
    return [TrajectorySource(PiecewisePolynomial.ZeroOrderHold(breaks, values))
            for values in (glitched, held)]


def test_a_non_finite_sample_scores_its_channel_zero_for_one_window_and_poisons_nothing():
    """One NaN or inf sample must not keep the streaming state wrong after it leaves the
    window, nor give NaN scores. Through the EventMatcher
    (WindowNormalizer and scores in one update): the sample enters as its channel's previous one, the channel scores 0 while it is
    in the window (0.5 s), every other score and every later one is that of the stream
    without the glitch, and the event still matches when it comes."""
    # (channel, time, value): ra_left NaN, sa_right inf, ra_right -inf
    glitches = [(2, 0.2, np.nan), (1, 0.25, np.inf), (3, 0.3, -np.inf)]
    runs = []
    for source in glitched_and_held(glitches):
        harness = Harness(source)
        harness.expect("reach_load")
        runs.append(np.array([[time, match, *scores]
                              for time, scores, match in harness.run(1.3)]))
    glitched, held = runs
    times = glitched[:, 0]
    assert np.all(np.isfinite(glitched))
    in_window = np.zeros(glitched[:, 2:].shape, dtype=bool)
    for channel, time, _ in glitches:
        in_window[:, channel] = (times > time) & (times < time + 0.5)
        assert np.any(held[in_window[:, channel], 2 + channel] != 0.0)  # so 0 is the glitch's
    np.testing.assert_array_equal(glitched[:, 2:][in_window], 0.0)
    np.testing.assert_allclose(glitched[:, 2:][~in_window], held[:, 2:][~in_window],
                               rtol=0, atol=1e-9)
    matched = [times[run[:, 1] > 0][0] for run in runs]
    assert matched[0] == matched[1] and 0.8 < matched[0] < 1.3



def test_per_event_thresholds_replace_the_common_pair_for_their_event_only():
    """The taxel_aware controller's ensemble events carry a threshold pair each.
    Unmatchable thresholds for Load-Lift alone stop the sequence there; the others match."""
    config = EventMatcherConfig(event_thresholds={"load_lift": (1.0, 1.0)})
    matched = run_grasp_sequence(replay(NOISY), config)
    assert list(matched) == ["reach_load"]
    with pytest.raises(ValueError, match="without an event"):
        EventMatcher(EVENTS, EventMatcherConfig(event_thresholds={"hold_place": (0.5, 0.5)}))
