"""What a sweep runs: the typed sweep specification, its validation and the trial list.
The paper's experiment (Sec. IV-B): every object at every marker of a grid, a few attempts
each, once per controller. Marker offsets are in the gripper's frame at the expected grasp
(x the approach axis, y the finger stroke). A trial's random numbers come from (base_seed,
object, marker, attempt), never the controller, so controllers meet the same scenes."""

import dataclasses
import math
import re
import typing
import zlib
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

import numpy as np

from tegrasp_drake.rig.api_boundary import describe_hint, public_dataclass, value_matches
from tegrasp_drake.rig.ranges import (SEED_RANGE, Range, bounded, check_ranges, field_range,
                                      settings)
from tegrasp_drake.rig.number_text import count_text
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, PAPER_CONTROLLERS
from tegrasp_drake.rig import objects
from tegrasp_drake.rig.objects import ObjectConfig, object_problem
from tegrasp_drake.rig.ranges import number_problem, real_number
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.rig.typed_yaml import (ConfigError, assignment_key, assignment_problem,
                                          keys_overlap, refuse_a_key_set_twice, set_words,
                                          unknown_field_problem)

# The paper's three objects (Fig. 8a); a spec can add its own (`user_objects`).
BUILTIN_OBJECTS = tuple(objects.BUILTIN_OBJECTS)

# The paper's grid (Sec. IV-B): +-1 cm normal to the palm, +-1.5 cm along the stroke.
PAPER_NORMAL_OFFSETS_M = (-0.010, 0.0, 0.010)
PAPER_STROKE_OFFSETS_M = (-0.015, 0.0, 0.015)

# The scenario fields a sweep sets per trial; a spec's scenario_overrides may not set them.
PER_TRIAL_SCENARIO_FIELDS = ("object", "placement.offset", "placement.yaw_deg", "random_seed",
                             "controller.name")

# A sweep's own object: a primitive shape given by these fields of ObjectConfig.
_OBJECT_SHAPES = tuple(shape for shape in objects.OBJECT_SHAPES if shape != "file")
USER_OBJECT_FIELDS = ("shape", "size", "mass", "friction", "color")
# The field names of sweep specs written before the sweep used ObjectConfig.
RENAMED_OBJECT_FIELDS = {"size_m": "size", "mass_kg": "mass",
                         "friction_coefficient": "friction"}

# The most any study may make, confirmed or not: its trials are listed in memory before the
# first runs (about 0.6 kB each at the peak, measured on 81,000 listed trials: 0.6 GB at this
# bound, and a minute or two to list), and it is about 8,000 core-hours. Split a larger one.
MAX_CONFIRMED_TRIALS = 1_000_000

# The most entries each list of a spec holds, checked before anything is built from it
# (check_spec_counts): a 2000 x 2000 product grid is 4 million markers, which took 33 s and
# 0.5 GB to build and check before a refusal. The grid: a 100 x 100 grid covers the whole
# +-0.2 m its offsets may span at 4 mm, finer than a hand sets an object. Objects: each is
# recorded and run at every marker (the paper's 3). Settings: a scenario has fewer fields.
MAX_GRID_MARKERS = 10_000
MAX_SWEEP_OBJECTS = 100
MAX_SCENARIO_OVERRIDES = 500
SPEC_COUNTS = {"objects": (MAX_SWEEP_OBJECTS, "objects"),
               "controllers": (len(CONTROLLER_NAMES), "controllers"),
               "grid": (MAX_GRID_MARKERS, "markers"),
               "user_objects": (MAX_SWEEP_OBJECTS, "objects"),
               "scenario_overrides": (MAX_SCENARIO_OVERRIDES, "settings")}


def check_spec_counts(counts: Mapping[str, tuple[int, str]], source: str) -> None:
    """ConfigError "SOURCE: field 'F' holds N ITEMS (HOW); a sweep takes at most M" for the
    first field of `counts` ({field: (count, how it was counted, "" for a list's length)})
    past its SPEC_COUNTS maximum: a cheap check made before a spec's lists are read, built
    or checked one by one."""
    for field_name, (count, how) in counts.items():
        refuse_too_many(field_name, count, *SPEC_COUNTS[field_name], source, how)


def refuse_too_many(field_name: str, count: int, most: int, items: str, source: str,
                    how: str = "", study: str = "sweep") -> None:
    """ConfigError "SOURCE: field 'F' holds N ITEMS (HOW); a STUDY spec takes at most M
    ITEMS" when `count` is past `most`: the one wording of a list past its maximum."""
    if count > most:
        how = f" ({how})" if how else ""
        raise ConfigError(f"{source}: field '{field_name}' holds {count} {items}{how}; a "
                          f"{study} takes at most {most} {items}: give fewer, or split the "
                          f"{study} into several")


