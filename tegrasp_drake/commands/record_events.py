"""`tegrasp record-events`: memorize the tactile events of the ideal grasp (Sec. III-A).

For each object, the ideal open-loop grasp is simulated on its built-in scenario, the SA
(Eq. 1, at the taxel rate) and RA (Eq. 2, at 1 kHz) channels are cut into 0.5 s windows
around the physical events that mark the transitions (first contact -> reach_load, grip
force reached -> load_lift, table touch -> place_unload), normalised by their maxima and
stored in the events folder with an index (format: tegrasp_drake/events/FORMAT.md).
"""

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS

EVENT_OF_TRANSITION = {"reach_load": "first_contact", "load_lift": "grip_force_reached",
                       "place_unload": "table_touch"}


def register(subparsers) -> None:
    parser = subparsers.add_parser("record-events",
                                   help="simulate the ideal grasp and store memorized events")
    parser.add_argument("--object", action="append", choices=sorted(BUILTIN_OBJECTS),
                        help="only this object (repeatable; default: all three)")
    parser.add_argument("--out", default=None,
                        help="events folder (default: the package's events/ folder)")
    parser.add_argument("--scenario", metavar="FILE", default=None,
                        help="record the object of this scenario file instead (your own object)")
    parser.add_argument("--scenario-name", default=None,
                        help="which scenario of --scenario (its object is recorded)")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE", help="override a field of that scenario")
    parser.set_defaults(func=run)


def record_object_events(object_name: str, scenario=None):
    """Runs the ideal grasp of one object (a built-in one by name, or the object of
    `scenario`); returns its MemorizedEvents."""
    from tegrasp_drake.events import extract_memorized_events, tactile_trial_from_log
    from tegrasp_drake.experiments.grasp_outcome import physical_events
    from tegrasp_drake.experiments.ideal_grasp import run_ideal_grasp
    from tegrasp_drake.experiments.scenario import load_scenario, scenario_to_yaml
    from tegrasp_drake.experiments.trial_logging import package_versions
    scenario = scenario or load_scenario(name=object_name)
    log, _ = run_ideal_grasp(scenario)
    events = physical_events(log, scenario.grasp.grip_force, scenario.object)
    missing = [name for name in EVENT_OF_TRANSITION.values() if events[name] is None]
    if missing:
        raise RuntimeError(f"the ideal grasp of {object_name} shows no {', '.join(missing)}")
    trial = tactile_trial_from_log(log, {transition: events[event] for transition, event
                                         in EVENT_OF_TRANSITION.items()})
    return extract_memorized_events(
        trial, object_name=object_name, sa_rate_hz=scenario.tactile.sample_rate_hz,
        ra_rate_hz=scenario.vibration.sample_rate_hz, scenario=scenario_to_yaml(scenario),
        package_versions=package_versions())


def _scenarios_to_record(args) -> list:
    """(object name, scenario or None for the built-in one) of each object to record."""
    if args.scenario or args.scenario_name or args.overrides:
        from tegrasp_drake.commands.scenario_args import scenario_from_arguments
        from tegrasp_drake.experiments.scenario import DEFAULT_SCENARIO
        args.scenario_name = args.scenario_name or DEFAULT_SCENARIO
        scenario = scenario_from_arguments(args)
        return [(scenario.object.name, scenario)]
    return [(name, None) for name in args.object or sorted(BUILTIN_OBJECTS)]


def run(args) -> int:
    from tegrasp_drake.events import save_memorized_events
    out = args.out or paths.events_dir()
    for object_name, scenario in _scenarios_to_record(args):
        events = record_object_events(object_name, scenario)
        written = save_memorized_events(out, events.values())
        print(f"{object_name}: {', '.join(events)} -> {len(written)} files in {out}")
    return 0
