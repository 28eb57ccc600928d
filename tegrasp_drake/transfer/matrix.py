"""Do memorized events transfer? Events memorized in one world, trials run in another. A world is a
scenario preset plus `--set` assignments; a transfer spec names the worlds, the cells (memorizing,
running world) and one sweep. `run_transfer` records each memorizing world's events, then runs each
cell as an ordinary, resumable sweep (docs/transfer.md, "A transfer sweep")."""

import dataclasses
import json
import logging
import os
import pathlib
import sys
import time
from collections.abc import Mapping

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.events.event_file import WORLD_FILE
from tegrasp_drake.sweep.spec import (MAX_SCENARIO_OVERRIDES, per_trial_override_problem,
                                      SweepSpec, refuse_too_many)
from tegrasp_drake.sweep.spec_file import sweep_spec_from_fields
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.api_boundary import bound_arguments
from tegrasp_drake.rig.ranges import SEED_RANGE, bounded, settings
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.rig.typed_yaml import (ConfigError, RefinedSettings, assignment_key,
                                          check_fields, keys_overlap, optional_section,
                                          refuse_a_key_set_twice, read_yaml_file,
                                          refuse_null_section,
                                          read_yaml_file_cached, require_mapping,
                                          require_fields)

EVENTS_FOLDER = "events"  # OUT/events/<world>: each memorizing world's events
CELLS_FOLDER = "cells"  # OUT/cells/<cell>: each cell's sweep
# WORLD_FILE: in a world's events folder, the assignments it was recorded with (the events
# package declares it: a file its folder check knows)
# The random_seed of the ideal grasp that records a world's paper events: the default
# scenario's, which every transfer recorded its events at before a spec could set it.
DEFAULT_EVENTS_SEED = 0
logger = logging.getLogger(__name__)
_NAME_CHARACTERS = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_")
# A world's name names its events folder and, twice, its cells' folders (`<m>-in-<r>`): 64
# characters, as an object's name, keeps a cell's name within a file system's 255 bytes.
_NAME_MAX_CHARACTERS = 64
# The most worlds and cells a transfer spec names, counted before any is built: each world
# records its events, each cell is a sweep; a sensitivity study's Latin hypercube is at most
# as many worlds. Listing and checking 90,000 cells took 113 s before the bound.
MAX_WORLDS = 1000
MAX_CELLS = 10_000


@dataclasses.dataclass(frozen=True)
class TransferWorld:
    """A world: a scenario preset of the built-in scenario file, then `--set` overrides."""
    scenario: str
    overrides: tuple[str, ...] = settings()


@dataclasses.dataclass(frozen=True)
class TransferSpec:
    """The worlds, the cells (memorizing world, running world), the sweep of each cell, and
    the seed of the ideal grasps that record the memorizing worlds' paper events (their sensor
    noise and start pose, as a trial's random_seed; the ensemble's runs take their own)."""
    worlds: Mapping[str, TransferWorld]
    cells: tuple[tuple[str, str], ...]
    sweep: SweepSpec
    events_seed: int = bounded(DEFAULT_EVENTS_SEED, **dataclasses.asdict(SEED_RANGE))

    def memorizing_worlds(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys(a for a, _ in self.cells))


def cell_name(memorizing: str, running: str) -> str:
    """The folder name of a cell: `<memorizing>-in-<running>`."""
    return f"{memorizing}-in-{running}"


def world_assignments(world: TransferWorld, source: str = "transfer spec") -> tuple[str, ...]:
    """The world as `--set` assignments: its preset's dotted fields but `object`, then overrides."""
    document = read_yaml_file_cached(paths.scenarios_file(), "the scenario file", kind=None)
    if world.scenario not in document:
        raise ConfigError(f"{source}: scenario '{world.scenario}' is not in "
                          f"{paths.scenarios_file()} (scenarios: {', '.join(document)})")
    preset = dict(document[world.scenario] or {})
    preset.pop("object", None)
    assignments = []

    def flatten(prefix, value):
        if isinstance(value, dict):  # an empty section (or preset) sets nothing
            for key, item in value.items():
                flatten(f"{prefix}.{key}" if prefix else str(key), item)
        else:  # JSON is YAML: quoted text, numbers, true/false, [lists]
            assignments.append(f"{prefix}={json.dumps(value)}")
    flatten("", preset)
    return tuple(assignments) + tuple(world.overrides)


