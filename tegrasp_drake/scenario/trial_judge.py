"""A trial's judgement from its log and timeline (judge_trial: success as in the paper, the
physical events, detection latencies, false triggers), and the check that a trial log's
stored result is that judgement of its own data (stored_verdict_problem): run_trial judges
with it, and every reader of a trial log (trial_log_file.load_trial_log) judges again, so a
log whose result was edited is refused rather than shown."""

import types

from tegrasp_drake.control.corrective_actions import corrective_action_of
from tegrasp_drake.control.grasp_modes import Mode, Transition
from tegrasp_drake.events.transitions import event_transition
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.number_text import distinct_number_texts
from tegrasp_drake.scenario.grasp_outcome import (first_contact_time, grip_force_time,
                                                  grip_fraction_at, judge_grasp,
                                                  release_height_m, table_touch_time)
from tegrasp_drake.scenario.physical_event_search import physical_event_search_starts
from tegrasp_drake.scenario.trial_result import (FALSE_TRIGGER_MARGIN_S, HIT_EVENT,
                                                  HOLD_REQUIRED_S, UPRIGHT_TILT_DEG)

RESTING_HEIGHT_M = 0.005  # back on the table: within this of its starting height


def _event_transition(transition: Transition) -> str | None:
    """The event-triggered transition (reach_load, ...) that `transition` is, if any."""
    return event_transition(transition.from_mode.label, transition.to_mode.label)


def physical_event_times(log, transitions: list[Transition], grip_force: float,
                         object_config=None, hit_time_s: float = -1.0) -> dict:
    """The physical event behind each event transition taken, looked for from its search
    start (physical_event_search_starts: first contact and the grip settled after the last
    Reach, table touch after the last Place), and "hit" when the scenario's hit came within
    the simulated time."""
    events = {}
    if 0.0 <= hit_time_s <= float(log.t_slow[-1]):
        events[HIT_EVENT] = float(hit_time_s)
    search = {"reach_load": lambda since: first_contact_time(log, after=since),
              "load_lift": lambda since: grip_force_time(log, grip_force, after=since),
              "place_unload": lambda since: table_touch_time(log, object_config, after=since)}
    for name, since in physical_event_search_starts(transitions).items():
        events[name] = search[name](since)
    return events


def lift_grip_fraction(log, transitions: list[Transition], grip_force: float
                       ) -> float | None:
    """The weaker pad's true force at the first Load -> Lift as a fraction of the settled
    grip (grasp_outcome.grip_fraction_at); None when the trial never lifted from Load. The
    grip is the one settled after the last Reach before that lift, as for the Load-Lift
    physical event (physical_event_times): a close before a Re-Reach is let go, and the grip
    it first reached, measured while the gripper opens, can be a rub of a few tenths of a
    newton."""
    reach, lift = 0.0, None
    for entry in transitions:
        if entry.from_mode == Mode.LOAD and entry.to_mode == Mode.LIFT:
            lift = entry.t
            break
        if entry.to_mode == Mode.REACH:
            reach = entry.t
    return None if lift is None else grip_fraction_at(log, lift, grip_force, after=reach)


def judge_trial(log, transitions: list[Transition], scenario) -> dict:
    """Success as in the paper (Sec. IV-C), from the ground truth: hold = lifted and held
    at least 3 s; unload = after Unload, upright on the table, released, gripper retracted.
    release_height_m: the object's lowest point above the table top when Unload began (the
    first transition to Unload: the gripper's open command); None without one."""
    outcome = judge_grasp(log, target_xy=scenario.placement.expected_xy,
                          grip_force=scenario.grasp.grip_force, object_config=scenario.object)
    hold_success = outcome.hold_time_s >= HOLD_REQUIRED_S
    reached = [entry.to_mode for entry in transitions]
    final_mode = reached[-1] if reached else Mode.REACH
    z = log.object_state[:, 6]
    resting = abs(z[-1] - z[0]) < RESTING_HEIGHT_M
    unload_success = bool(hold_success and Mode.UNLOAD in reached and final_mode == Mode.DONE
                          and outcome.final_tilt_deg < UPRIGHT_TILT_DEG and outcome.released
                          and resting)
    grip_force = scenario.grasp.grip_force
    physical = physical_event_times(log, transitions, grip_force, scenario.object,
                                    hit_time_s=scenario.disturbance.hit_time_s)
    latency, false_triggers = {}, 0
    for entry in transitions:
        name = _event_transition(entry)
        if name is None or not entry.trigger.is_event:
            continue
        if physical.get(name) is None or entry.t < physical[name] - FALSE_TRIGGER_MARGIN_S:
            false_triggers += 1
        else:
            latency[name] = entry.t - physical[name]
    corrective = [action for action in (corrective_action_of(e.from_mode, e.to_mode, e.trigger)
                                        for e in transitions) if action is not None]
    unload = next((e.t for e in transitions if e.to_mode == Mode.UNLOAD), None)
    return {"hold_success": bool(hold_success), "unload_success": unload_success,
            "final_mode": final_mode.label, "hold_time_s": outcome.hold_time_s,
            "lift_height_m": outcome.lift_height_m, "final_tilt_deg": outcome.final_tilt_deg,
            "placement_error_m": outcome.placement_error_m, "released": outcome.released,
            "release_height_m": None if unload is None else release_height_m(
                log, unload, scenario.object),
            "physical_events": physical, "detection_latency_s": latency,
            "false_triggers": false_triggers, "lift_grip_fraction": lift_grip_fraction(
                log, transitions, grip_force),
            "corrective_actions": corrective,
            "failure": next((e.reason for e in transitions if e.to_mode == Mode.FAILED), "")}




