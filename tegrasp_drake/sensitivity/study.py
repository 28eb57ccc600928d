"""The sensitivity study: the uncertain parameters (parameters.py) each moved from its
default to either end of its range, one at a time, or all drawn together as a Latin
hypercube; each point a world of the transfer machinery (transfer/matrix.py), its trials a
resumable sweep, its events memorized in that world (as the robot memorizes its own) or once
at the default (docs/sweeps.md, "How much the guesses matter")."""

import dataclasses
import json
import os
import pathlib

from tegrasp_drake.rig.files import JSON_OBJECT_START, write_atomically
from tegrasp_drake.rig.ranges import is_integer
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.typed_yaml import (ConfigError, assignment_key, keys_overlap,
                                          optional_field, optional_section, read_yaml_file,
                                          require_mapping,
                                          require_fields)
from tegrasp_drake.sensitivity.parameters import (UNCERTAIN_PARAMETERS, UncertainParameter,
                                                  parameter)
from tegrasp_drake.sweep.spec import SweepSpec, refuse_too_many
from tegrasp_drake.sweep.spec_file import sweep_spec_from_fields
from tegrasp_drake.rig.files import MAX_STATE_FILE_BYTES, read_json_file
from tegrasp_drake.rig.ranges import SEED_RANGE, bounded
from tegrasp_drake.transfer.matrix import (DEFAULT_EVENTS_SEED, TransferSpec, TransferWorld,
                                           check_matrix_size, check_worlds, events_seed_field)

DEFAULT_POINT = "default"
BASE_PRESET = "default"  # every point: the built-in default scenario, then its assignments
EVENTS_CHOICES = ("each_point", "default_point")
POINTS_FILE = "points.json"  # OUT/points.json: what each point sets
MAX_LATIN_HYPERCUBE = 1000  # samples; each is a whole sweep
_FIELDS = ("parameters", "events", "events_seed", "sweep")
# Each uncertain parameter is named at most once, so a spec names at most all of them.
MAX_SENSITIVITY_PARAMETERS = len(UNCERTAIN_PARAMETERS)


@dataclasses.dataclass(frozen=True)
class SensitivitySpec:
    """The parameters swept, where each point's events are memorized ("each_point": in the
    point's own world; "default_point": once, at the defaults), the seed of the ideal grasps
    that record them (a transfer's events_seed) and the sweep of each point."""
    parameters: tuple[UncertainParameter, ...] = UNCERTAIN_PARAMETERS
    events: str = "each_point"
    sweep: SweepSpec = dataclasses.field(default_factory=SweepSpec)
    events_seed: int = bounded(DEFAULT_EVENTS_SEED, **dataclasses.asdict(SEED_RANGE))


@dataclasses.dataclass(frozen=True)
class SensitivityPoint:
    """One world of the study: its name (a folder's), the parameter it moves and to which
    end ("" and "" for the default and for a Latin-hypercube sample), and every value set."""
    name: str
    values: tuple[tuple[str, float], ...]  # (key, value) of each parameter set off default
    parameter: str = ""
    end: str = ""  # "low" or "high"

    def assignments(self) -> tuple[str, ...]:
        return tuple(a for key, value in self.values for a in parameter(key).assignments(value))