def running_sweep(spec: TransferSpec, running: str) -> SweepSpec:
    """A cell's sweep in world `running`: the world's assignments before the sweep's overrides
    (RefinedSettings: the world's overrides refine its preset)."""
    return dataclasses.replace(spec.sweep, scenario_overrides=RefinedSettings(
        world_assignments(spec.worlds[running]) + tuple(spec.sweep.scenario_overrides)))


def LoadTransferSpec(path, *, confirmed_trials: int | None = None) -> TransferSpec:
    """Reads and checks a transfer spec. Fields:

    worlds: {name: {scenario: PRESET, overrides: [KEY=VALUE, ...]}}
    cells: [[memorizing, running], ...], or {memorize_in: [worlds], run_in: [worlds]}
    sweep: the fields of a sweep spec (the paper's sweep when left out)
    events_seed: the seed of the ideal grasps that record the events (DEFAULT_EVENTS_SEED
        when left out)

    ConfigError names the file and the field of anything that cannot run, and gives the
    cost of a matrix over the trial bound (check_matrix_size; `confirmed_trials`, the count
    given with --confirm-trials, runs it)."""
    source = str(path)
    data = read_yaml_file(path, "the transfer spec", kind=TransferSpec)
    require_fields(data, source, "the transfer spec", "give its worlds and cells (e.g. "
                   "worlds: {a: {scenario: memorizing_world}}, cells: [[a, a]])")
    require_mapping(data, source, "the transfer spec",
                    "its fields (worlds, cells, sweep, events_seed)")
    unknown = set(data) - {"worlds", "cells", "sweep", "events_seed"}
    if unknown:
        raise ConfigError(f"{source}: unknown field '{sorted(unknown)[0]}' (fields: worlds, "
                          "cells, sweep, events_seed)")
    for required in ("worlds", "cells"):
        if required not in data:
            raise ConfigError(f"{source}: field '{required}' is missing")
    worlds = _parse_worlds(data["worlds"], source)
    cells = _parse_cells(data["cells"], worlds, source)
    sweep = sweep_spec_from_fields(optional_section(data, "sweep", source, {}),
                                   f"{source} [sweep]")
    _check_sweep_leaves_worlds_alone(worlds, sweep, source)
    _check_a_controller_reads_events(sweep, source)
    spec = TransferSpec(worlds=worlds, cells=cells, sweep=sweep,
                        events_seed=events_seed_field(data, source))
    check_matrix_size(spec, source, confirmed_trials)
    check_worlds(spec, source)
    return spec


def _check_a_controller_reads_events(sweep, source: str) -> None:
    """ConfigError when none of the sweep's controllers reads memorized events: a transfer
    study runs events memorized in one world in another, so with none every cell would run
    the same trials and the recordings would go unused."""
    from tegrasp_drake.control.controller_registry import controller_entry
    if any(controller_entry(name).event_triggered for name in sweep.controllers):
        return
    raise ConfigError(
        f"{source}: field 'sweep.controllers': {', '.join(sweep.controllers)} read no "
        "memorized events, so no cell would differ from another; add a controller that "
        "reads them (memorized, taxel_aware), or run `tegrasp sweep` for these")


def _check_sweep_leaves_worlds_alone(worlds, sweep, source: str) -> None:
    """ConfigError when a sweep override sets a field (or a section holding one) that a
    world's preset or overrides set: the sweep's come last and would silently replace what
    names the world."""
    for k, assignment in enumerate(sweep.scenario_overrides):
        key = assignment_key(assignment)
        for name, world in worlds.items():
            for world_key in map(assignment_key, world_assignments(world)):
                if keys_overlap(key, world_key):
                    raise ConfigError(
                        f"{source}: field 'sweep.scenario_overrides[{k}]': '{shorten(key)}' "
                        f"sets '{world_key}', which world '{name}' sets (its preset or "
                        "overrides); set it in the worlds, or drop it here")