def spec_counts(spec: "SweepSpec") -> dict[str, tuple[int, str]]:
    """check_spec_counts's counts of a SweepSpec's lists."""
    return {name: (len(getattr(spec, name)), "") for name in SPEC_COUNTS
            if isinstance(getattr(spec, name), Collection)}


def product_grid(normal_offsets_m, stroke_offsets_m) -> tuple[tuple[float, float], ...]:
    """Every (x, y) combination of the two offset lists, x (normal) varying slowest."""
    return tuple((float(dx), float(dy))
                 for dx in normal_offsets_m for dy in stroke_offsets_m)


def user_object(name: str, fields: Mapping) -> ObjectConfig:
    """The ObjectConfig called `name` of a sweep's own object (its `fields` from a spec or a
    record; older records' size_m, mass_kg, friction_coefficient read as size, mass, friction)."""
    fields = {RENAMED_OBJECT_FIELDS.get(key, key): value for key, value in fields.items()}
    fields = {key: value for key, value in fields.items() if key != "name"}
    return ObjectConfig(name=name, **{**fields,
                                      "size": [float(v) for v in fields.get("size", [])]})


@dataclass(frozen=True)
class RandomisationConfig:
    """How much attempts differ, as on a real robot: each draw uniform on +-bound (not
    Gaussian, so jitter never carries an object onto a neighbouring marker, 1 cm away)."""
    # x, y jitter around the marker: an object set by hand on a marker
    placement_xy_bound_m: float = bounded(0.002, low=0.0, high=0.05, unit="m")
    # yaw jitter about the vertical, likewise
    placement_yaw_bound_deg: float = bounded(3.0, low=0.0, high=180.0, unit="deg")
    # friction scaled by 1 + U(-b, b): a friction estimate from handbook ranges
    friction_scale_bound: float = bounded(0.10, low=0.0, high=1.0, high_open=True,
                                          why="the friction is scaled by 1 + U(-b, b), which must "
                                              "stay positive")
    # mass scaled by 1 + U(-b, b): the spread between nominally equal objects
    mass_scale_bound: float = bounded(0.10, low=0.0, high=1.0, high_open=True,
                                      why="the mass is scaled by 1 + U(-b, b), which must stay "
                                          "positive")
    sensor_noise: bool = True               # the trial function adds sensor noise


@public_dataclass
@dataclass(frozen=True)
class SweepSpec:
    """A sweep: objects x grid markers x attempts, once per controller; `grid` holds the marker
    offsets (dx_m, dy_m), x normal to the palm, y along the stroke."""
    objects: tuple[str, ...] = BUILTIN_OBJECTS
    controllers: tuple[str, ...] = PAPER_CONTROLLERS
    grid: tuple[tuple[float, float], ...] = bounded(
        product_grid(PAPER_NORMAL_OFFSETS_M, PAPER_STROKE_OFFSETS_M), low=-0.2, high=0.2,
        unit="m", why="marker offsets near the centre marker, within the open hand's reach")
    # more than MAX_TRIALS with the objects, markers and controllers only when confirmed
    # (check_sweep_size)
    attempts: int = bounded(3, low=1, high=MAX_CONFIRMED_TRIALS,
                            below="must be a positive integer",
                            why=f"a sweep makes at most {MAX_CONFIRMED_TRIALS} trials")
    base_seed: int = bounded(0, **dataclasses.asdict(SEED_RANGE))
    randomisation: RandomisationConfig = field(default_factory=RandomisationConfig)
    user_objects: Mapping[str, ObjectConfig] = field(default_factory=dict)
    # `--set key=value` assignments for every trial's scenario (not PER_TRIAL_SCENARIO_FIELDS)
    scenario_overrides: tuple[str, ...] = settings()


# The largest perturbation draw_perturbation can draw: each draw is U(-b, b) with b at most the
# upper end declared on RandomisationConfig's bound (a scale's bound below 1 keeps it positive).
_XY_BOUND_M = field_range(RandomisationConfig, "placement_xy_bound_m").high
_YAW_BOUND_RAD = math.radians(field_range(RandomisationConfig, "placement_yaw_bound_deg").high)
_SCALE_BOUND = 1.0 + field_range(RandomisationConfig, "mass_scale_bound").high


