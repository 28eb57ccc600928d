"""`tegrasp record-events`: memorize the tactile events of the ideal grasp (Sec. III-A).

For each object (its built-in scenario, or the object of a scenario given), the events
of its ideal grasp (experiments/record_events.py) are stored in the events folder with an
index (format: tegrasp_drake/events/FORMAT.md).
"""

import argparse

from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS


DESCRIPTION = """\
Simulates the ideal open-loop grasp (Sec. III-A) of each object and stores its memorized
tactile events (Reach-Load, Load-Lift, Place-Unload) with an index (format:
tegrasp_drake/events/FORMAT.md)."""

EPILOG = """\
examples:
  tegrasp record-events --object box          # re-record the box's events into events/
  tegrasp record-events --scenario my.yaml --scenario-name my_can --out my_events

The events of an object are replaced by the new recording (that is what re-recording is);
give --out to write them elsewhere."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "record-events", help="simulate the ideal grasp and store memorized events",
        description=DESCRIPTION, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
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
    from tegrasp_drake.experiments.record_events import record_events
    out = args.out or paths.events_dir()
    for object_name, scenario in _scenarios_to_record(args):
        with SimulatedTimeBar(object_name, enabled=progress_wanted(args)) as progress:
            events = record_events(object_name, scenario, progress=progress)
        written = save_memorized_events(out, events.values())
        print(f"{object_name}: {', '.join(events)} -> {len(written)} files in {out}")
    return 0
