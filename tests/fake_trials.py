"""A cheap, deterministic stand-in for the closed-loop trial function (no tests here).

The sweep tests run the sweep machinery with these functions instead of the Drake
simulation. The outcome is a pure function of the trial dict: the seed gives uniform
numbers shared by every controller (so the comparison is paired, as with the real
trial), and each controller turns them into success with its own probability.
"""

import hashlib
import os
import pathlib
import time

# P(success) by controller and placement: (well placed, misplaced).
_HOLD_PROBABILITY = {"memorized": (0.95, 0.85), "heuristic": (0.9, 0.7),
                     "open_loop": (0.8, 0.4), "taxel_aware": (0.95, 0.9)}
_UNLOAD_PROBABILITY = {"memorized": (0.9, 0.8), "heuristic": (0.8, 0.6),
                       "open_loop": (0.5, 0.3), "taxel_aware": (0.9, 0.85)}
SLOW_TRIAL_S = 0.05


def timeline_ending(final_mode: str, t: float = 1.0,
                    reason: str = "the test's timeline") -> list[dict]:
    """A hand-built result's timeline: one timed transition at `t` [s] from Reach into
    `final_mode` ([] for Reach), since a result's final mode is its last transition's, for
    `reason` (a result's failure is the reason of its transition to Failed). No event
    transition: nothing in it counts as a match or a false trigger."""
    if final_mode == "Reach":
        return []
    return [{"t": t, "from": "Reach", "to": final_mode, "trigger": "timer", "reason": reason}]


def whole_result(trial: dict | None = None, **fields) -> dict:
    """A TrialResult's whole JSON form (TrialResult.from_dict requires every field): `fields`
    over the defaults of a trial that took no transition, its identity (object, controller,
    seed, offset) that of `trial` (a sweep trial's dict) where it names them."""
    import dataclasses
    from tegrasp_drake.scenario.trial_result import TrialResult
    result = {field.name: (field.default_factory() if field.default is dataclasses.MISSING
                           else field.default)
              for field in dataclasses.fields(TrialResult) if field.name != "log"}
    result.update(transitions=[], final_mode="Reach")
    trial = trial or {}
    for field, key in (("object", "object_name"), ("controller", "controller"),
                       ("seed", "seed")):
        if trial.get(key) is not None:
            result[field] = trial[key]
    if "marker_dx_m" in trial and "perturbation" in trial:  # where a sweep puts the object
        jitter = trial["perturbation"]
        result["offset_m"] = [trial["marker_dx_m"] + jitter["dx_m"],
                              trial["marker_dy_m"] + jitter["dy_m"]]
    return {**result, **fields}


def result_of_trial(result: dict, trial: dict) -> dict:
    """A whole `result` as `trial`'s (a sweep trial's dict): its object, controller, seed and
    offset those the trial gives (as a sweep's records must have them)."""
    identity = whole_result(trial)
    return {**result, **{name: identity[name]
                         for name in ("object", "controller", "seed", "offset_m")}}


def _uniforms(trial, count):
    digest = hashlib.sha256(f"{trial['pair_id']}|{trial['seed']}".encode()).digest()
    return [int.from_bytes(digest[4 * k:4 * k + 4], "big") / 2.0 ** 32 for k in range(count)]


def event_trigger(controller: str) -> str:
    """The trigger of `controller`'s event transitions: its detector's (ControllerEntry.
    triggers), the timer for the open-loop script, which has none."""
    from tegrasp_drake.control.controller_registry import controller_entry
    fired = controller_entry(controller).triggers()
    return next((trigger.value for trigger in fired if trigger.is_event), "timer")


def fake_trial(trial):
    u_hold, u_unload, u_latency, u_false = _uniforms(trial, 4)
    placement = 0 if trial["well_placed"] else 1
    hold = u_hold < _HOLD_PROBABILITY[trial["controller"]][placement]
    unload = hold and u_unload < _UNLOAD_PROBABILITY[trial["controller"]][placement]
    trigger = event_trigger(trial["controller"])
    closed_loop = trigger != "timer"  # the open-loop script neither detects nor corrects
    latency = round(0.01 + 0.05 * u_latency, 6) if closed_loop else None
    re_reach = [{"t": 0.4, "from": "Reach", "to": "Re-Reach", "trigger": "corrective",
                 "reason": "only the left finger touched"},
                {"t": 0.7, "from": "Re-Reach", "to": "Reach", "trigger": "corrective",
                 "reason": "re-centred"}] if not trial["well_placed"] and hold else []
    re_reach = re_reach if closed_loop else []
    return whole_result(trial, **{
        "hold_success": hold,
        "unload_success": unload,
        # Unloaded: judged only in a Done trial, the object released; else it stopped in Load.
        "final_mode": "Done" if unload else "Load",
        "released": unload,
        # A misplaced trial that held re-centred first (one Re-Reach, its corrective action).
        "transitions": (re_reach + [{"t": 1.0, "from": "Reach", "to": "Load",
                                     "trigger": trigger, "reason": "Reach-Load event"}]
                        + ([{"t": 2.0, "from": "Load", "to": "Done", "trigger": "timer",
                             "reason": "the test's timeline"}] if unload else [])),
        "corrective_actions": ["re_reach"] if re_reach else [],
        # The Reach-Load detection's latency behind its physical event (first contact).
        "physical_events": {} if latency is None else {"reach_load": 1.0 - latency},
        "detection_latency_s": {} if latency is None else {"reach_load": latency},
        "false_triggers": int(u_false < 0.2),
        "sim_time_s": 8.0,
        "wall_time_s": 0.0,
    })