@dataclass(frozen=True)
class Perturbation:
    """One attempt's random perturbation of the scene, drawn from the trial's seed; each in
    the range draw_perturbation draws it from under the largest RandomisationConfig bounds."""
    # placement jitter along x (normal to the palm)
    dx_m: float = bounded(low=-_XY_BOUND_M, high=_XY_BOUND_M, unit="m",
                          why="U(-b, b), b at most placement_xy_bound_m's upper end")
    # placement jitter along y (stroke)
    dy_m: float = bounded(low=-_XY_BOUND_M, high=_XY_BOUND_M, unit="m",
                          why="U(-b, b), b at most placement_xy_bound_m's upper end")
    # placement jitter about the vertical
    yaw_rad: float = bounded(low=-_YAW_BOUND_RAD, high=_YAW_BOUND_RAD, unit="rad",
                             why="U(-b, b), b at most placement_yaw_bound_deg's 180 deg")
    # multiplies the object's friction coefficient
    friction_scale: float = bounded(low=0.0, high=_SCALE_BOUND, low_open=True, high_open=True,
                                    why="1 + U(-b, b) with b below 1")
    # multiplies the object's mass
    mass_scale: float = bounded(low=0.0, high=_SCALE_BOUND, low_open=True, high_open=True,
                                why="1 + U(-b, b) with b below 1")


@dataclass(frozen=True)
class TrialSpec:
    """One trial; `to_dict()` is what the trial function receives. The object sits at the
    expected position + marker offset + jitter (x normal, y stroke); `seed` seeds the sensor
    noise; `pair_id` names the same scene for every controller."""
    trial_id: str
    pair_id: str
    controller: str
    object_name: str
    object_definition: ObjectConfig | None  # a user object; None: the built-in one
    marker: str
    marker_dx_m: float = bounded(**dataclasses.asdict(field_range(SweepSpec, "grid")))
    marker_dy_m: float = bounded(**dataclasses.asdict(field_range(SweepSpec, "grid")))
    well_placed: bool  # exactly when the marker is (0, 0)
    attempt: int = bounded(low=0, high=MAX_CONFIRMED_TRIALS - 1,
                           why="attempts count from 0, fewer than SweepSpec.attempts' most")
    base_seed: int = bounded(**dataclasses.asdict(SEED_RANGE))
    seed: int = bounded(**dataclasses.asdict(SEED_RANGE))  # scene_seeds of the scene
    sensor_noise: bool
    perturbation: Perturbation
    scenario_overrides: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        d = dataclasses.asdict(self)
        # Left out when empty, so older folders without the field still resume.
        if self.scenario_overrides:
            d["scenario_overrides"] = list(self.scenario_overrides)
        else:
            del d["scenario_overrides"]
        return d

    @classmethod
    def from_dict(cls, d: Mapping) -> "TrialSpec":
        definition = d["object_definition"]
        if definition is not None:
            definition = user_object(d["object_name"], definition)
        return cls(**{**d, "object_definition": definition,
                      "perturbation": Perturbation(**d["perturbation"]),
                      "scenario_overrides": tuple(d.get("scenario_overrides", ()))})


def _from_json(value, hint):
    """`value` as TrialSpec.from_dict takes it: a record's list for a tuple field."""
    if typing.get_origin(hint) is tuple and isinstance(value, list):
        return tuple(value)
    return value


def trial_dict_problem(trial: Mapping) -> str | None:
    """What keeps `trial` (a TrialSpec.to_dict()) from being a sweep trial; or None."""
    parts = []
    for name, fields, given in (
            ("trial", TrialSpec, trial),
            ("trial 'perturbation'", Perturbation, trial.get("perturbation"))):
        if not isinstance(given, Mapping):
            if given is not None:
                parts.append(f"{name} must be a mapping, got {type(given).__name__}")
            continue
        hints = typing.get_type_hints(fields)
        optional = {f.name for f in dataclasses.fields(fields)
                    if f.default is not dataclasses.MISSING}
        missing = [key for key in hints if key not in given and key not in optional]
        unknown = [f"{key}={given[key]!r}" for key in given if key not in hints]
        wrong = [f"{key} must be {describe_hint(hints[key])}, got {given[key]!r}"
                 for key in hints if key in given and key != "perturbation"
                 and key != "object_definition"
                 and not value_matches(_from_json(given[key], hints[key]), hints[key])]
        if missing:
            parts.append(f"{name} lacks {', '.join(missing)}")
        if unknown:
            parts.append(f"{name} has unknown keys {', '.join(unknown)}")
        parts += [f"{name}: {text}" for text in wrong]
    if not parts:
        return None
    return ("; ".join(parts) + " (a sweep trial is a TrialSpec.to_dict(), as expand_trials "
            "makes them)")


# A marker's name as marker_names gives it: m, then the x and y indices, equally wide.
_MARKER_NAME = re.compile(r"m(\d+)")


