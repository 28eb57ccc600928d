"""`tegrasp record-events`: memorize the tactile events of the ideal grasp (Sec. III-A).

For each object (built-in, or a scenario's), the paper's events (recording/paper_events.py)
and, for an object whose ensemble the package does not ship, the taxel_aware ensemble
(recording/ensemble_events.py), stored together in `--events DIR` or the user's events
folder, never the installed package (docs/user-guide.md, "Your recorded events live
outside the package").
"""

import argparse
import contextlib
import pathlib

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.files import (absent_folders, folder_problem, free_space_problem,
                                     interruptions_deferred, made_folders_removed_if_empty)
from tegrasp_drake.rig.number_text import count_text
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.rig.typed_yaml import set_option
from tegrasp_drake.rig.usage_parser import AppendSettings

TEMPLATE_RUNS = 5  # recording/ensemble_events.py TEMPLATE_RUNS (imported late: drake)
MAX_ENSEMBLE_RUNS = 50  # each is an ideal grasp of about 20 s wall


DESCRIPTION = """\
Simulates the ideal open-loop grasp (Sec. III-A) of each object and stores its memorized
tactile events (Reach-Load, Load-Lift, Place-Unload) with an index (format:
tegrasp_drake/events/FORMAT.md)."""

EPILOG = """\
examples:
  tegrasp record-events --object box          # the box's events, into your events folder
  tegrasp record-events --set gripper.model=prismatic --events prismatic  # all three, so set
  tegrasp record-events --scenario my.yaml --scenario-name my_can --events my_events
  tegrasp record-events --events events       # from a source checkout: the package's own

Your own object gets the events of every controller: the paper's (one ideal grasp) and the
taxel_aware controller's ensemble (--ensemble-runs, default 5 more ideal grasps; 0 skips
them). A built-in object's ensemble ships with the package (--ensemble-runs 0 by default).
The events of an object are replaced by the new recording (that is what re-recording is),
once it is complete; give --events DIR to write them elsewhere."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "record-events", help="simulate the ideal grasp and store memorized events",
        description=DESCRIPTION, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--object", action="append", choices=sorted(BUILTIN_OBJECTS),
                        help="only this object (repeatable; default: all three, each with "
                        "the --set options, or the one object that --scenario, "
                        "--scenario-name or --set object.name=... names)")
    parser.add_argument("--events", "--out", dest="events", default=None, metavar="DIR",
                        help="events folder to write (default: $TEGRASP_EVENTS_DIR, else "
                        "~/.local/share/tegrasp/events)")
    parser.add_argument("--scenario", metavar="FILE", default=None,
                        help="record the object of this scenario file instead (your own object)")
    parser.add_argument("--scenario-name", default=None,
                        help="which scenario of --scenario (its object is recorded)")
    parser.add_argument("--set", dest="overrides", action=AppendSettings, default=[],
                        type=set_option, metavar="KEY=VALUE",
                        help="override a field of the scenario of each object recorded "
                        "(repeatable)")
    parser.add_argument("--ensemble-runs", type=integer_option, default=None, metavar="N",
                        help="also record the taxel_aware controller's ensemble events from "
                        f"N randomised ideal grasps (default {TEMPLATE_RUNS} for your own "
                        "object, 0 for a built-in one, whose ensemble ships with the "
                        "package)")
    parser.set_defaults(func=run)


def _scenarios_to_record(args) -> list:
    """(object name, scenario or None for the built-in one) of each object to record:
    --object names built-in objects (default all three), each from its own scenario with
    --set; --scenario/--scenario-name, or a --set that names an object (object.name=...),
    record that scenario's object. --object is refused with --scenario/--scenario-name, and
    so is a --set that changes which object an --object records."""
    if args.object and (args.scenario or args.scenario_name):
        raise SystemExit(f"{ERROR_LEAD}--object records a built-in object from its own "
                         "scenario; --scenario/--scenario-name record a scenario's object: "
                         "give one or the other")
    if args.object and args.overrides:
        chosen = _builtin_scenarios(args.object, args.overrides)
        for name, scenario in chosen:
            if scenario.object.name != name:
                raise SystemExit(f"{ERROR_LEAD}--object {name} with --set "
                                 f"{' --set '.join(args.overrides)} would record the object "
                                 f"'{scenario.object.name}'; drop --object to record it")
        return chosen
    if args.overrides and not (args.scenario or args.scenario_name):
        chosen = _builtin_scenarios(sorted(BUILTIN_OBJECTS), args.overrides)
        if all(scenario.object.name == name for name, scenario in chosen):
            return chosen  # the --set names no object: all three, each with it
    if args.scenario or args.scenario_name or args.overrides:
        from tegrasp_drake.commands.scenario_args import scenario_from_arguments
        from tegrasp_drake.scenario.scenario import DEFAULT_SCENARIO
        args.scenario_name = args.scenario_name or DEFAULT_SCENARIO
        scenario = scenario_from_arguments(args, simulates="events")
        return [(scenario.object.name, scenario)]
    return [(name, None) for name in args.object or sorted(BUILTIN_OBJECTS)]


def _builtin_scenarios(object_names, overrides) -> list:
    """(name, its built-in scenario with the --set overrides) of each built-in object."""
    from tegrasp_drake.commands.scenario_args import scenario_from_arguments
    return [(name, scenario_from_arguments(argparse.Namespace(
        scenario=None, scenario_name=name, overrides=list(overrides)), simulates="events"))
        for name in object_names]


def _ensemble_runs(args, to_record) -> int:
    if args.ensemble_runs is None:
        # Built-in objects recorded from their own scenarios (--object, or all three) have
        # their ensembles shipped with the package; the one object of a scenario (--scenario,
        # --scenario-name, a --set naming it) gets its ensemble recorded.
        scenarios_object = not args.object and len(to_record) == 1
        return TEMPLATE_RUNS if scenarios_object and to_record[0][1] is not None else 0
    if not 0 <= args.ensemble_runs <= MAX_ENSEMBLE_RUNS:
        raise SystemExit(f"{ERROR_LEAD}--ensemble-runs {args.ensemble_runs}: give 0 "
                         f"(none) to {MAX_ENSEMBLE_RUNS} ideal grasps (each about 20 s)")
    return args.ensemble_runs


def run(args) -> int:
    out, named = ((args.events, f"--events {args.events}") if args.events
                  else paths.user_events_setting())
    if paths.is_installed_package_data(out):
        raise SystemExit(f"{ERROR_LEAD}{out} holds the installed package's events, which "
                         "`pip install` replaces; record into your own folder (--events DIR "
                         f"or {paths.EVENTS_ENV}; default {paths.user_events_dir()})")
    problem = folder_problem(out)
    if problem:
        raise SystemExit(f"{ERROR_LEAD}{named}: {problem}; give a folder you can write"
                         f"{'' if args.events else ' (or --events DIR)'}")
    from tegrasp_drake.commands.run_folder import other_run_problem
    problem = other_run_problem(out, "record-events", named=named)
    if problem:  # the events would mix with a trial's, sweep's or study's files
        raise SystemExit(f"{ERROR_LEAD}{problem}")
    to_record = _scenarios_to_record(args)
    runs = _ensemble_runs(args, to_record)
    _check_destination(out, named, [name for name, _ in to_record], runs)
    # A recording refused, failed or interrupted before it saved leaves no folder it made.
    with made_folders_removed_if_empty(absent_folders(out)), _held_events_folder(out, named):
        return _record(out, to_record, runs, args)


@contextlib.contextmanager
def _held_events_folder(out, named: str):
    """Holds the events folder (made if missing) for the whole recording, with the hold each
    save takes (events_folder.held_events_folder): a second record-events, or a script's
    save, into it is refused at once, instead of replacing the first's events (and the
    index's entries) when both save."""
    from tegrasp_drake.events.events_folder import EventsFolderHeldError, held_events_folder
    with contextlib.ExitStack() as stack:
        try:
            stack.enter_context(held_events_folder(out))
        except EventsFolderHeldError:
            raise SystemExit(f"{ERROR_LEAD}{named}: another run is recording events "
                             "there now; wait for it to end, or give another folder") from None
        except OSError as e:
            raise SystemExit(f"{ERROR_LEAD}{named}: cannot open it: {os_error_text(e)}; "
                             "give a folder you can write") from None
        yield