def slow_fake_trial(trial):
    """fake_trial after a pause, so a sweep of a few dozen trials takes seconds."""
    time.sleep(SLOW_TRIAL_S)
    result = fake_trial(trial)
    result["wall_time_s"] = SLOW_TRIAL_S  # Nominal, so records stay deterministic.
    return result


def started_fake_trial(trial):
    """Says it started (a file named for its trial in the folder $FAKE_TRIALS_STARTED), then
    runs for a minute: a trial the sweep is in the middle of when a test signals it."""
    folder = pathlib.Path(os.environ["FAKE_TRIALS_STARTED"])
    (folder / trial["trial_id"].replace("/", ".")).touch()
    time.sleep(60.0)
    return fake_trial(trial)


def failing_fake_trial(trial):
    """Raises on attempt 1, like a simulation that diverges."""
    if trial["attempt"] == 1:
        raise RuntimeError(f"simulated divergence in {trial['trial_id']}")
    return fake_trial(trial)


def invalid_result_trial(trial):
    """Returns a result without the booleans the table needs."""
    return {"hold_success": 1, "unload_success": None}


def dying_fake_trial(trial):
    """Kills its worker process on the well-placed box, attempt 0 (a hard crash)."""
    if trial["pair_id"] == "box/m11/a0":
        os._exit(3)
    return fake_trial(trial)


def numpy_fake_trial(trial):
    """fake_trial with numpy booleans and numbers, as a simulation tends to return."""
    import numpy as np
    result = fake_trial(trial)
    return {**result, "hold_success": np.bool_(result["hold_success"]),
            "unload_success": np.bool_(result["unload_success"]),
            "false_triggers": np.int64(result["false_triggers"]),
            "sim_time_s": np.float64(result["sim_time_s"])}


def process_reporting_fake_trial(trial):
    """fake_trial's result plus the process that ran it, after a short pause so that every
    worker of a pool takes some of the trials."""
    import os
    import time
    time.sleep(0.2)
    return {**fake_trial(trial), "worker_pid": os.getpid()}


def fake_trial_with_events(trial, *, events_dir):
    """fake_trial of a transfer cell, which hands each trial its memorizing world's events
    folder: the result names that folder, so a test can check which events a cell used."""
    result = fake_trial(trial)
    load = next(k for k, entry in enumerate(result["transitions"]) if entry["to"] == "Load")
    result["transitions"][load] = {"t": 1.0, "from": "Reach", "to": "Load",
                                "trigger": event_trigger(trial["controller"]),
                                "reason": "Reach-Load event"}
    result["physical_events"] = {"reach_load": 0.97}
    if result["detection_latency_s"]:  # the detection's at 1 s, 30 ms behind its event
        result["detection_latency_s"] = {"reach_load": 1.0 - 0.97}
    result["events_dir"] = str(events_dir)
    return result


def stuck_fake_trial(trial):
    """fake_trial, except for a trial carrying a "marker" path: it writes MARKER.started
    (its process id), runs for two minutes, then writes MARKER.finished: a long simulation
    that an interrupted sweep must abandon rather than wait for."""
    marker = trial.get("marker")
    if marker:
        with open(marker + ".started", "w") as stream:
            stream.write(str(os.getpid()))
        time.sleep(120.0)
        with open(marker + ".finished", "w") as stream:
            stream.write("finished")
    return fake_trial(trial)


def slow_fake_trial_with_events(trial, *, events_dir):
    """slow_fake_trial of a transfer cell or sensitivity point: the result names the events'
    world (the folder's name, so that records in two output folders compare equal)."""
    import pathlib
    result = slow_fake_trial(trial)
    result["events_world"] = pathlib.Path(events_dir).name
    return result


def fake_trial_reading_events(trial, *, events_dir):
    """fake_trial of a sensitivity point or transfer cell that reads its controller's events
    as the real trial does (trial_events): the result gives the pad modulus [Pa] of the
    scenario each event was recorded in (None where the recording did not name one)."""
    import yaml
    from tegrasp_drake.sweep.trial_function import trial_events
    _, events, _ = trial_events(trial, events_dir)
    result = fake_trial(trial)
    result["events_pad_modulus_pa"] = sorted(
        {(yaml.safe_load(event.scenario) or {}).get("tactile", {}).get("pad_modulus_pa")
         for event in events.values()}, key=str)
    return result


def fake_memorized_trial(trial, *, events_dir=None):
    """fake_trial, as a trial function that matches against memorized events: the sweep
    records the events' identity as it does run_trial_from_spec's."""
    return fake_trial(trial)


def _events_identities(trials, events_dir=None):
    from tegrasp_drake.sweep.trial_function import events_identities
    return events_identities(trials, events_dir)


fake_memorized_trial.events_identities = _events_identities


def full_disk_fake_trial(trial, *, log_dir):
    """fake_trial that saves its log in `log_dir` (`tegrasp sweep --logs`) as the sweep's
    trial function does, through save_log_copy, on a full disk: the write fails with ENOSPC
    (the workers are separate processes, so the failing write is here, not monkeypatched)."""
    import errno
    import pathlib
    from tegrasp_drake.scenario.trial_log_file import save_log_copy

    def save(path):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    result = fake_trial(trial)
    save_log_copy(save, pathlib.Path(log_dir) / f"{trial['trial_id'].replace('/', '.')}.log",
                  result)
    return result


def small_trial_log():
    """A small TrialLog that load_trial_log reads and TrialLog.save writes (probes.trial_log's
    eleven-sample arrays), for tests of how a log is written rather than of what it holds."""
    import tempfile
    from tegrasp_drake.scenario.trial_log_file import load_trial_log
    from tests.bad_input.probes import trial_log
    with tempfile.TemporaryDirectory() as folder:
        return load_trial_log(trial_log(pathlib.Path(folder) / "small.npz"))
