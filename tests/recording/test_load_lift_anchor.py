"""Load-Lift is anchored on the script's start of the lift, after a Load phase in which the
grip settles: its memorized event is the settled grip, not Reach-Load's rise moved a few
milliseconds, and a closed-loop lift starts with the grip settled."""

import dataclasses

import pytest

from tegrasp_drake.control.scripted_grasp import GraspScriptConfig
from tegrasp_drake.events import load_memorized_events
from tegrasp_drake.events.correlation import max_normalized_xcorr_reference, window_contrast
from tegrasp_drake.events.event_matcher import EventMatcherConfig
from tegrasp_drake.recording.campaign import RecordEventsError
from tegrasp_drake.recording.paper_events import record_events
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.channels import CHANNEL_NAMES
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.scenario.grasp_outcome import GRIP_FRACTION
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.scenario.scenario import LoadScenario
from tests.cheap_contact import CHEAP_CONTACT

MATCHER = EventMatcherConfig()  # the paper's thresholds and the contrast gate


def template_correlations(events) -> dict[str, float]:
    """Eq. 3 (max over lags) between the Reach-Load and Load-Lift templates, per channel."""
    return {name: max_normalized_xcorr_reference(events["reach_load"].channel(name),
                                                 events["load_lift"].channel(name))
            for name in CHANNEL_NAMES}


# The ensemble's Reach-Load window ends 50 ms after the first touch (0.2 N of true force),
# before the squeeze: on the capacitive pad it holds only the pad's noise (about 1.5 N a pad
# at rest, against a 26 N grip), and noise with a positive mean correlates with the flat
# Load-Lift template at 0.97. A defect of the ensemble's window on this pad, not of the
# anchor; the paper's events (Reach-Load centred on the contact) hold.
ENSEMBLE_ON_NOISE = pytest.mark.xfail(
    strict=True, reason="the ensemble's Reach-Load SA window ends before the squeeze and "
                        "holds the capacitive pad's noise")


@pytest.mark.parametrize("folder", ["", pytest.param("ensemble", marks=ENSEMBLE_ON_NOISE)])
@pytest.mark.parametrize("object_name", sorted(BUILTIN_OBJECTS))
def test_the_load_lift_event_is_the_settled_grip_not_a_shifted_reach_load(object_name,
                                                                          folder):
    events = load_memorized_events(paths.package_events_dir() / folder, object_name)
    correlations = template_correlations(events)
    print(object_name, folder, {name: round(r, 3) for name, r in correlations.items()})
    script = GraspScriptConfig()
    lift_start = script.settle_s + script.reach_s + script.load_s
    assert events["load_lift"].transition_time_s == pytest.approx(lift_start, abs=1e-9)
    for name in ("sa_left", "sa_right"):
        # Reach-Load's SA window holds the rise; Load-Lift's is flat: the settled grip.
        assert window_contrast(events["reach_load"].channel(name))[0] > 0.5
        assert window_contrast(events["load_lift"].channel(name))[0] < MATCHER.min_contrast
        # A live window shaped like Reach-Load's does not pass Load-Lift's SA threshold
        # at any lag (a shifted copy would score 1).
        assert correlations[name] < MATCHER.sa_threshold


@pytest.mark.slow
def test_recording_refuses_a_load_phase_that_lifts_before_the_grip_settles():
    """The 25 mm cylinder touches about 1.24 s after the close command: a Load phase of
    1.25 s lifts with a fraction of the grip."""
    # The cheap contact: the claim is the recording's check of the grip at the lift, which
    # the pads' squeeze decides (about 1.24 s to contact), not how the held rod creeps.
    scenario = LoadScenario(name="thin_cylinder",
                            overrides=["grasp.load_s=1.25", *CHEAP_CONTACT])
    with pytest.raises(RecordEventsError, match="lengthen grasp.load_s"):
        record_events("thin_cylinder", scenario)


@pytest.mark.slow
@pytest.mark.parametrize(("object_name", "offset", "seed"), [
    ("box", (0.0, 0.0), 600), ("box", (0.0, 0.015), 602),
    # With the grip-reached anchor this one lifted 20 ms after Reach-Load, at 32 % of the
    # grip.
    ("thick_cylinder", (-0.01, -0.015), 603)])
def test_the_closed_loop_lift_starts_with_the_grip_settled(object_name, offset, seed):
    base = LoadScenario(name=object_name)
    scenario = dataclasses.replace(base, random_seed=seed, placement=dataclasses.replace(
        base.placement, offset=list(offset)))
    result = run_trial(scenario).result
    lifts = [e for e in result["transitions"] if (e["from"], e["to"]) == ("Load", "Lift")]
    assert lifts and lifts[0]["trigger"] == "memorized_event"
    assert result["lift_grip_fraction"] >= GRIP_FRACTION