def _record(out, to_record, runs: int, args) -> int:
    """Records and saves each object's events into `out` (held by the caller)."""
    from tegrasp_drake.events import save_memorized_events
    from tegrasp_drake.events.events_folder import (EventsDestinationError,
                                                    UnreadableEventsError)
    from tegrasp_drake.recording.ensemble_events import (ENSEMBLE_FOLDER, record_object_ensemble)
    from tegrasp_drake.recording.paper_events import RecordEventsError, record_events
    for object_name, scenario in to_record:
        try:
            with SimulatedTimeBar(object_name, enabled=progress_wanted(args)) as progress:
                events = record_events(object_name, scenario, progress=progress)
            ensemble = {}
            if runs:
                with contextlib.ExitStack() as bar:  # one bar at a time, one per run

                    def progress_of_run(k):
                        bar.close()
                        return bar.enter_context(SimulatedTimeBar(
                            f"{object_name} ensemble {k + 1}/{runs}",
                            enabled=progress_wanted(args)))
                    ensemble = record_object_ensemble(
                        object_name, scenario or _builtin_scenario(object_name), runs,
                        progress_of_run=progress_of_run)
            with interruptions_deferred():  # the paper's events and the ensemble together
                written = save_memorized_events(out, events.values())
                if ensemble:
                    written += save_memorized_events(pathlib.Path(out) / ENSEMBLE_FOLDER,
                                                     ensemble.values())
        except (RecordEventsError, EventsDestinationError, UnreadableEventsError) as e:
            raise SystemExit(f"{ERROR_LEAD}{e}") from None
        except OSError as e:
            raise SystemExit(f"{ERROR_LEAD}cannot write the events to {out}: "
                             f"{os_error_text(e)}; nothing of '{object_name}' was "
                             "replaced") from None
        made = ", ".join(events) + (f"; ensemble of {runs} runs" if ensemble else "")
        print(f"{object_name}: {made} -> {len(written)} files in {out}")
    return 0


