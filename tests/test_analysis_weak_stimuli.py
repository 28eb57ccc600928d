"""Missed memorized events, classed from a replay of the wait (events/missed_waits.py,
sweep/missed_event_report.py, analysis/weak_stimuli.py), on synthetic grasps: the events
are memorized from an ideal synthetic grasp, and the trials that miss them are synthetic
grasps whose vibration is buried in noise (a weak dynamic stimulus) or whose second finger
touches too late (SA fails)."""

import dataclasses

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import MemorizedControllerConfig
from tegrasp_drake.control.controller_registry import rule_tables
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
from tegrasp_drake.control.transition_logic import Observation, next_mode
from tegrasp_drake.events.event_matcher import EventMatcherConfig
from tegrasp_drake.events.events_folder import save_memorized_events
from tegrasp_drake.events.extraction import extract_memorized_events
from tegrasp_drake.events.missed_waits import (
    EVENT_TIMEOUT_RULES, MATCHED_IN_REPLAY, SA_DID_NOT_MATCH, WEAK_DYNAMIC_STIMULUS, EventWait,
    classify_missed_wait, event_waits, timeout_reason_prefix)
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.events.synthetic import (SyntheticGraspConfig, SyntheticSensorsConfig,
                                             synthetic_grasp, synthetic_sa)
from tegrasp_drake.events.ra_noise_floor import rule_sigmas
from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.rig.objects import object_description
from tegrasp_drake.scenario.scenario import sample_rates_hz
from tegrasp_drake.scenario.trial_log_file import TrialLog
from tegrasp_drake.sweep.missed_event_report import (
    WITHIN_FLOOR, TrialMiss, class_counts, report_markdown)
from tegrasp_drake.sweep.records import make_record, write_record
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tegrasp_drake.sweep.trial_function import scenario_from_trial_spec, trial_log_name
from tests.analysis_script import load_analysis_script
from tests.fake_trials import whole_result



def load_command():
    """analysis/weak_stimuli.py as a module."""
    return load_analysis_script("weak_stimuli")

IDEAL = SyntheticGraspConfig()
EVENTS = extract_memorized_events(synthetic_grasp(IDEAL), object_name="box",
                                  sa_rate_hz=100.0, ra_rate_hz=1000.0, package_versions={})
# The paper's thresholds; the RA noise is measured on the 0.5 s before the first contact.
CONFIG = EventMatcherConfig(ra_noise_quiet_s=0.5)
# The machine waits in Reach from the start until 1.6 s, past the contact at 0.8 s.
REACH_WAIT = EventWait("reach_load", 0.0, 1.6, "no Reach-Load event 2 s after closing")
# A grasp with sensor noise, 0.2 m/s^2 per RA axis: the contact's ring-down peaks at
# 20 m/s^2, a hundred times the noise.
CLEAR_FILM = SyntheticGraspConfig(sensors=SyntheticSensorsConfig(ra_noise=0.2, sa_noise_n=0.005,
                                                                seed=3))
# The same with the vibration 100 times weaker: the ring-down no higher than the noise.
WEAK_FILM = dataclasses.replace(CLEAR_FILM, sensors=dataclasses.replace(CLEAR_FILM.sensors,
                                                                       ra_scale=0.01))
# The right finger touches 1 s after the left: within the wait only the left SA rises.
LATE_RIGHT_FINGER = SyntheticGraspConfig(sensors=SyntheticSensorsConfig(right_delay_s=1.0))