def events_seed_field(data: dict, source: str) -> int:
    """The spec's `events_seed` (DEFAULT_EVENTS_SEED when left out); ConfigError naming
    `source` and the field for one that is not a whole number in SEED_RANGE."""
    value = data.get("events_seed", DEFAULT_EVENTS_SEED)
    if type(value) is not int:
        raise ConfigError(f"{source}: field 'events_seed' must be a whole number (the seed of "
                          f"the ideal grasps that record the events), got "
                          f"{shorten(repr(value))}")
    if not SEED_RANGE.contains(value):
        raise ConfigError(f"{source}: field 'events_seed' {SEED_RANGE.words(value)}, got "
                          f"{value}")
    return value


# A check of more worlds than this says on stderr what it checks and how long it took (a
# world's check, its scenario with every controller, is tens of milliseconds).
WORLDS_CHECKED_QUIETLY = 20


def check_worlds(spec: TransferSpec, source: str) -> None:
    """ConfigError naming `source` and the world whose preset and overrides, with the
    sweep's, some controller's scenario refuses (each cell's sweep checks them so). Every
    world is checked, those no cell uses too: a spec names only worlds that can run. A run
    checks the matrix's size first (check_matrix_size), before any world. Over
    WORLDS_CHECKED_QUIETLY worlds, a line on stderr before and one after (with the time)."""
    talk = len(spec.worlds) > WORLDS_CHECKED_QUIETLY
    if talk:
        print(f"checking {len(spec.worlds)} worlds (each world's scenario with "
              f"{len(spec.sweep.controllers)} controllers) ...", file=sys.stderr, flush=True)
    start = time.perf_counter()
    for name in spec.worlds:
        try:
            sweep_spec_from_fields(
                {"scenario_overrides": list(running_sweep(spec, name).scenario_overrides),
                 "controllers": list(spec.sweep.controllers)}, f"{source} [worlds.{name}]",
                written=False)  # the world's preset, then its overrides: these refine it
        except ConfigError as error:
            _refuse_world_entry(spec, name, source)
            raise ConfigError(str(error).replace("field 'scenario_overrides'", "the world's "
                                                 "preset and overrides with the sweep's")
                              ) from None
    if talk:
        print(f"checked {len(spec.worlds)} worlds in {time.perf_counter() - start:.1f} s",
              file=sys.stderr, flush=True)


def _refuse_world_entry(spec: TransferSpec, name: str, source: str) -> None:
    """ConfigError naming the spec's entry at fault in world `name`, which some controller's
    scenario refuses: the first of worlds.<name>.overrides refused after the world's preset,
    else the first of sweep.scenario_overrides refused after the world's settings."""
    from tegrasp_drake.scenario.scenario import refuse_listed_override
    world = spec.worlds[name]
    preset = world_assignments(dataclasses.replace(world, overrides=()))
    sweep_overrides = tuple(spec.sweep.scenario_overrides)
    for controller in spec.sweep.controllers:
        refuse_listed_override(world.overrides,
                               lambda k: f"{source}: field 'worlds.{name}.overrides[{k}]'",
                               base=preset, controller=controller)
        refuse_listed_override(sweep_overrides, lambda k: f"{source}: field "
                               f"'sweep.scenario_overrides[{k}]' in world '{name}'",
                               base=world_assignments(world), controller=controller)


def check_matrix_size(spec: TransferSpec, source: str, confirmed: int | None = None) -> None:
    """ConfigError, with the cost, for a matrix whose trials (cells x each cell's sweep) and
    ideal-grasp recordings (memorizing worlds x objects, 1 + TEMPLATE_RUNS each with the
    ensemble) are together more than sweep.spec.MAX_TRIALS unless `confirmed` (the count of
    --confirm-trials) covers them, as for a sweep (check_study_size): many cells are one run."""
    from tegrasp_drake.recording.ensemble_events import ENSEMBLE_FOLDER, TEMPLATE_RUNS
    from tegrasp_drake.sweep.spec import check_study_size, trial_count
    trials = len(spec.cells) * trial_count(spec.sweep)
    per_object = 1 + (TEMPLATE_RUNS if ENSEMBLE_FOLDER in recorded_events_folders(spec) else 0)
    recordings = len(spec.memorizing_worlds()) * len(spec.sweep.objects) * per_object
    check_study_size(trials + recordings,
                     f"{len(spec.cells)} cells x {trial_count(spec.sweep)} trials and "
                     f"{recordings} ideal grasps to record the events",
                     "a transfer or sensitivity run, as a sweep,", source, confirmed)