# The most an object's memorized events take on disk [bytes], its index entries included: the
# package's largest, the prismatic's, take 0.6 MB; an ensemble as much again.
EVENTS_BYTES_PER_OBJECT = 1_000_000


def _check_destination(out, named: str, object_names, runs: int) -> None:
    """Refuses, before anything is simulated, an events folder the new events could not be
    saved into (events_folder.check_events_destination; the ensemble's folder too) or on a
    disk too full to take them (rig.files.free_space_problem), naming the option or
    environment setting that chose it (`named`)."""
    from tegrasp_drake.events.events_folder import (EventsDestinationError,
                                                    check_events_destination)
    from tegrasp_drake.recording.ensemble_events import ENSEMBLE_FOLDER
    folders = [pathlib.Path(out)] + ([pathlib.Path(out) / ENSEMBLE_FOLDER] if runs else [])
    try:
        for folder in folders:
            check_events_destination(folder, object_names)
    except EventsDestinationError as e:
        raise SystemExit(f"{ERROR_LEAD}{named}: {e}; nothing was recorded") from None
    ensemble = ", twice with an ensemble" if runs else ""
    problem = free_space_problem(
        out, EVENTS_BYTES_PER_OBJECT * len(object_names) * (2 if runs else 1),
        f"the events of {count_text(len(object_names), 'object')} (at most "
        f"{EVENTS_BYTES_PER_OBJECT / 1e6:g} MB an object{ensemble})")
    if problem:
        raise SystemExit(f"{ERROR_LEAD}{named}: {problem}; nothing was recorded")


def _builtin_scenario(object_name: str):
    from tegrasp_drake.scenario.scenario import LoadScenario
    return LoadScenario(name=object_name)