def trial_problem(trial) -> str | None:
    """What keeps `trial` (a record's TrialSpec.to_dict()) from being one expand_trials
    makes, or None: its fields' types (trial_dict_problem), the ranges declared on TrialSpec's
    and Perturbation's fields, and the relations expand_trials gives them (trial and pair
    ids from the controller, object, marker and attempt; well placed exactly at the (0, 0)
    marker; the seed scene_seeds derives from the base seed and the scene; the perturbation
    its draw, perturbation_problem)."""
    if not isinstance(trial, Mapping):
        return f"trial must be a mapping, got {type(trial).__name__}"
    problem = trial_dict_problem(trial)
    if problem:
        return problem
    try:
        spec = TrialSpec.from_dict(trial)
        check_ranges(spec, "trial")
    except (TypeError, ValueError) as error:
        return str(error)
    name_problem = objects.object_name_problem(spec.object_name)
    if name_problem:
        return f"trial: field 'object_name': {name_problem}"
    if spec.controller not in CONTROLLER_NAMES:
        return (f"trial: field 'controller' must be one of {', '.join(CONTROLLER_NAMES)}, got "
                f"{spec.controller!r}")
    marker = _MARKER_NAME.fullmatch(spec.marker)
    if not marker or len(marker.group(1)) % 2:
        return (f"trial: field 'marker' must be a marker name as a sweep gives it (m, then "
                f"the x and y indices, e.g. m11), got {spec.marker!r}")
    pair_id = f"{spec.object_name}/{spec.marker}/a{spec.attempt}"
    if spec.pair_id != pair_id:
        return (f"trial: field 'pair_id' must be {pair_id!r} (object/marker/attempt), got "
                f"{spec.pair_id!r}")
    if spec.trial_id != f"{spec.controller}/{pair_id}":
        return (f"trial: field 'trial_id' must be {spec.controller + '/' + pair_id!r} "
                f"(controller/pair_id), got {spec.trial_id!r}")
    offset = (spec.marker_dx_m, spec.marker_dy_m)
    if spec.well_placed != (offset_key(offset) == (0, 0)):
        return (f"trial: field 'well_placed' is {str(spec.well_placed).lower()} but the marker "
                f"is ({spec.marker_dx_m!r}, {spec.marker_dy_m!r}) m (well placed is the marker "
                "at (0, 0))")
    _, seed = scene_seeds(spec.base_seed, spec.object_name, offset, spec.attempt)
    if spec.seed != seed:
        return (f"trial: field 'seed' must be {seed}, the seed of base_seed {spec.base_seed}, "
                f"object {spec.object_name!r}, marker {list(offset)} m and attempt "
                f"{spec.attempt}, got {spec.seed}")
    return perturbation_problem(spec)


# Validation


def validate_spec(spec: SweepSpec, source: str = "sweep spec", *,
                  builtin_objects: Collection[str] = BUILTIN_OBJECTS,
                  controllers: Collection[str] = CONTROLLER_NAMES,
                  override_place: Callable[[int], str] | None = None) -> None:
    """Raises ConfigError naming `source` and the field when `spec` cannot run (objects against
    `builtin_objects` and the spec's `user_objects`, controllers against `controllers`).
    `override_place(k)` names where scenario_overrides[k] was written (default: `source`'s
    field; "--set" for one given on the command line), its assignment shown after it; they
    may not set one key twice to two values unless RefinedSettings (refuse_a_key_set_twice)."""
    def fail(field_name, message):
        raise ConfigError(f"{source}: field '{field_name}': {message}")

    check_spec_counts(spec_counts(spec), source)  # cheap checks first
    if not spec.grid:
        fail("grid", "is empty: a sweep needs at least one marker offset")
    for offset in spec.grid:
        if (not isinstance(offset, (tuple, list)) or len(offset) != 2
                or not all(number_problem(v) is None for v in offset)):
            fail("grid", f"marker offset {offset!r} is not a pair of finite numbers (m)")
    check_ranges(spec, source)  # each number in the range declared on its field
    for name, config in spec.user_objects.items():
        _check_name(name, f"user_objects.{name}", fail)
        if name in builtin_objects:
            fail(f"user_objects.{name}", "redefines a built-in object; choose another name")
        _check_user_object(name, config, fail)
    known_objects = tuple(builtin_objects) + tuple(spec.user_objects)
    _check_names_in(spec.objects, known_objects, "objects", "object", fail)
    for name in spec.user_objects:  # a definition no trial uses is a spec that says two things
        if name not in spec.objects:
            fail(f"user_objects.{name}", f"defines an object that 'objects' does not name "
                 f"(it names {', '.join(spec.objects)}), so no trial would run it: add it to "
                 "'objects', or remove its definition")
    _check_names_in(spec.controllers, tuple(controllers), "controllers", "controller", fail)

    seen_markers = set()
    for offset in spec.grid:  # in range (check_ranges): a whole number of micrometres
        key = offset_key(offset)
        if key in seen_markers:
            fail("grid", f"marker offset {offset!r} appears twice")
        seen_markers.add(key)
    if not isinstance(spec.randomisation.sensor_noise, bool):
        fail("randomisation.sensor_noise",
             f"expected true or false, got {spec.randomisation.sensor_noise!r}")
    refuse_a_key_set_twice(spec.scenario_overrides, source, "scenario_overrides")
    place = override_place or (lambda k: f"{source}: field 'scenario_overrides[{k}]'")
    _check_scenario_overrides(spec.scenario_overrides, spec.controllers, place, fail)
    _check_jittered_placements(spec, source, fail)