def _check_count(field_name: str, count: int, most: int, items: str, source: str,
                 how: str = "") -> None:
    """refuse_too_many for a transfer spec's list, checked before anything is built from it."""
    refuse_too_many(field_name, count, most, items, source, how, study="transfer spec")


def _parse_worlds(value, source: str) -> dict[str, TransferWorld]:
    refuse_null_section(value, source, "worlds", required=True)
    if not isinstance(value, dict) or not value:
        raise ConfigError(f"{source}: field 'worlds' must map world names to "
                          "{scenario: PRESET, overrides: [...]}")
    _check_count("worlds", len(value), MAX_WORLDS, "worlds", source)
    worlds = {}
    for name, fields in value.items():
        name = str(name)
        if not name or not set(name) <= _NAME_CHARACTERS:
            raise ConfigError(f"{source}: field 'worlds.{shorten(name)}': a world's name is "
                              "letters, digits and '_' (it names folders)")
        if len(name) > _NAME_MAX_CHARACTERS:
            raise ConfigError(f"{source}: field 'worlds.{shorten(name)}': a world's name must "
                              f"be at most {_NAME_MAX_CHARACTERS} characters (it names folders), "
                              f"got {len(name)}")
        if isinstance(fields, dict) and isinstance(fields.get("overrides"), list):
            _check_count(f"worlds.{name}.overrides", len(fields["overrides"]),
                         MAX_SCENARIO_OVERRIDES, "settings", source)
        check_fields(fields, TransferWorld, source, f"worlds.{name}")
        world = TransferWorld(scenario=fields["scenario"],
                              overrides=tuple(fields.get("overrides", ())))
        refuse_a_key_set_twice(world.overrides, source, f"worlds.{name}.overrides")
        for assignment in world.overrides:
            problem = per_trial_override_problem(assignment, "a world may not set it")
            if problem:
                raise ConfigError(f"{source}: field 'worlds.{name}.overrides': {problem}")
        world_assignments(world, f"{source}: field 'worlds.{name}.scenario'")
        worlds[name] = world
    return worlds


def _parse_cells(value, worlds, source: str) -> tuple[tuple[str, str], ...]:
    refuse_null_section(value, source, "cells", required=True)
    if isinstance(value, dict):
        check_fields(value, _CellProduct, source, "cells")
        memorize_in, run_in = value["memorize_in"], value["run_in"]
        _check_count("cells", len(memorize_in) * len(run_in), MAX_CELLS, "cells", source,
                     f"{len(memorize_in)} memorize_in x {len(run_in)} run_in")
        cells = [(a, b) for a in memorize_in for b in run_in]
    elif isinstance(value, list):
        _check_count("cells", len(value), MAX_CELLS, "cells", source)
        cells = []
        for item in value:
            if not isinstance(item, list) or len(item) != 2:
                raise ConfigError(f"{source}: field 'cells': {item!r} is not a pair "
                                  "[memorizing world, running world]")
            cells.append((str(item[0]), str(item[1])))
    else:
        raise ConfigError(f"{source}: field 'cells' must be a list of [memorizing, running] "
                          "pairs or {memorize_in: [...], run_in: [...]}")
    if not cells:
        raise ConfigError(f"{source}: field 'cells' is empty: name at least one cell")
    for cell in cells:
        for world in cell:
            if world not in worlds:
                raise ConfigError(f"{source}: field 'cells': unknown world '{world}' "
                                  f"(worlds: {', '.join(worlds)})")
    listed, repeated = set(), None
    for cell in cells:
        if cell in listed:
            repeated = cell
            break
        listed.add(cell)
    if repeated is not None:
        raise ConfigError(f"{source}: field 'cells' lists the cell {shown(list(repeated))} "
                          "twice; list each cell once")
    return tuple(cells)


@dataclasses.dataclass
class _CellProduct:
    """The mapping form of `cells`: every pair of the two lists."""
    memorize_in: list[str]
    run_in: list[str]


