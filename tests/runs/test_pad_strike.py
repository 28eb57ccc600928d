"""The RA (PVDF film) transient of a pad striking an object, in the smallest scene."""

import dataclasses
import math

import numpy as np
import pytest

from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.runs.pad_strike import (PadStrikeConfig, run_pad_strike, strike_scenario)
from tegrasp_drake.rig import paths

SHORT = dict(before_contact_s=0.05, after_contact_s=0.05)


@pytest.fixture(scope="module")
def strikes_by_speed():
    return {speed: run_pad_strike(PadStrikeConfig(finger_speed_mps=speed, **SHORT))
            for speed in (0.0125, 0.025, 0.05)}


@pytest.mark.slow
def test_ra_converges_with_the_plant_step():
    """At 1, 0.5 and 0.25 ms the contact peaks agree within 15 % and the Eq. 3
    scores of the same trial against the same memorized event within 0.05 (measured: peaks
    within 1 %, scores within 0.03)."""
    # The strike is the prismatic hand's finger: that hand's memorized event.
    event = load_memorized_events(paths.package_events_dir() / "prismatic", "box")["reach_load"]
    strikes = [run_pad_strike(PadStrikeConfig(time_step_s=dt)) for dt in (1e-3, 5e-4, 2.5e-4)]
    for pad in (0, 1):  # the right pad's peak is its own contact, the object already moving
        peaks = [strike.contact_peak(pad) for strike in strikes]
        assert max(peaks) <= 1.15 * min(peaks), (pad, peaks)
    scores = np.array([strike.eq3_scores(event) for strike in strikes])
    assert np.all(scores.max(axis=0) - scores.min(axis=0) <= 0.05), scores


def test_contact_peak_grows_with_approach_speed(strikes_by_speed):
    peaks = [strikes_by_speed[speed].contact_peak(0) for speed in (0.0125, 0.025, 0.05)]
    assert peaks[0] < peaks[1] < peaks[2]
    assert peaks[2] / peaks[1] > 1.5 and peaks[1] / peaks[0] > 1.5  # about linear


def test_the_finger_that_does_not_touch_sees_the_contact_attenuated(strikes_by_speed):
    """The right film sees no contact force and no impact, only its fingertip's inertia
    while the mimic-coupled finger slows, through the 60 Hz load low-pass: about 3 % of the
    left film's peak (measured 2.6-4 %)."""
    for strike in strikes_by_speed.values():
        assert np.isnan(strike.contact_times[1])  # the right pad has not touched yet
        assert np.abs(strike.ra[:, 1]).max() < 0.1 * strike.contact_peak(0)


def test_the_contact_rings_for_several_ms_at_the_mode_damping():
    """With the load path frozen (a 1 mHz low-pass) and no texture, what the film shows
    after the strike is the impact's ring: its 1 ms peak-hold decays as exp(-zeta w t)."""
    config = PadStrikeConfig(**SHORT)
    scenario = strike_scenario(config)
    vibration = dataclasses.replace(
        scenario.vibration, slip_texture_height_m=0.0,
        film=dataclasses.replace(scenario.vibration.film, load_lowpass_hz=1e-3))
    strike = run_pad_strike(config, dataclasses.replace(scenario, vibration=vibration))
    first = np.searchsorted(strike.t_ra, strike.contact_times[0])
    envelope = np.abs(strike.ra[first:first + 20, 0])
    t = strike.t_ra[first:first + 20]
    rate = -np.polyfit(t, np.log(envelope), 1)[0]
    zeta_w = vibration.film.mode_damping_ratio * 2 * math.pi * vibration.film.mode_frequency_hz
    assert rate == pytest.approx(zeta_w, rel=0.15)
    assert np.all(envelope[:6] > envelope[0] / math.e)  # more than 1/e for 5 ms