def _check_jittered_placements(spec: SweepSpec, source: str, fail) -> None:
    """Each object at each marker, moved and yawed by the placement jitter's far end
    (randomisation.placement_xy_bound_m along each axis, placement_yaw_bound_deg): the load-time
    checks of a scenario's object and placement (the object, yawed, fits the open hand; it
    stands on the table, clear of the hand's start pose, where the shift may put it) hold at
    every jitter a trial may draw, not only at the marker itself, so that no trial is refused
    after the sweep has started."""
    from tegrasp_drake.scenario.object_placement import ObjectPlacementConfig
    from tegrasp_drake.scenario.scenario import LoadScenario, check_start_clearance
    xy_bound = spec.randomisation.placement_xy_bound_m
    yaw_bound = spec.randomisation.placement_yaw_bound_deg
    _check_jittered_offsets(spec.grid, xy_bound, source)
    # the arm's start and the marker, which no controller changes
    base = LoadScenario(overrides=spec.scenario_overrides, controller=spec.controllers[0])
    for name in spec.objects:
        config = spec.user_objects.get(name) or objects.BUILTIN_OBJECTS.get(name)
        if config is None:  # a built-in of the caller's own list: resolved by the scenario
            continue
        problem = objects.object_fit_problem(config, yaw_bound_deg=yaw_bound)
        if problem:
            fail("randomisation", f"object '{name}': {problem}; give a smaller "
                                  "placement_yaw_bound_deg, or a smaller object")
        for offset in spec.grid:
            placement = ObjectPlacementConfig(expected_xy=list(base.placement.expected_xy),
                                              offset=[float(v) for v in offset])
            where = f"{source}: object '{name}' at marker {list(offset)} with its placement jitter"
            off_table = placement.problem(config.shape, config.size, xy_bound)
            if off_table:
                raise ConfigError(f"{where}: field 'placement.{off_table[0]}' {off_table[1]}")
            check_start_clearance(dataclasses.replace(base, object=config,
                                                      placement=placement), where, xy_bound)


def _check_jittered_offsets(grid, xy_bound: float, source: str) -> None:
    """ConfigError naming the `grid` entry whose marker, moved by up to xy_bound [m] of
    placement jitter (randomisation.placement_xy_bound_m), a trial's placement.offset range
    would refuse, with the largest marker that range allows."""
    from tegrasp_drake.scenario.object_placement import ObjectPlacementConfig
    allowed = field_range(ObjectPlacementConfig, "offset")
    for k, offset in enumerate(grid):
        for axis, value in zip("xy", offset):
            if allowed.contains(value + xy_bound) and allowed.contains(value - xy_bound):
                continue
            largest = min(allowed.high, -allowed.low) - xy_bound
            raise ConfigError(
                f"{source}: field 'grid[{k}]': marker {shown(list(offset))} m, moved by up to "
                f"+-{xy_bound:g} m of placement jitter (randomisation.placement_xy_bound_m), "
                f"reaches an offset of {value + math.copysign(xy_bound, value):g} m along "
                f"{axis}, outside placement.offset's [{allowed.low:g}, {allowed.high:g}] m "
                f"({allowed.why}); give markers within +-{largest:g} m, or a smaller "
                "placement_xy_bound_m")


def per_trial_override_problem(assignment: str, remedy: str = "set it there") -> str | None:
    """Why a sweep's (or a transfer world's) scenario override `assignment` may not be given,
    or None: it sets a field of PER_TRIAL_SCENARIO_FIELDS, which the sweep sets per trial, or
    names a field of such a section that no scenario has (a misspelt `object.mas`: told as
    one, with the nearest names, never as a field set per trial); `remedy` ends the words of
    a field set per trial."""
    from tegrasp_drake.scenario.scenario import Scenario
    key = assignment_key(assignment)
    if not any(keys_overlap(key, per_trial) for per_trial in PER_TRIAL_SCENARIO_FIELDS):
        return None
    unknown = unknown_field_problem(assignment, Scenario)
    if unknown:
        return f"{unknown}; give one of its fields"
    return (f"'{key}' is set per trial by the sweep (objects, grid, randomisation, base_seed, "
            f"controllers); {remedy}")


