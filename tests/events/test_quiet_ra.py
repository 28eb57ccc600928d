"""Quiet RA templates (events/extraction.py, events/ra_noise_floor.py): an RA window that
holds only the sensor's noise is memorized flat, and a flat RA template passes a live
window that stays within the live noise floor; above it Eq. 3 judges (a transient fails,
a steady level passes)."""

import dataclasses

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.events.event_matcher import (EventMatcher, EventMatcherConfig,
                                                add_event_matcher)
from tegrasp_drake.events.extraction import (TactileTrial, extract_memorized_events,
                                             quiet_as_flat, recording_ra_floor)
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.ra_noise_floor import rule_sigmas

CODE = 1.23  # [m/s^2] one converter code at the film's sensitivity (docs/model.md)


def converter_noise(rng, samples: int) -> np.ndarray:
    """|Gaussian noise of 0.5 code rms|, quantised to whole codes [m/s^2]: the film at
    rest read through the 12-bit converter (mostly 0, some 1-code samples)."""
    return CODE * np.abs(np.round(rng.normal(0.0, 0.5, samples)))


def grasp_trial(rng, contact_height: float) -> TactileTrial:
    """8 s of a grasp: converter noise on both RA channels throughout, a contact burst of
    `contact_height` [m/s^2] decaying from 3.0 s over 0.3 s, the SA rising at 3.0 s and
    held."""
    t_ra = np.arange(8000) / 1000.0
    ra = np.column_stack([converter_noise(rng, len(t_ra)) for _ in range(2)])
    burst = np.where((t_ra >= 3.0) & (t_ra < 3.3),
                     contact_height * np.exp(-(t_ra - 3.0) / 0.03), 0.0)
    ra += burst[:, np.newaxis]
    t_sa = np.arange(800) / 100.0
    grip = np.clip((t_sa - 3.0) / 0.3, 0.0, 1.0) * 20.0
    return TactileTrial(t_sa=t_sa, sa=np.column_stack([grip, grip]), t_ra=t_ra, ra=ra,
                        transition_times={"reach_load": 3.2, "load_lift": 6.0})


def test_the_recordings_floor_is_its_approachs_mean_plus_k_deviations():
    trial = grasp_trial(np.random.default_rng(600), 50.0)
    quiet = trial.ra[trial.t_ra < 2.0]
    np.testing.assert_allclose(recording_ra_floor(trial, quiet_s=2.0, sigmas=5.0),
                               quiet.mean(axis=0) + 5.0 * quiet.std(axis=0))
    # Converter noise of 0.5 code rms: about 0.4 + 5.39 x 0.5 codes, between 2 and 4 codes.
    floor = recording_ra_floor(trial, quiet_s=2.0, sigmas=rule_sigmas(1000.0))
    assert np.all((floor > 2.0 * CODE) & (floor < 4.0 * CODE))


def test_a_window_within_the_floor_is_stored_flat_and_one_above_it_as_cut():
    window = np.array([[0.0, CODE, 0.0, 2 * CODE], [0.0, CODE, 10.0 * CODE, 0.0]])
    flattened = quiet_as_flat(window, [2.5 * CODE, 2.5 * CODE])
    np.testing.assert_array_equal(flattened[0], np.ones(4))
    np.testing.assert_array_equal(flattened[1], window[1])


def test_a_noise_only_held_grip_is_memorized_flat_and_a_contact_is_not():
    trial = grasp_trial(np.random.default_rng(601), 50.0)
    floor = recording_ra_floor(trial, quiet_s=2.0, sigmas=rule_sigmas(1000.0))
    events = extract_memorized_events(trial, object_name="box", sa_rate_hz=100.0,
                                      ra_rate_hz=1000.0, ra_floor=floor,
                                      pre_transition_s=0.5)
    # The held grip's window (5.5-6.0 s) is noise only: flat, ones on both channels.
    np.testing.assert_array_equal(events["load_lift"].ra, np.ones((2, 500)))
    # First contact rises far above the floor: kept as cut (max-normalised), not flat.
    assert np.ptp(events["reach_load"].ra, axis=1).min() > 0.9
    # Without a floor the held grip's window is the max-normalised sparse noise.
    plain = extract_memorized_events(trial, object_name="box", sa_rate_hz=100.0,
                                     ra_rate_hz=1000.0, pre_transition_s=0.5)
    assert np.mean(plain["load_lift"].ra == 0.0) > 0.5