def recording_assignments(spec: TransferSpec, world: str) -> tuple[str, ...]:
    """The `--set` assignments `world`'s events are recorded with, as its world.json keeps
    them: the world's, the sweep's, then `random_seed` when spec.events_seed is not
    DEFAULT_EVENTS_SEED (left out at the default, as folders recorded before the field
    name their settings). RefinedSettings: the world's overrides refine its preset."""
    seed = (() if spec.events_seed == DEFAULT_EVENTS_SEED
            else (f"random_seed={spec.events_seed}",))
    return RefinedSettings(world_assignments(spec.worlds[world])
                           + tuple(spec.sweep.scenario_overrides) + seed)


def world_scenario(spec: TransferSpec, world: str, object_name: str):
    """The nominal Scenario of `object_name` in `world`, at spec.events_seed: what its events
    are recorded on."""
    from tegrasp_drake.scenario.scenario import LoadScenario, resolve_object, validate
    from tegrasp_drake.rig.objects import ObjectConfig
    base = LoadScenario(overrides=recording_assignments(spec, world))
    definition = spec.sweep.user_objects.get(object_name)
    obj = (definition.object_config(object_name) if definition
           else resolve_object(ObjectConfig(name=object_name)))
    return validate(dataclasses.replace(base, object=obj), f"world {world}")


def recorded_events_folders(spec: TransferSpec) -> tuple[str, ...]:
    """The events folders (controller.events_folder) a world's recording makes: always the
    paper's events (""), and the ensemble ("ensemble") when a sweep's controller reads it."""
    from tegrasp_drake.control.controller_registry import controller_class
    from tegrasp_drake.recording.ensemble_events import ENSEMBLE_FOLDER
    wanted = {controller_class(name).events_folder for name in spec.sweep.controllers}
    return ("",) + ((ENSEMBLE_FOLDER,) if ENSEMBLE_FOLDER in wanted else ())


def record_world_events(spec: TransferSpec, world: str, folder, *,
                        progress: bool = False) -> int:
    """Records, in `world`, the events every object of the sweep needs for the sweep's
    controllers (the paper's into `folder`, the taxel_aware controller's ensemble into
    `folder`/ensemble, as `tegrasp record-events` does), skipping those there; returns how
    many recordings it made (an object's paper events, its ensemble). As a sweep tells of its
    trials: a progress bar over the recordings when `progress`, each one logged at INFO.
    SweepError for a folder of other world settings."""
    from tegrasp_drake.events import save_memorized_events
    from tegrasp_drake.events.event_file import has_index, read_index
    from tegrasp_drake.events.events_folder import UnreadableEventsError
    from tegrasp_drake.recording.campaign import RecordEventsError
    from tegrasp_drake.recording.ensemble_events import (ENSEMBLE_FOLDER, TEMPLATE_RUNS,
                                                         record_object_ensemble)
    from tegrasp_drake.recording.paper_events import record_events
    from tegrasp_drake.sweep.runner import SweepError, progress_bar_factory
    from tegrasp_drake.rig.files import (JSON_ARRAY_START, UserPathError,
                                         folder_problem, read_json_file, replace_problem,
                                         write_atomically)
    progress_bar = progress_bar_factory(progress, description=f"events of {world}",
                                        unit="recording")
    folder = pathlib.Path(folder)
    assignments = list(recording_assignments(spec, world))
    marker = folder / WORLD_FILE
    kept = os.path.lexists(marker)
    written = json.dumps(assignments, indent=1) + "\n"  # what this world's file holds
    if kept:  # a folder or device in its place is refused by the reader
        recorded = read_json_file(
            marker, limit=world_file_limit(written), kind="this world's settings file",
            check=_assignments_problem, remedy=f"remove {folder} (its events are recorded "
            "again) or give another output folder")
        if recorded != assignments:
            raise SweepError(f"{folder} holds the events of world '{world}' recorded with "
                             f"other settings ({first_difference(recorded, assignments)}); "
                             "give another output folder or remove that one")
    if not kept:  # a kept one holds these settings (checked above): nothing to write
        problem = folder_problem(folder) or replace_problem(marker)  # e.g. a file in its place
        if problem:
            raise UserPathError(f"{marker}: {problem}; give another output folder")
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as error:  # a file system that changed since the check, or refuses
            raise UserPathError(f"{folder}: cannot be made ({os_error_text(error)}); give "
                                "another output folder") from None
        write_atomically(marker, written, start=JSON_ARRAY_START)
    recorders = {"": ("", record_events),  # what the log calls them, how they are recorded
                 ENSEMBLE_FOLDER: ("ensemble ", lambda name, scenario: record_object_ensemble(
                     name, scenario, TEMPLATE_RUNS))}
    pending = []  # (sub-folder, object) of each recording to make
    for sub in recorded_events_folders(spec):
        destination = folder / sub
        have = ({entry["object"] for entry in read_index(destination)}
                if has_index(destination) else set())
        pending += [(sub, name) for name in spec.sweep.objects if name not in have]
    with progress_bar(len(pending)) as bar:
        for sub, object_name in pending:
            what, record = recorders[sub]
            logger.info(f"recording the {what}events of {object_name} in world {world}")
            try:
                events = record(object_name, world_scenario(spec, world, object_name))
                save_memorized_events(folder / sub, events.values())
            except (RecordEventsError, UnreadableEventsError) as error:
                # a world whose trials give no usable events (UnreadableEventsError: what
                # they gave would not read back as one grasp's): nothing of it was saved
                raise SweepError(f"world {world}: {error}") from None
            bar.update(1)
    return len(pending)