def _check_scenario_overrides(assignments, controllers, place, fail):
    """Each override a `key=value` every controller's scenario accepts, no per-trial field;
    a refused one named by `place(k)`."""
    from tegrasp_drake.scenario.scenario import LoadScenario, refuse_listed_override

    def refuse(k, message):
        given = assignments[k]
        where = set_words(given, place(k)) if isinstance(given, str) else place(k)
        raise ConfigError(f"{where}: {message}")

    for k, assignment in enumerate(assignments):
        if not isinstance(assignment, str) or assignment_problem(assignment):
            refuse(k, f"expected 'key=value' (as `tegrasp trial --set`), key a dotted "
                      f"field name such as object.mass, got {shorten(repr(assignment))}")
        problem = per_trial_override_problem(assignment)
        if problem:
            refuse(k, problem)
    from tegrasp_drake.hardware.config import HardwareStationConfig
    for controller in controllers if assignments else ():
        try:
            scenario = LoadScenario(overrides=assignments, controller=controller)
        except ConfigError as error:
            refuse_listed_override(assignments, place, controller=controller)
            fail("scenario_overrides", str(error))
        if isinstance(scenario.station, HardwareStationConfig):
            fail("scenario_overrides", "sets the station to !HardwareStationConfig (the real "
                                       "arm, gripper and pads); a sweep simulates its trials: "
                                       "leave the station out")


def _check_name(name, field_name, fail):
    problem = objects.object_name_problem(name)  # it becomes part of trial ids and file names
    if problem:
        fail(field_name, problem)


def _check_names_in(names, known, field_name, kind, fail):
    if not names:
        fail(field_name, f"is empty: name at least one {kind}")
    for name in names:
        if name not in known:
            fail(field_name, f"unknown {kind} {name!r}; known: {', '.join(known)}")
    repeated = next((name for k, name in enumerate(names) if name in names[:k]), None)
    if repeated is not None:
        fail(field_name, f"lists {shown(repeated)} twice; list each {kind} once")


def _check_user_object(name, config, fail):
    """The checks of the scenario's objects (rig/objects.py), on a primitive shape."""
    if not isinstance(config, ObjectConfig):
        fail(f"user_objects.{name}", "expected an object (shape, size, mass, friction)")
    problem = object_problem(config, shapes=_OBJECT_SHAPES)
    if problem:
        config_field, words = problem
        fail(f"user_objects.{name}.{config_field}", words)


def is_number(value) -> bool:
    """A number (a NumPy scalar as the one it holds), not a bool."""
    return real_number(value) is not None


def offset_key(offset) -> tuple[int, int]:
    """A marker offset in whole micrometres: its identity for seeds and duplicates."""
    return (round(offset[0] * 1e6), round(offset[1] * 1e6))


# Expansion into trials


def marker_names(grid) -> list[str]:
    """`m{i}{j}`: i, j index the sorted distinct x and y offsets (zero-padded past ten values);
    the paper's grid gives m00 .. m22, m11 well placed."""
    xs = sorted({offset_key(o)[0] for o in grid})
    ys = sorted({offset_key(o)[1] for o in grid})
    width = len(str(max(len(xs), len(ys)) - 1))
    return [f"m{xs.index(offset_key(o)[0]):0{width}d}{ys.index(offset_key(o)[1]):0{width}d}"
            for o in grid]


def trial_seed_sequence(base_seed: int, object_name: str, marker_offset,
                        attempt: int) -> np.random.SeedSequence:
    """The seed of one scene, from (base_seed, object, marker offset, attempt) only: CRC-32 of
    their text (stable across processes), the offset in whole micrometres (a marker keeps its
    seed when the grid around it changes)."""
    dx_um, dy_um = offset_key(marker_offset)
    return np.random.SeedSequence(
        entropy=base_seed,
        spawn_key=(zlib.crc32(object_name.encode("utf-8")),
                   zlib.crc32(f"{dx_um:+d},{dy_um:+d}".encode("ascii")),
                   attempt))


def scene_seeds(base_seed: int, object_name: str, marker_offset,
                attempt: int) -> tuple[np.random.SeedSequence, int]:
    """One scene's two children of trial_seed_sequence: the seed sequence its perturbation is
    drawn from, and the trial's 32-bit `seed` (the sensor noise's)."""
    perturbation_seq, trial_seq = trial_seed_sequence(
        base_seed, object_name, marker_offset, attempt).spawn(2)
    return perturbation_seq, int(trial_seq.generate_state(1, dtype=np.uint32)[0])