def reason_of(mode: Mode, observation: Observation, counters=Counters()) -> Transition:
    """The transition the state machine's own rule takes, as a trial's result holds it."""
    config = MemorizedControllerConfig()
    decision = next_mode(mode, observation, counters, config,
                         event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
    assert decision is not None
    return decision


def entry(t: float, from_mode: Mode, to_mode: Mode, reason: str,
          trigger=Trigger.CORRECTIVE, code: str | None = None) -> dict:
    return Transition(t=t, from_mode=from_mode, to_mode=to_mode, trigger=trigger,
                      reason=reason, code=code).as_dict()


def decided(t: float, from_mode: Mode, decision, trigger=Trigger.CORRECTIVE) -> dict:
    """The timeline entry of a rule's decision, with its code."""
    return entry(t, from_mode, decision.mode, decision.reason, trigger, decision.code)


def without_codes(transitions: list[dict]) -> list[dict]:
    """The entries as written before timeline entries carried their rule's code."""
    return [{key: value for key, value in e.items() if key != "code"} for e in transitions]


@pytest.mark.parametrize("codes", [True, False], ids=["by code", "by the words, no codes"])
def test_event_waits_are_the_timeouts_of_the_state_machines_rules(codes):
    reach = reason_of(Mode.REACH, Observation(closing_s=10.0))
    load = reason_of(Mode.LOAD, Observation(time_in_mode=10.0))
    place = reason_of(Mode.PLACE, Observation(motion_done=True, time_since_motion_done=10.0,
                                                contact=(True, True)))
    one_finger = reason_of(Mode.REACH, Observation(contact=(True, False), one_sided_s=10.0))
    event = Trigger.MEMORIZED_EVENT
    transitions = [
        decided(3.0, Mode.REACH, reach),
        entry(4.0, Mode.RE_REACH, Mode.REACH, "re-centred", code="re_centred"),
        entry(5.0, Mode.REACH, Mode.LOAD, "Reach-Load event", event, "reach_event"),
        decided(7.0, Mode.LOAD, load),
        entry(8.0, Mode.RE_REACH, Mode.REACH, "re-centred", code="re_centred"),
        decided(9.0, Mode.REACH, one_finger),
        entry(10.0, Mode.RE_REACH, Mode.REACH, "re-centred", code="re_centred"),
        entry(11.0, Mode.REACH, Mode.LOAD, "Reach-Load event", event, "reach_event"),
        entry(11.5, Mode.LOAD, Mode.LIFT, "Load-Lift event", event, "load_lift_event"),
        entry(13.0, Mode.LIFT, Mode.HOLD, "lift motion ended", Trigger.TIMER, "lift_ended"),
        entry(16.0, Mode.HOLD, Mode.PLACE, "held 3 s", Trigger.TIMER, "hold_time"),
        decided(19.0, Mode.PLACE, place, Trigger.TIMER),
    ]
    waits = event_waits(transitions if codes else without_codes(transitions))
    assert [(w.transition, w.start_s, w.end_s) for w in waits] == [
        ("reach_load", 0.0, 3.0), ("load_lift", 5.0, 7.0), ("place_unload", 16.0, 19.0)]


def test_a_reworded_timeout_is_a_wait_by_its_rules_code():
    transitions = [
        entry(2.0, Mode.REACH, Mode.LOAD, "waited 2 s for the Reach-Load event in vain, both "
              "pads hold the object: load", code="reach_timeout_both_pads"),
        entry(4.0, Mode.LOAD, Mode.RE_REACH, "the Load-Lift event never came",
              code="load_timeout")]
    assert [(w.transition, w.start_s, w.end_s) for w in event_waits(transitions)] == [
        ("reach_load", 0.0, 2.0), ("load_lift", 2.0, 4.0)]
    assert event_waits(without_codes(transitions)) == []  # the words alone name no timeout


def test_a_reason_that_reads_like_a_timeout_is_no_wait_when_its_rule_is_another():
    transitions = [entry(1.0, Mode.REACH, Mode.RE_REACH,
                         "no Reach-Load event: only the left finger touched", code="one_sided")]
    assert event_waits(transitions) == []
    assert len(event_waits(without_codes(transitions))) == 1  # as the words alone read it


def test_every_rule_that_gives_up_on_an_event_is_a_timeout_rule():
    """A rule is in EVENT_TIMEOUT_RULES, with its event, exactly when its `when` in the rule
    tables (docs/controller.md) starts "no X-Y event": a new timeout rule cannot be left out."""
    rules = {rule.name: rule for table in rule_tables().values() for rule in table.all_rules()}
    described = {name: transition for name, rule in rules.items()
                 for transition in REQUIRED_TRANSITIONS
                 if rule.when.startswith(timeout_reason_prefix(transition))}
    assert EVENT_TIMEOUT_RULES == described


def test_a_trial_that_matched_every_event_has_no_waits():
    transitions = [entry(1.0, Mode.REACH, Mode.LOAD, "Reach-Load event"),
                   entry(1.5, Mode.LOAD, Mode.LIFT, "Load-Lift event")]
    assert event_waits(transitions) == []


@pytest.fixture(scope="module")
def classified():
    return {name: classify_missed_wait(synthetic_grasp(config), EVENTS, REACH_WAIT, CONFIG)
            for name, config in (("clear film", CLEAR_FILM), ("weak film", WEAK_FILM),
                                 ("late right finger", LATE_RIGHT_FINGER))}


def test_a_clear_vibration_matches_in_the_replay(classified):
    assert classified["clear film"].miss_class == MATCHED_IN_REPLAY


def test_a_vibration_buried_in_noise_is_a_weak_dynamic_stimulus(classified):
    weak = classified["weak film"]
    assert weak.miss_class == WEAK_DYNAMIC_STIMULUS
    assert np.all(weak.best_sa > CONFIG.sa_threshold)
    assert np.any(weak.best_ra <= CONFIG.ra_threshold)
    assert REACH_WAIT.start_s <= weak.best_tick_s <= REACH_WAIT.end_s


def test_the_weak_stimulus_stands_fewer_noise_sigmas_above_the_noise_than_the_clear(classified):
    weak, clear = classified["weak film"], classified["clear film"]
    assert np.all(weak.ra_peak_sigmas() < clear.ra_peak_sigmas())
    assert np.all(weak.ra_wait_peak_sigmas() < clear.ra_wait_peak_sigmas())


def test_a_vibration_buried_in_noise_stays_within_the_noise_floor(classified):
    k = rule_sigmas(CONFIG.ra_rate_hz)
    assert classified["weak film"].failing_ra_within_floor(k)
    assert classified["late right finger"].failing_ra_within_floor(k) is None


def test_a_finger_that_touches_too_late_is_an_sa_miss(classified):
    late = classified["late right finger"]
    assert late.miss_class == SA_DID_NOT_MATCH
    assert late.best_sa[1] <= CONFIG.sa_threshold
    assert late.best_tick_s is None and late.ra_peak is None


def test_the_report_counts_each_class_per_object(classified):
    rate = CONFIG.ra_rate_hz
    misses = [TrialMiss("memorized/box/m00/a0", "box", classified["weak film"], None, rate),
              TrialMiss("memorized/box/m01/a0", "box", classified["late right finger"], None,
                        rate),
              TrialMiss("memorized/mug/m00/a0", "mug", classified["weak film"], 0.01, rate)]
    assert class_counts(misses) == {
        "box": {WEAK_DYNAMIC_STIMULUS: 1, WITHIN_FLOOR: 1, SA_DID_NOT_MATCH: 1,
                MATCHED_IN_REPLAY: 0},
        "mug": {WEAK_DYNAMIC_STIMULUS: 1, WITHIN_FLOOR: 1, SA_DID_NOT_MATCH: 0,
                MATCHED_IN_REPLAY: 0}}
    text = report_markdown(misses, [], 3, "memorized", "Missed")
    rows = [line for line in text.splitlines() if line.startswith("| memorized/")]
    assert [row.split("|")[-2].strip() for row in rows] == [
        WEAK_DYNAMIC_STIMULUS, SA_DID_NOT_MATCH, WEAK_DYNAMIC_STIMULUS]
    assert "codes" in text  # the mug's trial knows its converter's code


def test_a_wait_outside_the_trial_is_refused():
    wait = dataclasses.replace(REACH_WAIT, start_s=50.0, end_s=51.0)
    with pytest.raises(ValueError, match="not within the log"):
        classify_missed_wait(synthetic_grasp(IDEAL), EVENTS, wait, CONFIG)


# ---- The command, on a sweep record and its trial log -----------------------------------

# A synthetic grasp on the sweep's timeline: the first 2 s quiet (the matcher's RA noise
# period, controller.matching.ra_noise_quiet_s), contact at 2.5 s, the table at 4.8 s.
SWEEP_GRASP = SyntheticGraspConfig(duration_s=6.0, contact_s=2.5, place_s=4.8,
                                   sensors=SyntheticSensorsConfig(ra_noise=0.2,
                                                                  sa_noise_n=0.005, seed=5))


def synthetic_trial_log(config: SyntheticGraspConfig) -> TrialLog:
    """A TrialLog of the synthetic grasp `config`: SA on one taxel of each pad (its true
    taxels the noise-free forces, never negative), RA as the channels' film."""
    def zeros(times, width):
        return np.zeros((len(times), width))
    trial = synthetic_grasp(config)
    t_slow = np.array([0.0, trial.t_ra[-1]])
    taxels = zeros(trial.t_sa, 2 * TAXELS_PER_PAD)
    taxels[:, 0], taxels[:, TAXELS_PER_PAD] = trial.sa[:, 0], trial.sa[:, 1]
    true_taxels = zeros(trial.t_sa, 2 * TAXELS_PER_PAD)
    true_taxels[:, 0], true_taxels[:, TAXELS_PER_PAD] = (
        synthetic_sa(trial.t_sa, config, delay) for delay in (0.0, config.sensors.right_delay_s))
    # held as the loggers record it: from the first taxel sample at or after each RA time
    held = np.searchsorted(trial.t_sa, trial.t_ra - 1e-9, side="left")
    sa_at_ra = trial.sa[np.minimum(held, len(trial.t_sa) - 1)]
    pad_acceleration = zeros(trial.t_ra, 6)  # each film's RA along the pad's x
    pad_acceleration[:, 0], pad_acceleration[:, 3] = trial.ra[:, 0], trial.ra[:, 1]
    object_state = zeros(t_slow, 13)
    object_state[:, 0] = 1.0  # the identity orientation, a unit quaternion
    arm_q = zeros(t_slow, 6)
    arm_q[:, 1:3] = [3.0, 1.0]  # joints 2 and 3 within the JACO2's limits
    return TrialLog(t_sa=trial.t_sa, taxels=taxels, true_taxels=true_taxels, t_ra=trial.t_ra,
                    channels=np.hstack([sa_at_ra, trial.ra]),
                    pad_acceleration=pad_acceleration, t_slow=t_slow,
                    arm_q=arm_q, arm_q_desired=arm_q,
                    gripper_command=zeros(t_slow, 3), gripper_status=zeros(t_slow, 8),
                    phase=np.zeros(2), object_state=object_state,
                    meta={"controller": "memorized"})


def test_the_command_classes_a_sweeps_missed_waits_from_its_records_and_logs(tmp_path):
    spec = SweepSpec(objects=("thin_cylinder",), controllers=("memorized",), attempts=1,
                     base_seed=601, grid=((0.0, 0.0), (0.0, 0.015)))
    trials = [t.to_dict() for t in expand_trials(spec)]
    scenario = scenario_from_trial_spec(trials[0], nominal=True)
    sa_rate, ra_rate = sample_rates_hz(scenario)
    events = extract_memorized_events(
        synthetic_grasp(dataclasses.replace(SWEEP_GRASP, sensors=SyntheticSensorsConfig())),
        object_name="thin_cylinder", sa_rate_hz=sa_rate, ra_rate_hz=ra_rate,
        package_versions={}, object_description=object_description(scenario.object))
    save_memorized_events(tmp_path / "events", events.values())
    place = reason_of(Mode.PLACE, Observation(motion_done=True, time_since_motion_done=10.0,
                                              contact=(True, True)))
    reach = reason_of(Mode.REACH, Observation(closing_s=10.0))
    # The first trial waits in Place from 4.3 s, past the table at 4.8 s, and reads the
    # table through a film 100 times weaker; the second waits in Reach until 3.4 s, past the
    # left finger's contact at 2.5 s, and its right finger touches 1 s late, at 3.5 s.
    cases = [(dataclasses.replace(SWEEP_GRASP, sensors=dataclasses.replace(SWEEP_GRASP.sensors,
                                                                           ra_scale=0.01)),
              [entry(2.5, Mode.REACH, Mode.LOAD, "Reach-Load event", Trigger.MEMORIZED_EVENT),
               entry(3.0, Mode.LOAD, Mode.LIFT, "Load-Lift event", Trigger.MEMORIZED_EVENT),
               entry(3.5, Mode.LIFT, Mode.HOLD, "lift motion ended", Trigger.TIMER),
               entry(4.3, Mode.HOLD, Mode.PLACE, "held 3 s", Trigger.TIMER),
               entry(5.5, Mode.PLACE, place.mode, place.reason, Trigger.TIMER)]),
             (dataclasses.replace(SWEEP_GRASP, sensors=dataclasses.replace(SWEEP_GRASP.sensors,
                                                                           right_delay_s=1.0)),
              [entry(3.4, Mode.REACH, reach.mode, reach.reason)])]
    assert reach.mode == Mode.RE_REACH  # the timeout's first Re-Reach, its corrective action
    for trial, (config, transitions), actions in zip(trials, cases, ([], ["re_reach"])):
        write_record(tmp_path / "results", make_record(trial, result=whole_result(
            trial, transitions=transitions, hold_success=True, unload_success=False,
            final_mode=transitions[-1]["to"], corrective_actions=actions)))
        synthetic_trial_log(config).save(
            tmp_path / "logs" / trial_log_name(trial))
    out = tmp_path / "weak_stimuli.md"
    assert load_command().main([str(tmp_path / "results"), str(tmp_path / "logs"), "--events",
                                str(tmp_path / "events"), "--out", str(out)]) == 0
    rows = [line.split("|") for line in out.read_text().splitlines()
            if line.startswith("| memorized/")]
    assert [(row[1].strip(), row[2].split()[0], row[-2].strip()) for row in rows] == [
        (trials[0]["trial_id"], "place_unload", WEAK_DYNAMIC_STIMULUS),
        (trials[1]["trial_id"], "reach_load", SA_DID_NOT_MATCH)]
