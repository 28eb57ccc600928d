"""The memorized events a scenario's controller reads: its object's, for its controller and
its hand, from the events search path (rig/paths.py), checked against the object they were
recorded on. They read the whole Scenario, so they live with it; the controller itself takes
the events given."""

import functools
import pathlib
from typing import Annotated

from tegrasp_drake.control.grasp_controller import controller_events_folders
from tegrasp_drake.rig import paths
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.rig.typed_yaml import YamlSyntaxError, parse_yaml
from tegrasp_drake.scenario.scenario import Scenario
from tegrasp_drake.rig.api_boundary import SEARCHED_FOLDER, PathLike, public_api


def _hand_folder(scenario) -> str:
    return gripper_hand(scenario.gripper.model).events_folder


@public_api
def load_controller_events(scenario: Scenario,
                           events_dir: Annotated[PathLike | None, SEARCHED_FOLDER] = None, *,
                           nominal_object: ObjectConfig | None = None) -> dict:
    """The memorized events of the scenario's object for its controller, from `events_dir` or else
    the user's events folder or the package's. MemorizedEventError (naming the folders, the file and
    the command that records them) when missing or recorded on an object that differs from the
    scenario's (or `nominal_object`) in a field not in controller.event_object_may_differ."""
    return _load_checked_events(
        scenario, controller_events_folders(scenario.controller, events_dir,
                                            _hand_folder(scenario)),
        nominal_object=nominal_object)


@public_api
def load_corrective_events(scenario: Scenario,
                           events_dir: Annotated[PathLike | None, SEARCHED_FOLDER] = None, *,
                           nominal_object: ObjectConfig | None = None) -> dict:
    """The corrective events (lift_load, hold_avoid) of the scenario's object from the search path's
    CORRECTIVE_EVENTS_FOLDER, checked against the object as load_controller_events checks."""
    from tegrasp_drake.rig.objects import CORRECTIVE_EVENTS_FOLDER
    from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
    folders = [folder / CORRECTIVE_EVENTS_FOLDER
               for folder in paths.events_search_path(events_dir, _hand_folder(scenario))]
    return _load_checked_events(scenario, folders, nominal_object=nominal_object,
                                required=CORRECTIVE_TRANSITIONS,
                                record_hint="`python analysis/record_corrective_events.py "
                                "LOGS --object NAME`, or --set "
                                "controller.memorized_corrective.events=[]")


def _load_checked_events(scenario, folders, *, nominal_object=None, required=None,
                         record_hint: str = "") -> dict:
    """The scenario object's events from the first of `folders` that lists it, checked
    against the object (load_controller_events)."""
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.events.events_folder import find_memorized_events
    from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
    from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
    name = scenario.object.name
    try:
        folder, events = find_memorized_events(folders, name,
                                               required=required or REQUIRED_TRANSITIONS)
    except MemorizedEventError as e:
        if record_hint:  # not `tegrasp record-events`: say what makes these
            e.args = (f"{e.args[0].split(' Record them')[0]} Record them with "
                      f"{record_hint}.",)
            raise
        if name not in BUILTIN_OBJECTS:
            e.args = (f"{e.args[0]} For your own object: `tegrasp record-events --scenario "
                      "FILE --scenario-name NAME` (or the same --set options you gave "
                      "here), or run `--controller heuristic`.",)
        raise
    check_recorded_runs(folder, events)
    check_events_object(scenario, folder, events, nominal_object=nominal_object)
    return events


def check_events_object(scenario, folder, events: dict, *,
                        nominal_object: ObjectConfig | None = None) -> None:
    """MemorizedEventError naming the event file when an event of `events` (read from
    `folder`) records no object or one that differs from the scenario's object (or
    `nominal_object`) in a field not in controller.event_object_may_differ: events are used
    only on the object they felt (load_controller_events, tegrasp replay)."""
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.rig.objects import description_differences, object_description
    name = scenario.object.name
    current = object_description(nominal_object or scenario.object)
    allowed = set(scenario.controller.event_object_may_differ)
    for event in events.values():
        if not event.object_description:
            error = MemorizedEventError(folder / event.relative_path(),
                                        "records no object description", name)
            raise error
        differences = [d for d in description_differences(event.object_description, current)
                       if d.split(" ", 1)[0] not in allowed]
        if differences:
            path = folder / event.relative_path()
            raise MemorizedEventError(
                path, f"the memorized events of '{name}' were recorded on another object: "
                f"{'; '.join(differences)}", name,
                remedy="Give your object its own name and record its events (`tegrasp "
                "record-events` with the same scenario options), or accept the difference "
                "with --set controller.event_object_may_differ="
                f"[{','.join(d.split(' ', 1)[0] for d in differences)}].")


