"""The sweep's trial function: a sweep trial (a TrialSpec.to_dict()) turned into its
scenario, run with its memorized events (runs/trial.py) and returned as its result dict;
`check_sweep_events` checks before a sweep starts that every trial's events are there."""

import dataclasses
import hashlib
import logging
import pathlib
from typing import Annotated

import numpy as np

from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.sweep.records import TRIALS_FOLDER, canonical_json, record_file_name
from tegrasp_drake.scenario.trial_log_file import (TrialLog, TrialLogError, load_trial_log,
                                                   logged_scenario, save_log_copy)
from tegrasp_drake.rig.api_boundary import INPUT_FOLDER, OUTPUT_FOLDER, PathLike, public_api
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.scenario.object_placement import result_offset_problem
from tegrasp_drake.rig.typed_yaml import ConfigError

logger = logging.getLogger(__name__)


def scenario_from_trial_spec(trial: dict, *, nominal: bool = False):
    """The Scenario of one sweep trial (a TrialSpec.to_dict()): the default scenario with the
    sweep's overrides and the trial's object (perturbed unless `nominal`), placement, seed and
    controller."""
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.scenario.scenario import LoadScenario, resolve_object, validate
    from tegrasp_drake.rig.typed_yaml import RefinedSettings
    from tegrasp_drake.sweep.spec import user_object
    p = trial["perturbation"]
    base = LoadScenario(overrides=RefinedSettings(trial.get("scenario_overrides", ())),
                        controller=trial["controller"])
    definition = trial.get("object_definition")
    if definition:
        obj = user_object(trial["object_name"], definition)
    else:
        obj = resolve_object(ObjectConfig(name=trial["object_name"]))
    if not nominal:
        obj = dataclasses.replace(obj, mass=obj.mass * float(p["mass_scale"]),
                                  friction=obj.friction * float(p["friction_scale"]))
    scenario = dataclasses.replace(
        base, object=obj, random_seed=int(trial["seed"]), placement=dataclasses.replace(
            base.placement, offset=[float(trial["marker_dx_m"]) + float(p["dx_m"]),
                                    float(trial["marker_dy_m"]) + float(p["dy_m"])],
            yaw_deg=float(np.degrees(p["yaw_rad"]))))
    if not trial.get("sensor_noise", True):
        scenario = dataclasses.replace(
            scenario, tactile=dataclasses.replace(
                scenario.tactile, noise_std_n=0.0, capacitive=dataclasses.replace(
                    scenario.tactile.capacitive, noise_std_counts=0.0)),
            vibration=dataclasses.replace(scenario.vibration, noise_std_mps2=0.0,
                                          adc_noise_lsb=0.0))
    return validate(scenario, f"sweep trial {trial['trial_id']}")


def trial_log_name(trial: dict, events: dict | None = None) -> str:
    """A sweep trial's log file name: its id ('/' as '.') and the first 12 hex digits of the
    SHA-256 of the trial spec and, for a trial that matched memorized events, their content
    (`events`: its events_identity, a record's "events"), so sweeps sharing a --logs folder
    keep their own logs, those run against other events too."""
    named = trial if events is None else {"trial": trial, "events": events["sha256"]}
    digest = hashlib.sha256(canonical_json(named).encode("utf-8")).hexdigest()[:12]
    return f"{trial['trial_id'].replace('/', '.')}.{digest}.npz"


def record_log_problem(log: TrialLog, record: dict) -> str | None:
    """Why `log` (a loaded trial log) is not the log of `record`'s trial, or None: the
    controller it ran (meta 'controller'), the object it grasped, its seed (the scenario's
    random_seed) and where it placed the object (placement.offset), in its scenario and its
    result where it holds them, must be the record's trial's (controller, object_name, seed,
    marker + perturbation offset: result_offset_problem). A log copied or renamed onto another
    trial's name holds another trial."""
    trial = record["trial"]
    scenario, _ = logged_scenario(log.meta)
    jitter = trial["perturbation"]
    offset = [trial["marker_dx_m"] + jitter["dx_m"], trial["marker_dy_m"] + jitter["dy_m"]]
    result = log.meta.get("result") or {}
    checks = [("meta 'controller'", log.meta.get("controller"), "controller",
               trial["controller"])]
    if scenario is not None:
        checks += [("meta 'scenario' object.name", scenario.object.name, "object_name",
                    trial["object_name"]),
                   ("meta 'scenario' random_seed", scenario.random_seed, "seed", trial["seed"]),
                   ("meta 'scenario' placement.offset", list(scenario.placement.offset),
                    "marker + perturbation offset", offset)]
    checks += [(f"meta 'result' {name}", result[name], trial_field, expected)
               for name, trial_field, expected in (("object", "object_name",
                                                    trial["object_name"]),
                                                   ("seed", "seed", trial["seed"]),
                                                   ("offset_m", "marker + perturbation offset",
                                                    offset))
               if name in result]
    for field, logged, trial_field, expected in checks:
        if field.endswith("offset") or field.endswith("offset_m"):
            same = result_offset_problem(logged, expected) is None
        else:
            same = logged == expected
        if not same:
            return (f"its {field} is {shorten(repr(logged))}, but the record's trial's "
                    f"{trial_field} is {shorten(repr(expected))}")
    return None