def LoadSensitivitySpec(path) -> SensitivitySpec:
    """Reads and checks a sensitivity spec. Fields:

    parameters: [dotted keys of the uncertain parameters] (all of them when left out)
    events: each_point (default) or default_point
    events_seed: the seed of the ideal grasps that record the events (a transfer spec's)
    sweep: the fields of a sweep spec (the paper's sweep when left out)

    ConfigError names the file and the field of anything that cannot run."""
    source = str(path)
    data = read_yaml_file(path, "the sensitivity spec", kind=SensitivitySpec)
    # the example names a real parameter (the table's first), so that it cannot drift
    require_fields(data, source, "the sensitivity spec", "give at least one field (e.g. "
                   f"parameters: [{UNCERTAIN_PARAMETERS[0].key}]; `sweep: {{}}` for every "
                   "parameter over the paper's sweep)")
    require_mapping(data, source, "the sensitivity spec",
                    "its fields (parameters, events, sweep)")
    unknown = sorted(set(map(str, data)) - set(_FIELDS))
    if unknown:
        raise ConfigError(f"{source}: unknown field '{unknown[0]}' (fields: "
                          f"{', '.join(_FIELDS)})")
    parameters = _parse_parameters(optional_field(data, "parameters", source, None), source)
    events = optional_field(data, "events", source, "each_point")
    if events not in EVENTS_CHOICES:
        raise ConfigError(f"{source}: field 'events' must be one of "
                          f"{', '.join(EVENTS_CHOICES)}, got {events!r}")
    sweep = sweep_spec_from_fields(optional_section(data, "sweep", source, {}),
                                   f"{source} [sweep]")
    swept = {assignment_key(assignment) for entry in parameters
             for value in (entry.low, entry.default, entry.high)
             for assignment in entry.assignments(value)}
    for k, assignment in enumerate(sweep.scenario_overrides):
        key = assignment_key(assignment)
        for swept_key in sorted(swept):
            if keys_overlap(key, swept_key):
                held = "" if key == swept_key else f" (it holds '{swept_key}')"
                raise ConfigError(f"{source}: field 'sweep.scenario_overrides[{k}]': "
                                  f"'{shorten(key)}'{held} is set by the study's points; drop "
                                  "it here, or drop its parameter from 'parameters'")
    spec = SensitivitySpec(parameters=parameters, events=events, sweep=sweep,
                           events_seed=events_seed_field(data, source))
    check_worlds(transfer_spec(spec, one_at_a_time(spec)), source)
    return spec


def _parse_parameters(value, source: str) -> tuple[UncertainParameter, ...]:
    if value is None:
        return UNCERTAIN_PARAMETERS
    if not isinstance(value, list) or not value:
        raise ConfigError(f"{source}: field 'parameters' must be a list of the uncertain "
                          "parameters' keys (docs/model.md, \"What was guessed\"), or left out "
                          "for all of them")
    refuse_too_many("parameters", len(value), MAX_SENSITIVITY_PARAMETERS, "parameters", source,
                    study="sensitivity spec")
    chosen = []
    for k, key in enumerate(value):
        try:
            entry = parameter(str(key))
        except KeyError as error:
            raise ConfigError(f"{source}: field 'parameters[{k}]': {error.args[0]}") from None
        if entry in chosen:
            raise ConfigError(f"{source}: field 'parameters[{k}]': '{key}' is named twice")
        chosen.append(entry)
    return tuple(chosen)


def one_at_a_time(spec: SensitivitySpec) -> tuple[SensitivityPoint, ...]:
    """The default point, then each parameter at its low and its high end (an end equal to
    the default is the default point and is left out)."""
    points = [SensitivityPoint(DEFAULT_POINT, ())]
    for entry in spec.parameters:
        for end, value in (("low", entry.low), ("high", entry.high)):
            if value != entry.default:
                points.append(SensitivityPoint(f"{entry.name}_{end}", ((entry.key, value),),
                                               parameter=entry.key, end=end))
    return tuple(points)


def latin_hypercube(spec: SensitivitySpec, samples: int) -> tuple[SensitivityPoint, ...]:
    """The default point and `samples` points of a Latin hypercube over all the spec's
    parameters (scipy.stats.qmc, seeded with the sweep's base_seed): each parameter's range
    cut into `samples` equal strata, one point in each (parameters.at_fraction)."""
    if not is_integer(samples) or not 1 <= samples <= MAX_LATIN_HYPERCUBE:
        raise ConfigError(f"--latin-hypercube must be a whole number of samples from 1 to "
                          f"{MAX_LATIN_HYPERCUBE}, got {samples!r}")
    from scipy.stats import qmc
    unit = qmc.LatinHypercube(d=len(spec.parameters), seed=spec.sweep.base_seed).random(samples)
    width = len(str(samples - 1))
    points = [SensitivityPoint(DEFAULT_POINT, ())]
    for k, row in enumerate(unit):
        points.append(SensitivityPoint(f"lhs_{k:0{width}d}", tuple(
            (entry.key, entry.at_fraction(float(u))) for entry, u in zip(spec.parameters, row))))
    return tuple(points)