def quiet_event() -> MemorizedEvent:
    """Load-Lift memorized on a held grip: flat SA, flat (quiet) RA."""
    return MemorizedEvent(object_name="box", transition="load_lift",
                          sa=np.ones((2, 50)), ra=np.ones((2, 500)), sa_rate_hz=100.0,
                          ra_rate_hz=1000.0)


def ra_scores_of_quiet_template(burst_height: float, at_s: float = 2.9,
                                block_s: float = 0.0, level: float = 0.0) -> np.ndarray:
    """The matcher's RA scores at `at_s` [s] against a quiet template, the live film reading
    converter noise from 0 s (the floor's quiet period: 1 s, the rule's k), from 2.0 s
    plus a steady `level` [m/s^2], and a burst of `burst_height` [m/s^2] decaying from
    2.6 s; the SA held at 20 N."""
    rng = np.random.default_rng(602)
    times = np.arange(0.0, 3.2, 1e-3)
    ra = converter_noise(rng, len(times)) + np.where(times >= 2.0, level, 0.0)
    ra = ra + np.where(times >= 2.6, burst_height * np.exp(-(times - 2.6) / 0.03), 0.0)
    values = np.vstack([np.full_like(ra, 20.0), np.full_like(ra, 20.0), ra, ra])
    builder = DiagramBuilder()
    source = builder.AddSystem(TrajectorySource(PiecewisePolynomial.ZeroOrderHold(
        times - 1e-9, values)))
    matcher = add_event_matcher(builder, {"load_lift": quiet_event()}, EventMatcherConfig(
        sa_rate_hz=100.0, ra_noise_quiet_s=1.0, block_s=block_s),
        channels=source.get_output_port())
    expected = builder.AddSystem(ConstantVectorSource([0.0]))
    builder.Connect(expected.get_output_port(), matcher.GetInputPort("expected_event"))
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(at_s)
    return matcher.GetOutputPort("scores").Eval(
        matcher.GetMyContextFromRoot(simulator.get_context()))[2:]


def test_a_quiet_template_passes_a_live_window_of_noise_only():
    np.testing.assert_array_equal(ra_scores_of_quiet_template(0.0), [1.0, 1.0])
    np.testing.assert_array_equal(ra_scores_of_quiet_template(0.0, block_s=0.01), [1.0, 1.0])


def test_a_quiet_template_fails_a_live_event_above_the_floor():
    # A burst of 8 codes, a fingertip's tap, within the last 0.5 s window: above the floor,
    # and Eq. 3 of a transient against the flat template is below the RA threshold.
    threshold = EventMatcherConfig().ra_threshold
    for block_s in (0.0, 0.01):
        assert np.all(ra_scores_of_quiet_template(8.0 * CODE, block_s=block_s) < threshold)


def test_a_quiet_template_passes_a_steady_level_above_the_floor_by_eq_3():
    # A grip that creeps: the film reads a steady offset of 8 codes. Above the floor, Eq. 3
    # against the flat template scores the steady window near 1.
    assert np.all(ra_scores_of_quiet_template(0.0, level=8.0 * CODE) > 0.95)


def test_before_the_live_floor_is_known_eq_3_judges_the_noise():
    # At 0.9 s the window is full but the 1 s quiet period is not over: Eq. 3 of the sparse
    # noise against the flat template (about sqrt of the non-zero fraction, 0.6) fails.
    assert np.all(ra_scores_of_quiet_template(0.0, at_s=0.9) < EventMatcherConfig().ra_threshold)


def test_the_matcher_reads_the_floor_for_a_quiet_template_without_the_gate():
    matcher = EventMatcher({"load_lift": quiet_event()}, EventMatcherConfig(sa_rate_hz=100.0))
    assert matcher.has_ra_floor
    builder = DiagramBuilder()
    source = builder.AddSystem(ConstantVectorSource(np.zeros(4)))
    add_event_matcher(builder, {"load_lift": quiet_event()},
                      EventMatcherConfig(sa_rate_hz=100.0), channels=source.get_output_port())
    assert builder.HasSubsystemNamed("ra_noise_floor")
    # An event whose RA carries a change needs no floor unless the gate is set.
    event = dataclasses.replace(quiet_event(), ra=np.vstack([np.linspace(0.0, 1.0, 500)] * 2))
    assert not EventMatcher({"load_lift": event},
                            EventMatcherConfig(sa_rate_hz=100.0)).has_ra_floor


def test_the_quiet_rule_needs_the_channels_to_measure_the_floor():
    builder = DiagramBuilder()
    with pytest.raises(ValueError, match="noise floor needs the channels"):
        add_event_matcher(builder, {"load_lift": quiet_event()},
                          EventMatcherConfig(sa_rate_hz=100.0))