def world_file_limit(written: str) -> int:
    """[bytes] The most a world's WORLD_FILE is read to, `written` the text this package writes
    there for the world: 4 times it and 64 kB (room for other settings of a world, never the
    megabytes of a file that is no world's, whose list would cost hundreds of MB to parse)."""
    return 4 * len(written.encode("utf-8")) + 65_536


# [characters] About how much of each side of a differing assignment a refusal shows.
_DIFFERENCE_CHARS = 36


def first_difference(recorded: list, expected: list) -> str:
    """The first assignment in which the settings a world's events were `recorded` with
    differ from the `expected` ones, in about 80 characters: its number and both sides,
    or the one that only one side has."""
    for k in range(max(len(recorded), len(expected))):
        there = recorded[k] if k < len(recorded) else None
        here = expected[k] if k < len(expected) else None
        if there == here:
            continue
        if there is None:
            return (f"they lack setting {k + 1}, {shown(shorten(here, _DIFFERENCE_CHARS))}, "
                    "which this world has")
        if here is None:
            return (f"setting {k + 1} is {shown(shorten(there, _DIFFERENCE_CHARS))}, which "
                    "this world lacks")
        return (f"setting {k + 1} is {shown(shorten(there, _DIFFERENCE_CHARS))} there, "
                f"{shown(shorten(here, _DIFFERENCE_CHARS))} in this world")
    return "they are the same"


def _assignments_problem(data) -> str | None:
    if not isinstance(data, list) or not all(isinstance(item, str) for item in data):
        return "is not a list of KEY=VALUE assignments (text)"
    return None


def world_events_folder(out_dir, world: str) -> pathlib.Path:
    return pathlib.Path(out_dir) / EVENTS_FOLDER / world


def cell_folder(out_dir, memorizing: str, running: str) -> pathlib.Path:
    return pathlib.Path(out_dir) / CELLS_FOLDER / cell_name(memorizing, running)


def check_unrecorded_events(spec: TransferSpec, out_dir) -> None:
    """ConfigError, before anything is recorded or written, for a cell's trials of a controller
    that reads events a world's recording does not make (recorded_events_folders) when they
    are not there already."""
    from tegrasp_drake.control.controller_registry import controller_class
    from tegrasp_drake.sweep.spec import expand_trials
    from tegrasp_drake.sweep.trial_function import check_sweep_events
    made = recorded_events_folders(spec)
    for memorizing, running in spec.cells:
        trials = [t.to_dict() for t in expand_trials(running_sweep(spec, running))
                  if controller_class(t.controller).events_folder not in (None, *made)]
        try:
            check_sweep_events(trials, world_events_folder(out_dir, memorizing))
        except ConfigError as error:
            raise ConfigError(f"{error}; a world's recording makes the paper's events and the "
                              "ensemble alone, so record these there first or drop the "
                              "controller") from None