def draw_perturbation(rng: np.random.Generator,
                      randomisation: RandomisationConfig) -> Perturbation:
    """Draws, in this order: dx, dy, yaw, friction scale, mass scale; each U(-b, b)."""
    r = randomisation
    dx, dy = rng.uniform(-r.placement_xy_bound_m, r.placement_xy_bound_m, size=2)
    yaw_bound_rad = math.radians(r.placement_yaw_bound_deg)
    yaw = rng.uniform(-yaw_bound_rad, yaw_bound_rad)
    friction_scale = 1.0 + rng.uniform(-r.friction_scale_bound, r.friction_scale_bound)
    mass_scale = 1.0 + rng.uniform(-r.mass_scale_bound, r.mass_scale_bound)
    return Perturbation(dx_m=float(dx), dy_m=float(dy), yaw_rad=float(yaw),
                        friction_scale=float(friction_scale), mass_scale=float(mass_scale))


# How far a record's perturbation may lie from its seed's redraw, as a fraction of each draw's
# bound: a record does not keep the sweep's bounds, so each is taken from a draw's value over
# the seed's uniform (a quotient, rounded in its last digits) and the draws redrawn with it;
# JSON keeps floats exactly. A draw from another seed misses by about its bound.
PERTURBATION_TOLERANCE = 1e-9

# Each Perturbation field: the RandomisationConfig bound it is drawn under, the centre it is
# drawn about, and the field's units per unit of the bound (radians per degree for the yaw).
_DRAWN_UNDER = (("dx_m", "placement_xy_bound_m", 0.0, 1.0),
                ("dy_m", "placement_xy_bound_m", 0.0, 1.0),
                ("yaw_rad", "placement_yaw_bound_deg", 0.0, math.pi / 180.0),
                ("friction_scale", "friction_scale_bound", 1.0, 1.0),
                ("mass_scale", "mass_scale_bound", 1.0, 1.0))


def perturbation_problem(spec: TrialSpec) -> str | None:
    """Why spec.perturbation is not what draw_perturbation draws from the trial's scene seed
    (scene_seeds of its base seed, object, marker and attempt), or None. A record does not
    keep the sweep's RandomisationConfig, but each draw is c + b (2u - 1) with u a uniform the
    seed alone gives, so each value names its bound b: each must lie in RandomisationConfig's
    range of it (the value on the side of c the seed draws it), and the five redrawn under
    those bounds (dx and dy under one) must be the record's."""
    sequence, _ = scene_seeds(spec.base_seed, spec.object_name,
                              (spec.marker_dx_m, spec.marker_dy_m), spec.attempt)
    uniforms = np.random.default_rng(sequence).random(len(_DRAWN_UNDER))
    seed_words = (f"its seed's draw (base_seed {spec.base_seed}, object {spec.object_name!r}, "
                  f"marker {spec.marker}, attempt {spec.attempt})")
    bounds = {}  # bound name: (its value, the 2u - 1 it was taken over)
    for (drawn, bound, centre, unit), u in zip(_DRAWN_UNDER, uniforms):
        value, signed = getattr(spec.perturbation, drawn), 2.0 * u - 1.0
        implied = (value - centre) / (signed * unit) if signed else 0.0
        high = field_range(RandomisationConfig, bound).high
        if implied < 0.0:
            return (f"trial: field 'perturbation.{drawn}' {value!r} is not {seed_words}, which "
                    f"lies {'below' if signed < 0 else 'above'} {centre:g}")
        if implied > high * (1.0 + PERTURBATION_TOLERANCE):
            return (f"trial: field 'perturbation.{drawn}' {value!r} is not {seed_words}: it "
                    f"would take a {bound} of {implied:.6g}, above that bound's highest, {high:g}")
        if bound not in bounds or abs(signed) > abs(bounds[bound][1]):  # the finer quotient
            bounds[bound] = (abs(implied), signed)  # -0.0 is no bound numpy draws under
    redrawn = draw_perturbation(np.random.default_rng(sequence), RandomisationConfig(
        **{bound: value for bound, (value, _) in bounds.items()}))
    for drawn, bound, _, unit in _DRAWN_UNDER:
        value, expected = getattr(spec.perturbation, drawn), getattr(redrawn, drawn)
        allowed = (PERTURBATION_TOLERANCE * bounds[bound][0] * unit
                   + 4.0 * math.ulp(max(abs(value), abs(expected))))
        if abs(value - expected) > allowed:
            return (f"trial: field 'perturbation.{drawn}' must be {expected!r}, {seed_words} "
                    f"under the {bound} of {bounds[bound][0]:.6g} its draws give, got {value!r}")
    return None


# What one sweep may ask for: a trial is a simulation of about TRIAL_CORE_SECONDS of one core
# (docs/sweeps.md, "What a trial costs"); the paper's Table I sweep is 81 trials per controller.
MAX_TRIALS = 100_000
TRIAL_CORE_SECONDS = 30