# The result fields that are times [s] the judge reads off the log's samples: hold_time_s a
# span of the object state's (slow) sample times (grasp_outcome.longest_run_s), an event a
# sample's time, a latency a transition's time minus an event's. A stored time within one
# slow sample period of the judge's is the same reading at the log's time resolution (a
# lift that began or ended between two samples can be read from either); a time farther
# off claims a hold or an event the samples do not show.
JUDGED_TIMES = ("hold_time_s", "physical_events", "detection_latency_s")
# The result fields that are measures [m, deg, a ratio] of the logged states: a judgement
# re-run on the same float64 samples by the same code agrees to rounding (1e-15 relative);
# 1e-9 lets another numpy's rounding by and no edit of a digit any reader shows (a
# millimetre, a tenth of a degree, a percent).
JUDGED_MEASURES = ("lift_height_m", "final_tilt_deg", "placement_error_m",
                   "release_height_m", "lift_grip_fraction")
MEASURE_TOLERANCE = 1e-9


def _value_text(value) -> str:
    """A stored or judged result value as a message gives it (JSON's words)."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    return shorten(repr(value), 120)


def _disagreement(label: str, stored, judged, tolerance: float, unit: str) -> str | None:
    """`stored` and `judged` (one result field's, or one entry of it, named `label`) in
    words, when they differ by more than `tolerance` (0: exactly), else None."""
    numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool)
                  for v in (stored, judged))
    if numbers and tolerance > 0:
        if abs(stored - judged) <= tolerance:
            return None
        ours, theirs = distinct_number_texts(stored, judged)
        return f"{label} is {ours}{unit}, but the log's data judge it {theirs}{unit}"
    if stored == judged and (numbers or type(stored) is type(judged)):
        return None
    return f"{label} is {_value_text(stored)}, but the log's data judge it {_value_text(judged)}"


def _field_problem(field: str, label: str, stored, judged, period_s: float) -> str | None:
    """What is wrong if a stored result field (or an entry of it, `label`) disagrees with the
    judge's: times within one slow sample period (JUDGED_TIMES), measures within
    MEASURE_TOLERANCE, the rest (the success flags, the final mode, counts, names) exactly;
    None when they agree."""
    if isinstance(judged, dict):
        if not isinstance(stored, dict) or set(stored) != set(judged):
            return (f"{label} names {_value_text(sorted(stored))}, but the log's data judge "
                    f"{_value_text(sorted(judged))}")
        for key, value in judged.items():
            problem = _field_problem(field, f"{label} '{shorten(key)}'", stored[key], value,
                                     period_s)
            if problem:
                return problem
        return None
    if field in JUDGED_TIMES:
        return _disagreement(label, stored, judged, period_s, " s")
    if field in JUDGED_MEASURES and None not in (stored, judged):
        return _disagreement(label, stored, judged, MEASURE_TOLERANCE * max(1.0, abs(judged)), "")
    return _disagreement(label, stored, judged, 0.0, "")


def stored_verdict_problem(meta: dict, arrays: dict, scenario) -> str | None:
    """What is wrong if a trial log's stored result (meta 'result', a TrialResult's JSON form
    already checked by itself) is not what judge_trial makes of the log's own data (its
    object states, gripper status and noise-free taxels) and timeline (meta 'transitions')
    under its Scenario (`scenario`: the object's placement, grip force, object and hit),
    else None: the first field judge_trial computes that the result holds and that differs
    (hold_success, hold_time_s, unload_success, ...; _field_problem's tolerances), named
    with both values. A result with no scenario to judge it by is refused: run_trial stores
    both."""
    data = meta.get("result")
    if data is None:
        return None
    if scenario is None:
        return ("meta 'result' comes without the 'scenario' its trial ran (a trial's log "
                "stores both), so it cannot be judged again from the log's data")
    transitions = [Transition.from_dict(entry) for entry in meta.get("transitions", [])]
    judged = judge_trial(types.SimpleNamespace(meta=meta, **arrays), transitions, scenario)
    times = arrays["t_slow"]
    period = float(times[-1] - times[0]) / (len(times) - 1)  # one period: time_bases_problem
    for name, value in judged.items():
        if name not in data:  # a field added later, absent from an older result
            continue
        problem = _field_problem(name, f"'{name}'", data[name], value, period)
        if problem:
            return (f"meta 'result' field {problem} (judge_trial re-run on its object, gripper "
                    "and taxel samples and its transitions; a result is that judgement)")
    return None
