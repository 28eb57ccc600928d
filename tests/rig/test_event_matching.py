"""The Eq. 3 matching settings (rig/event_matching.py): declared once for the controllers
and the EventMatcher, with their ranges and what relates them to the RA stream."""

import dataclasses

import pytest

from tegrasp_drake.events import EventMatcherConfig
from tegrasp_drake.rig.event_matching import EventMatchingConfig
from tegrasp_drake.rig.ranges import check_ranges, range_of
from tegrasp_drake.rig.typed_yaml import ConfigError


def test_the_matcher_takes_each_shared_setting_as_declared_once():
    matcher = {field.name: field for field in dataclasses.fields(EventMatcherConfig)}
    for field in dataclasses.fields(EventMatchingConfig):
        assert matcher[field.name].default == field.default, field.name
        assert range_of(matcher[field.name]) is range_of(field), field.name


def test_the_thresholds_are_correlations():
    with pytest.raises(ConfigError, match=r"field 'ra_threshold' must lie in \[-1, 1\] "
                       r"\(Eq. 3 scores are correlations\), got 1.5"):
        check_ranges(EventMatchingConfig(ra_threshold=1.5), "here")


@pytest.mark.parametrize("settings, field, words", [
    (dict(ra_envelope_hz=500.0), "ra_envelope_hz", "half the RA rate (500 Hz)"),
    (dict(ra_noise_quiet_s=0.001), "ra_noise_quiet_s", "at least 2 RA samples"),
    (dict(ra_noise_floor_sigmas=5.39, ra_noise_quiet_s=3.0), "ra_noise_quiet_s",
     "must end with the approach, by grasp.settle_s + grasp.reach_s = 2.8 s"),
])
def test_the_envelope_and_the_noise_floor_must_fit_the_ra_stream(settings, field, words):
    found = EventMatchingConfig(**settings).problem(ra_rate_hz=1000.0, approach_s=2.8)
    assert found[0] == field and words in found[1]


def test_a_quiet_period_past_the_approach_is_fine_without_the_floor():
    assert EventMatchingConfig(ra_noise_quiet_s=3.0).problem(ra_rate_hz=1000.0,
                                                             approach_s=2.8) is None