def trial_count(spec: SweepSpec) -> int:
    """How many trials `spec` makes: objects x markers x attempts x controllers."""
    return len(spec.objects) * len(spec.grid) * spec.attempts * len(spec.controllers)


def core_hours(simulations: int) -> str:
    """The cost of `simulations` trial-sized simulations in words: "about N core-hours", or
    "about N core-minutes" under an hour (where whole hours would read 0)."""
    seconds = simulations * TRIAL_CORE_SECONDS
    if seconds < 3600:
        return f"about {seconds / 60:.0f} core-minutes"
    return f"about {seconds / 3600:.0f} core-hours"


# The command-line option that confirms a study of more than MAX_TRIALS (check_study_size).
CONFIRM_OPTION = "--confirm-trials"
# MAX_CONFIRMED_TRIALS (declared with the counts above): the most any study may make.
# The count a confirmation gives: a study of at least one simulation, at most the ceiling.
CONFIRMED_TRIALS = Range(low=1, high=MAX_CONFIRMED_TRIALS,
                         why="the count of trials and recordings the study makes; a larger "
                             "study is split into several")


def check_study_size(simulations: int, counted: str, what: str, source: str,
                     confirmed: int | None = None, *, unit: str = "simulations") -> None:
    """ConfigError "SOURCE: COUNTED make N UNIT, about H core-hours; ..." for a study of
    `simulations` trial-sized simulations over MAX_TRIALS unless `confirmed` (the count given
    with CONFIRM_OPTION) is at least `simulations`; and for a `confirmed` under
    `simulations` at any size, which confirmed a smaller study than this one. `what` names
    the kind of run ("a sweep"); any study over MAX_CONFIRMED_TRIALS, confirmed or not. The
    one check of a study's size."""
    cost = f"{source}: {counted} make {simulations} {unit}, {core_hours(simulations)}"
    run_it = f"add {CONFIRM_OPTION} {simulations} to run it"
    if simulations > MAX_CONFIRMED_TRIALS:
        raise ConfigError(f"{cost}; {what} is at most {MAX_CONFIRMED_TRIALS} {unit} even "
                          "confirmed (each is listed in memory before the first runs): split it")
    if confirmed is not None and confirmed < simulations:
        raise ConfigError(f"{cost}, more than the {confirmed} that {CONFIRM_OPTION} "
                          f"{confirmed} confirms: {run_it}")
    if confirmed is None and simulations > MAX_TRIALS:
        raise ConfigError(f"{cost}; {what} is at most {MAX_TRIALS} trials unless confirmed: "
                          f"{run_it}, or split it")


def check_sweep_size(spec: SweepSpec, source: str, confirmed: int | None = None) -> None:
    """check_study_size of the sweep's trials, naming its field 'attempts'."""
    counted = " x ".join(count_text(n, noun) for n, noun in (
        (spec.attempts, "attempt"), (len(spec.objects), "object"), (len(spec.grid), "marker"),
        (len(spec.controllers), "controller")))
    check_study_size(trial_count(spec), f"field 'attempts': {counted}", "a sweep", source,
                     confirmed, unit="trials")


def expand_trials(spec: SweepSpec, *, builtin_objects: Collection[str] = BUILTIN_OBJECTS,
                  controllers: Collection[str] = CONTROLLER_NAMES) -> list[TrialSpec]:
    """Validates `spec` and lists its trials, controller-major, deterministically. Each scene's
    seed sequence spawns two children: a PCG64 Generator for `draw_perturbation`, and the
    trial's 32-bit `seed`. Trial ids read `{controller}/{object}/{marker}/a{attempt}`."""
    validate_spec(spec, builtin_objects=builtin_objects, controllers=controllers)
    names = marker_names(spec.grid)
    scenes = []
    for object_name in spec.objects:
        for marker, offset in zip(names, spec.grid):
            for attempt in range(spec.attempts):
                perturbation_seq, seed = scene_seeds(spec.base_seed, object_name, offset,
                                                     attempt)
                scenes.append(dict(
                    pair_id=f"{object_name}/{marker}/a{attempt}",
                    object_name=object_name,
                    object_definition=spec.user_objects.get(object_name),
                    marker=marker,
                    marker_dx_m=float(offset[0]),
                    marker_dy_m=float(offset[1]),
                    well_placed=offset_key(offset) == (0, 0),
                    attempt=attempt,
                    base_seed=spec.base_seed,
                    seed=seed,
                    sensor_noise=spec.randomisation.sensor_noise,
                    perturbation=draw_perturbation(np.random.default_rng(perturbation_seq),
                                                   spec.randomisation),
                    scenario_overrides=tuple(spec.scenario_overrides)))
    return [TrialSpec(trial_id=f"{controller}/{scene['pair_id']}", controller=controller,
                      **scene)
            for controller in spec.controllers for scene in scenes]