def transfer_spec(spec: SensitivitySpec, points) -> TransferSpec:
    """The points as transfer worlds (the default scenario and each point's assignments) and
    cells: each point memorizing in itself, or the default point's events everywhere."""
    worlds = {point.name: TransferWorld(BASE_PRESET, point.assignments()) for point in points}
    memorizing = {"each_point": None, "default_point": DEFAULT_POINT}[spec.events]
    cells = tuple((memorizing or point.name, point.name) for point in points)
    return TransferSpec(worlds=worlds, cells=cells, sweep=spec.sweep,
                        events_seed=spec.events_seed)


def point_folder_cell(spec: SensitivitySpec, point: SensitivityPoint) -> tuple[str, str]:
    """The (memorizing, running) cell whose sweep holds `point`'s trials."""
    return (point.name if spec.events == "each_point" else DEFAULT_POINT, point.name)


def study_identity(spec: SensitivitySpec, points) -> dict:
    """What makes a study's folder its own, as points.json keeps it: the design (one factor at
    a time, a Latin hypercube of N points and its seed, or points given otherwise), each
    parameter with its range, where events are memorized and at which seed, and the sweep (its
    trials)."""
    points = tuple(points)
    if points == one_at_a_time(spec):
        design = {"design": "one_at_a_time"}
        entries = sorted(spec.parameters, key=lambda entry: entry.key)  # order is moot
    else:
        samples = len(points) - 1
        lhs = (1 <= samples <= MAX_LATIN_HYPERCUBE
               and all(p.name.startswith("lhs_") for p in points[1:])
               and points == latin_hypercube(spec, samples))
        design = ({"design": "latin_hypercube", "samples": samples,
                   "seed": spec.sweep.base_seed} if lhs else {"design": "given"})
        entries = spec.parameters  # a sample's columns follow this order
    return json.loads(json.dumps({
        **design,
        "parameters": [{"key": e.key, "low": e.low, "default": e.default, "high": e.high,
                        "choices": list(e.choices), "step": e.step, "log_scale": e.log_scale}
                       for e in entries],
        "events": spec.events,
        "events_seed": spec.events_seed,
        "sweep": dataclasses.asdict(spec.sweep)}))  # as read back: lists, not tuples


def record_points(spec: SensitivitySpec, points, out_dir) -> pathlib.Path:
    """Writes OUT/points.json: the study's identity (study_identity) and each point's
    assignments. SweepError, before anything is written, when the folder holds another study
    (another design, parameter, range, events or sweep; a folder written before points.json
    named its study is this study's when its points are exactly these)."""
    from tegrasp_drake.sweep.runner import SweepError
    path = pathlib.Path(out_dir) / POINTS_FILE
    study = study_identity(spec, points)
    wanted = {point.name: list(point.assignments()) for point in points}
    if os.path.lexists(path):
        known = read_json_file(path, limit=MAX_STATE_FILE_BYTES, kind="a study's points file",
                               check=_points_problem, remedy="give another output folder, or "
                               "remove the file if the folder holds this study's points only")
        named = set(known) == {"study", "points"}
        difference = (_study_difference(known["study"], study) if named else None) or \
            _points_difference(known["points"] if named else known, wanted)
        if difference:
            raise SweepError(f"{out_dir} holds another sensitivity study: {difference}; "
                             "give another --out")
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_atomically(path, json.dumps({"study": study, "points": wanted}, indent=1,
                                             sort_keys=True) + "\n", start=JSON_OBJECT_START)


def _design_words(study: dict) -> str:
    design = study.get("design")
    if design == "one_at_a_time":
        return "one-at-a-time"
    if design == "latin_hypercube":
        return f"a Latin hypercube of {study.get('samples')} points, seed {study.get('seed')}"
    return "points given by a script"


