"""The sensitivity study: the uncertain parameters (parameters.py) each moved from its
default to either end of its range, one at a time, or all drawn together as a Latin
hypercube; each point a world of the transfer machinery (transfer/matrix.py), its trials a
resumable sweep, its events memorized in that world (as the robot memorizes its own) or once
at the default (docs/sweeps.md, "How much the guesses matter")."""

import dataclasses
import json
import os
import pathlib

from tegrasp_drake.rig.files import write_atomically
from tegrasp_drake.rig.typed_yaml import (ConfigError, optional_field, read_yaml_file,
                                          require_fields)
from tegrasp_drake.sensitivity.parameters import (UNCERTAIN_PARAMETERS, UncertainParameter,
                                                  parameter)
from tegrasp_drake.sweep.spec import SweepSpec
from tegrasp_drake.sweep.spec_file import sweep_spec_from_fields
from tegrasp_drake.rig.files import MAX_STATE_FILE_BYTES, read_json_file
from tegrasp_drake.transfer.matrix import (TransferSpec, TransferWorld, check_matrix_size,
                                           check_worlds)

DEFAULT_POINT = "default"
BASE_PRESET = "default"  # every point: the built-in default scenario, then its assignments
EVENTS_CHOICES = ("each_point", "default_point")
POINTS_FILE = "points.json"  # OUT/points.json: what each point sets
MAX_LATIN_HYPERCUBE = 1000  # samples; each is a whole sweep
_FIELDS = ("parameters", "events", "sweep")


@dataclasses.dataclass(frozen=True)
class SensitivitySpec:
    """The parameters swept, where each point's events are memorized ("each_point": in the
    point's own world; "default_point": once, at the defaults) and the sweep of each point."""
    parameters: tuple[UncertainParameter, ...] = UNCERTAIN_PARAMETERS
    events: str = "each_point"
    sweep: SweepSpec = dataclasses.field(default_factory=SweepSpec)


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
    sweep: the fields of a sweep spec (the paper's sweep when left out)

    ConfigError names the file and the field of anything that cannot run."""
    source = str(path)
    data = read_yaml_file(path, "the sensitivity spec")
    require_fields(data, source, "the sensitivity spec", "give at least one field (e.g. "
                   "parameters: [object.friction]; `sweep: {}` for every parameter over the "
                   "paper's sweep)")
    if not isinstance(data, dict):
        raise ConfigError(f"{source}: must be a mapping with parameters, events and sweep")
    unknown = sorted(set(map(str, data)) - set(_FIELDS))
    if unknown:
        raise ConfigError(f"{source}: unknown field '{unknown[0]}' (fields: "
                          f"{', '.join(_FIELDS)})")
    parameters = _parse_parameters(optional_field(data, "parameters", source, None), source)
    events = data.get("events", "each_point")
    if events not in EVENTS_CHOICES:
        raise ConfigError(f"{source}: field 'events' must be one of "
                          f"{', '.join(EVENTS_CHOICES)}, got {events!r}")
    sweep = sweep_spec_from_fields(optional_field(data, "sweep", source, {}),
                                   f"{source} [sweep]")
    swept = {key.split("=", 1)[0] for entry in parameters
             for value in (entry.low, entry.default, entry.high)
             for key in entry.assignments(value)}
    for k, assignment in enumerate(sweep.scenario_overrides):
        key = assignment.split("=", 1)[0].strip()
        if key in swept:
            raise ConfigError(f"{source}: field 'sweep.scenario_overrides[{k}]': '{key}' is "
                              "set by the study's points; drop it here, or drop its "
                              "parameter from 'parameters'")
    spec = SensitivitySpec(parameters=parameters, events=events, sweep=sweep)
    check_worlds(transfer_spec(spec, one_at_a_time(spec)), source)
    return spec


def _parse_parameters(value, source: str) -> tuple[UncertainParameter, ...]:
    if value is None:
        return UNCERTAIN_PARAMETERS
    if not isinstance(value, list) or not value:
        raise ConfigError(f"{source}: field 'parameters' must be a list of the uncertain "
                          "parameters' keys (docs/model.md, \"What was guessed\"), or left out "
                          "for all of them")
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
    if not isinstance(samples, int) or not 1 <= samples <= MAX_LATIN_HYPERCUBE:
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
    return TransferSpec(worlds=worlds, cells=cells, sweep=spec.sweep)


def point_folder_cell(spec: SensitivitySpec, point: SensitivityPoint) -> tuple[str, str]:
    """The (memorizing, running) cell whose sweep holds `point`'s trials."""
    return (point.name if spec.events == "each_point" else DEFAULT_POINT, point.name)


def record_points(points, out_dir) -> pathlib.Path:
    """Adds the points' assignments to OUT/points.json; SweepError when the folder holds a
    point of the same name that set other values (another spec's)."""
    from tegrasp_drake.sweep.runner import SweepError
    path = pathlib.Path(out_dir) / POINTS_FILE
    known = (read_json_file(path, limit=MAX_STATE_FILE_BYTES, kind="a study's points file",
                            check=_points_problem, remedy="give another output folder, or "
                            "remove the file if the folder holds this study's points only")
             if os.path.lexists(path) else {})
    for point in points:
        wanted = list(point.assignments())
        if point.name in known and known[point.name] != wanted:
            raise SweepError(f"{out_dir} holds point '{point.name}' set to "
                             f"{known[point.name]}, not {wanted} (another sampling); give "
                             "another output folder")
        known[point.name] = wanted
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_atomically(path, json.dumps(known, indent=1, sort_keys=True) + "\n")


def _points_problem(data) -> str | None:
    if not isinstance(data, dict) or not all(
            isinstance(assignments, list) and all(isinstance(a, str) for a in assignments)
            for assignments in data.values()):
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
        record_points(points, out_dir)
        return run_transfer(matrix, trial_function, out_dir, workers=workers,
                            scheduler=scheduler, progress=progress,
                            confirmed_trials=confirmed_trials)