def load_record_log(path, record: dict, *, rejudge: bool = True) -> TrialLog:
    """The trial log at `path`, read for `record` (its name trial_log_name's for the record);
    TrialLogError naming the log, the record and the field when it is no log or is another
    trial's (record_log_problem). rejudge: load_trial_log's."""
    log = load_trial_log(path, rejudge=rejudge)
    problem = record_log_problem(log, record)
    if problem:
        raise TrialLogError(
            f"trial log '{path}' is not the log of record {TRIALS_FOLDER}/"
            f"{record_file_name(record['trial_id'])}: {problem}; a log named for a record "
            "holds that trial: give the --logs folder of the sweep that wrote the records")
    return log


def trial_events(trial: dict, events_dir=None) -> tuple:
    """(scenario, transition events or None, corrective events or None) of a sweep trial,
    from `events_dir`, else the user's folder, then the package's; recorded on the trial's
    unperturbed object. MemorizedEventError."""
    from tegrasp_drake.scenario.scenario_events import (load_controller_events,
                                                       load_corrective_events)
    scenario = scenario_from_trial_spec(trial)
    nominal = scenario_from_trial_spec(trial, nominal=True).object
    events = corrective_events = None
    if scenario.controller.events_folder is not None:
        events = load_controller_events(scenario, events_dir, nominal_object=nominal)
    if scenario.controller.memorized_corrective.events:
        corrective_events = load_corrective_events(scenario, events_dir,
                                                   nominal_object=nominal)
    return scenario, events, corrective_events


class SweepEventsError(ConfigError):
    """A sweep trial's memorized events missing or unusable: bad input (exit 1), unlike a
    trial's scenario refused, which refuses the spec (ConfigError, exit 2)."""


def check_sweep_events(trials, events_dir=None) -> None:
    """SweepEventsError naming the trial, file and remedy when a trial's events are missing or
    of another object (once per object and controller, before anything runs); a warning for
    another hand's. ConfigError when the trial's scenario is refused (the spec's fault)."""
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.scenario.scenario_events import another_worlds_events
    checked = set()
    for trial in trials:
        key = (trial["object_name"], trial["controller"])
        if key in checked:
            continue
        checked.add(key)
        try:
            scenario, events, _ = trial_events(trial, events_dir)
        except MemorizedEventError as error:
            raise SweepEventsError(f"trial {trial['trial_id']} ({trial['controller']} on "
                                   f"'{trial['object_name']}'): {error}") from None
        warning = events and another_worlds_events(scenario, events)
        if warning:
            logger.warning(warning)


def events_identity(events: dict | None, corrective_events: dict | None,
                    events_dir=None) -> dict | None:
    """What a record says of the memorized events a trial matched against: the SHA-256 of
    their content (each event's file text, as save_memorized_events writes it, in grasp
    order; the corrective events after them) and the folder asked for, absolute (None: your
    events folder, then the package's). None for a trial that reads no events."""
    from tegrasp_drake.events.event_file import event_json_text, event_to_json
    chosen = [event for group in (events, corrective_events) if group
              for event in group.values()]
    if not chosen:
        return None
    digest = hashlib.sha256()
    for event in chosen:
        digest.update(f"{event.object_name}/{event.transition}\n".encode("utf-8"))
        digest.update(event_json_text(event_to_json(event)).encode("utf-8"))
    # Resolved: a record read from another working folder still names the right one.
    return {"folder": None if events_dir is None else str(pathlib.Path(events_dir).resolve()),
            "sha256": digest.hexdigest()}


def events_identities(trials, events_dir=None) -> dict[str, dict | None]:
    """{trial id: events_identity} of sweep trials (TrialSpec.to_dict()) from `events_dir` as
    run_trial_from_spec reads them, the events loaded once per object, controller and
    overrides. SweepEventsError naming the trial, as check_sweep_events, for missing events."""
    from tegrasp_drake.events import MemorizedEventError
    identities, by_setting = {}, {}
    for trial in trials:
        setting = canonical_json([trial["object_name"], trial["controller"],
                                  trial.get("object_definition"),
                                  trial.get("scenario_overrides", [])])
        if setting not in by_setting:
            try:
                _, events, corrective_events = trial_events(trial, events_dir)
            except MemorizedEventError as error:
                raise SweepEventsError(f"trial {trial['trial_id']} ({trial['controller']} on "
                                       f"'{trial['object_name']}'): {error}") from None
            by_setting[setting] = events_identity(events, corrective_events, events_dir)
        identities[trial["trial_id"]] = by_setting[setting]
    return identities


@public_api
def run_trial_from_spec(trial: dict, *,
                        events_dir: Annotated[PathLike | None, INPUT_FOLDER] = None,
                        log_dir: Annotated[PathLike | None, OUTPUT_FOLDER] = None) -> dict:
    """The sweep's trial function: runs `trial` (a TrialSpec.to_dict()) and returns its result
    dict (its log also in `log_dir`); ConfigError when it is no sweep trial; LogNotWritten,
    carrying the result, when the log cannot be written in `log_dir`."""
    from tegrasp_drake.sweep.spec import trial_dict_problem
    problem = trial_dict_problem(trial)
    if problem:
        raise ConfigError(f"run_trial_from_spec: argument 'trial': {problem}")
    scenario, events, corrective_events = trial_events(trial, events_dir)
    run = run_trial(scenario, events=events, corrective_events=corrective_events)
    result = run.to_dict()
    if log_dir is not None:
        name = trial_log_name(trial, events_identity(events, corrective_events, events_dir))
        save_log_copy(run.log.save, pathlib.Path(log_dir) / name, result)
    return result


# The runner records what run_trial_from_spec's trials matched against (sweep/runner.py).
run_trial_from_spec.events_identities = events_identities