def check_kept_events(spec: TransferSpec, out_dir) -> None:
    """UserPathError, before anything is recorded or run, when an object a world's events
    folder already lists (so it is kept, not recorded again) lacks a file a cell's controller
    reads (a transition's event, missing or unusable): one line naming the file, and the
    remedy (remove the world's folder: its events are recorded again)."""
    from tegrasp_drake.control.controller_registry import controller_class
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.events.event_file import has_index, read_index
    from tegrasp_drake.rig.files import UserPathError
    from tegrasp_drake.sweep.spec import expand_trials
    from tegrasp_drake.sweep.trial_function import trial_events
    made = recorded_events_folders(spec)
    checked = set()
    for memorizing, running in spec.cells:
        folder = world_events_folder(out_dir, memorizing)
        for trial in expand_trials(running_sweep(spec, running)):
            sub = controller_class(trial.controller).events_folder
            key = (memorizing, trial.object_name, trial.controller)
            if sub not in made or key in checked:
                continue
            checked.add(key)
            if not has_index(folder / sub) or trial.object_name not in {
                    entry["object"] for entry in read_index(folder / sub)}:
                continue  # recorded by this run
            try:
                trial_events(trial.to_dict(), folder)
            except MemorizedEventError as error:
                raise UserPathError(f"{error.path}: {error.problem}; the events of world "
                                    f"'{memorizing}' in {folder} are kept from an earlier "
                                    f"run: remove {folder} (its events are recorded again) "
                                    "or give another output folder") from None


def run_transfer(spec: TransferSpec, trial_function, out_dir, *, workers=None,
                 scheduler=None, progress: bool = True,
                 confirmed_trials: int | None = None) -> dict:
    """Records the memorizing worlds' events, runs each cell's sweep; {cell: summary}.
    Resumable. `progress`: the recordings' and the sweeps' progress bars; the steps are
    logged at INFO. A matrix over the trial bound is refused before anything runs unless
    `confirmed_trials` covers it (check_matrix_size)."""
    from tegrasp_drake.sweep.runner import hold_output_folder
    from tegrasp_drake.sweep.trial_function import run_trial_from_spec
    check_matrix_size(spec, "run_transfer", confirmed_trials)
    if trial_function is run_trial_from_spec:
        check_unrecorded_events(spec, out_dir)
    pathlib.Path(out_dir).mkdir(parents=True, exist_ok=True)
    with hold_output_folder(out_dir):  # the whole folder, before anything is recorded
        return _run_transfer_held(spec, trial_function, out_dir, workers=workers,
                                  scheduler=scheduler, progress=progress,
                                  confirmed_trials=confirmed_trials)


def _run_transfer_held(spec: TransferSpec, trial_function, out_dir, *, workers, scheduler,
                       progress: bool, confirmed_trials: int | None) -> dict:
    """run_transfer's recordings and cells, its folder held."""
    from tegrasp_drake.sweep.runner import run_sweep
    from tegrasp_drake.sweep.spec import expand_trials
    from tegrasp_drake.sweep.trial_function import check_sweep_events, run_trial_from_spec
    if trial_function is run_trial_from_spec:  # before any recording or trial
        check_kept_events(spec, out_dir)
    for world in spec.memorizing_worlds():
        record_world_events(spec, world, world_events_folder(out_dir, world),
                            progress=progress)
    if trial_function is run_trial_from_spec:  # every cell's events, before any trial
        for memorizing, running in spec.cells:
            check_sweep_events([t.to_dict() for t in expand_trials(running_sweep(
                spec, running))], world_events_folder(out_dir, memorizing))
    summaries = {}
    for memorizing, running in spec.cells:
        events = world_events_folder(out_dir, memorizing)
        sweep = running_sweep(spec, running)
        name = cell_name(memorizing, running)
        logger.info(f"cell {name}: events of {memorizing}, trials in {running}")
        summaries[name] = run_sweep(sweep, bound_arguments(trial_function, events_dir=events),
                                    cell_folder(out_dir, memorizing, running), workers=workers,
                                    scheduler=scheduler, progress=progress,
                                    confirmed_trials=confirmed_trials)
    return summaries