@functools.lru_cache(maxsize=16)
def _recorded_run(scenario_text: str) -> tuple[float, float, float] | None:
    """(time limit [s], SA rate [Hz], RA rate [Hz]) of the scenario an event's `scenario`
    text holds, or None when the text is no whole scenario this version reads (a note, e.g.
    an ensemble's combined runs, an empty text, or an older layout). A recording stores the
    whole scenario it ran (scenario_to_yaml), its object described."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.grasp_diagram import scenario_time_limit
    from tegrasp_drake.scenario.scenario import sample_rates_hz, scenario_from_yaml
    try:
        recorded = scenario_from_yaml(scenario_text, "a memorized event's scenario")
        if not (recorded.object.shape and recorded.object.size):
            return None
        return (scenario_time_limit(recorded), *sample_rates_hz(recorded))
    except (ConfigError, ValueError, TypeError, KeyError, IndexError, AttributeError):
        return None


def recorded_run_problem(event) -> str | None:
    """Why `event` cannot have been cut from the run it says it was recorded in, or None: its
    window (transition_time_s - pre_transition_s, window_s long) must end within that run,
    by its scenario's time limit when its `scenario` text is a scenario, else by the longest
    run any scenario allows; and its rates must be that scenario's sample rates, at which a
    recording cuts its windows (recording/campaign.cut_events)."""
    from tegrasp_drake.rig.number_text import number_text
    from tegrasp_drake.scenario.grasp_diagram import longest_trial_s
    run = _recorded_run(event.scenario)
    start = event.transition_time_s - event.pre_transition_s
    end = start + event.window_s
    if run is None:
        limit, whose = longest_trial_s(), "the longest run any scenario allows"
    else:
        limit, whose = run[0], ("the time limit of the scenario it was recorded in (its "
                                "`scenario` field)")
    if end > limit:
        return (f"field 'transition_time_s' is {number_text(event.transition_time_s)} s, so "
                f"its window ({number_text(start)} to {number_text(end)} s) ends after "
                f"{whose}, {number_text(limit)} s: no recorded run holds it")
    if run is not None:
        for field, rate, recorded, setting in (
                ("sa_rate_hz", event.sa_rate_hz, run[1], "tactile.sample_rate_hz"),
                ("ra_rate_hz", event.ra_rate_hz, run[2], "vibration.sample_rate_hz")):
            if rate != recorded:
                return (f"field '{field}' is {number_text(rate)} Hz, but the scenario it was "
                        f"recorded in (its `scenario` field) samples at "
                        f"{number_text(recorded)} Hz ({setting}), the rate a recording cuts "
                        "its windows at")
    return None


def check_recorded_runs(folder, events: dict) -> None:
    """MemorizedEventError naming the file and field of the first of `events` (loaded from
    `folder`, by transition) that recorded_run_problem refuses."""
    from tegrasp_drake.events import MemorizedEventError
    for event in events.values():
        problem = recorded_run_problem(event)
        if problem:
            raise MemorizedEventError(pathlib.Path(folder) / event.relative_path(), problem,
                                      event.object_name)


# The hand of a scenario whose gripper section has no `model` (the prismatic one).
HAND_BEFORE_THE_MODEL_SETTING = "prismatic"


def recorded_setting(event, section: str, key: str, default=None) -> str | None:
    """The text value of `section.key` in the scenario an event was recorded in (`default`
    when the section has no such key), or None when its scenario text is not a scenario (a
    note, e.g. an ensemble's combined runs) or holds no such section. Read as every scenario
    is (parse_yaml): YAML past the reader's limits is a ConfigError naming the event."""
    try:
        recorded = parse_yaml(event.scenario,
                              f"memorized event {event.relative_path()}: its scenario")
    except YamlSyntaxError:
        return None
    settings = recorded.get(section) if isinstance(recorded, dict) else None
    if not isinstance(settings, dict):
        return None
    value = settings.get(key, default)
    return value if isinstance(value, str) else None


def recorded_hand(event) -> str | None:
    """The `gripper.model` of the scenario an event was recorded in (recorded_setting)."""
    return recorded_setting(event, "gripper", "model", HAND_BEFORE_THE_MODEL_SETTING)


# The sensor settings whose change makes memorized events another world's, as the hand's does
# (the transfer study, docs/transfer.md: events recorded through one transducer miss or fire
# early through the other): (section, key, what its values name).
EVENT_WORLD_SENSORS = (("tactile", "transducer", "taxels"),
                       ("vibration", "transducer", "RA transducer"))


def another_worlds_events(scenario, events: dict) -> str | None:
    """A one-line warning when `events` were recorded on a hand other than `gripper.model`,
    or through other SA or RA transducers than the scenario's (on purpose in the transfer
    study; else most likely --events names the wrong folder), else None."""
    differences = []
    hands = {recorded_hand(event) for event in events.values()} - {None}
    others = sorted(hands - {scenario.gripper.model})
    if others:
        differences.append(f"on the {' and '.join(others)} hand and are matched on the "
                           f"{scenario.gripper.model} hand")
    for section, key, what in EVENT_WORLD_SENSORS:
        live = getattr(getattr(scenario, section), key)
        recorded = {recorded_setting(event, section, key) for event in events.values()}
        others = sorted(recorded - {None, live})
        if others:
            differences.append(f"with {' and '.join(others)} {what} and are matched with "
                               f"{live} {what}")
    if not differences:
        return None
    return (f"the memorized events of '{scenario.object.name}' were recorded "
            f"{'; and '.join(differences)}: expect missed or early triggers (record this "
            "world's own with `tegrasp record-events` and the same --set, e.g. "
            "--set gripper.model=...)")