def _study_difference(known: dict, wanted: dict) -> str | None:
    """What differs between two study identities, in words (the folder's, then this one's);
    None when they are the same study. A folder's identity without events_seed was written
    before a spec could set it: its events were recorded at DEFAULT_EVENTS_SEED."""
    known = {"events_seed": DEFAULT_EVENTS_SEED, **known}
    if _design_words(known) != _design_words(wanted):
        return (f"the folder's design is {_design_words(known)}, this study's "
                f"{_design_words(wanted)}")
    keys = ([p.get("key") for p in known.get("parameters", ())],
            [p.get("key") for p in wanted["parameters"]])
    if keys[0] != keys[1]:
        return f"parameters {keys[0]} in the folder, not {keys[1]}"
    for had, has in zip(known["parameters"], wanted["parameters"]):
        if had != has:
            return (f"the folder's range of {has['key']} is {_range_words(had)}, this "
                    f"study's {_range_words(has)}")
    if known.get("events") != wanted["events"]:
        return f"events {known.get('events')} in the folder, not {wanted['events']}"
    if known["events_seed"] != wanted["events_seed"]:
        return (f"events recorded at events_seed {known['events_seed']!r} in the folder, not "
                f"{wanted['events_seed']}")
    sweep = known.get("sweep") if isinstance(known.get("sweep"), dict) else {}
    for field in wanted["sweep"]:
        if sweep.get(field) != wanted["sweep"][field]:
            return (f"the folder's sweep field '{field}' is {sweep.get(field)!r}, this "
                    f"study's {wanted['sweep'][field]!r}")
    return None if known == wanted else "the folder names its study otherwise"


def _range_words(entry: dict) -> str:
    return (f"{entry.get('low')} .. {entry.get('default')} .. {entry.get('high')}"
            + (f" (choices {entry.get('choices')})" if entry.get("choices") else "")
            + (", log scale" if entry.get("log_scale") else ""))


def _points_difference(known: dict, wanted: dict) -> str | None:
    """What differs between the folder's points and these, in words; None when the same."""
    extra = [name for name in known if name not in wanted]
    if extra:
        return f"point '{extra[0]}' in the folder is not one of this study's ({_names(wanted)})"
    missing = [name for name in wanted if name not in known]
    if missing:
        return f"point '{missing[0]}' of this study is not in the folder ({_names(known)})"
    for name, assignments in wanted.items():
        if known[name] != assignments:
            return f"point '{name}' set to {known[name]} in the folder, not {assignments}"
    return None


def _names(points, shown: int = 4) -> str:
    """The first `shown` point names, and how many more (a hypercube has up to 1001)."""
    names = list(points)
    more = f" and {len(names) - shown} more" if len(names) > shown else ""
    return ", ".join(names[:shown]) + more or "none"


def _points_problem(data) -> str | None:
    named = isinstance(data, dict) and set(data) == {"study", "points"}
    if named and not (isinstance(data["study"], dict)
                      and isinstance(data["study"].get("parameters"), list)
                      and all(isinstance(p, dict) for p in data["study"]["parameters"])):
        return "has a 'study' that is not a mapping with a list of parameters"
    points = data["points"] if named else data
    if not isinstance(points, dict) or not all(
            isinstance(assignments, list) and all(isinstance(a, str) for a in assignments)
            for assignments in points.values()):
        return "is not a mapping of point names to lists of KEY=VALUE assignments (text)"
    return None


def run_sensitivity(spec: SensitivitySpec, points, trial_function, out_dir, *, workers=None,
                    scheduler=None, progress: bool = True,
                    confirmed_trials: int | None = None) -> dict:
    """Records each memorizing point's events, runs each point's sweep; {cell: summary}.
    Resumable: what is finished in `out_dir` is kept. `progress` and the log: run_transfer's.
    A study over the trial bound is refused with its cost before anything else unless
    `confirmed_trials` (the count given with --confirm-trials) covers it
    (transfer.matrix.check_matrix_size)."""
    from tegrasp_drake.sweep.runner import hold_output_folder
    from tegrasp_drake.sweep.trial_function import run_trial_from_spec
    from tegrasp_drake.transfer.matrix import check_unrecorded_events, run_transfer
    matrix = transfer_spec(spec, points)
    check_matrix_size(matrix, "the sensitivity study", confirmed_trials)
    check_worlds(matrix, "the sensitivity study")
    if trial_function is run_trial_from_spec:  # before OUT is written
        check_unrecorded_events(matrix, out_dir)
    pathlib.Path(out_dir).mkdir(parents=True, exist_ok=True)
    with hold_output_folder(out_dir):  # before points.json; run_transfer shares the hold
        record_points(spec, points, out_dir)
        return run_transfer(matrix, trial_function, out_dir, workers=workers,
                            scheduler=scheduler, progress=progress,
                            confirmed_trials=confirmed_trials)
