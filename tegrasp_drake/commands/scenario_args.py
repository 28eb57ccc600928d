"""Command-line options shared by every command that loads a scenario."""

import logging
import pathlib
import sys

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.scenario.scenario import DEFAULT_SCENARIO, LoadScenario
from tegrasp_drake.commands.events_option import check_events_folder
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError, read_yaml_file_cached, set_option
from tegrasp_drake.rig.usage_parser import AppendSettings


def add_scenario_arguments(parser) -> None:
    parser.add_argument("--scenario", metavar="FILE", default=None,
                        help="YAML file of named scenarios (default: the built-in file)")
    parser.add_argument("--scenario-name", default=DEFAULT_SCENARIO,
                        help="which scenario of the file (default: %(default)s)")
    parser.add_argument("--set", dest="overrides", action=AppendSettings, default=[],
                        type=set_option, metavar="KEY=VALUE",
                        help="override a scenario field, e.g. --set object.name=thin_cylinder")
    parser.add_argument("--allow-long", action="store_true",
                        help="run a grasp script longer than 60 s of simulated time (refused "
                        "otherwise, with its cost)")


def scenario_from_arguments(args, *, simulates: str = ""):
    """Loads the scenario with `--controller`'s controller if given (naming the settings it
    ignores), or exits with the error. `simulates`: "trial" refuses a hardware scenario;
    "events" notes that its simulation is used."""
    if args.scenario and not pathlib.Path(args.scenario).exists() and \
            args.scenario in (read_yaml_file_cached(paths.scenarios_file(), "the scenario file",
                                                    kind=None) or {}):
        raise SystemExit(f"{ERROR_LEAD}--scenario takes a file of scenarios; "
                         f"'{args.scenario}' is a built-in scenario: give --scenario-name "
                         f"{args.scenario}")
    controller = getattr(args, "controller", None)

    def say_ignored(settings: list[str]) -> None:
        print(f"tegrasp: --controller {controller} ignores the scenario's controller "
              f"settings that it lacks: {', '.join(settings)}", file=sys.stderr, flush=True)

    try:
        scenario = LoadScenario(args.scenario, args.scenario_name, args.overrides,
                                controller=controller, on_ignored=say_ignored,
                                allow_long=getattr(args, "allow_long", False))
    except ConfigError as e:
        raise SystemExit(f"{ERROR_LEAD}{e}") from None
    if simulates and isinstance(scenario.station, HardwareStationConfig):
        where = f"{args.scenario or 'scenario'} [{args.scenario_name}]"
        if simulates == "trial":
            raise SystemExit(f"{ERROR_LEAD}{where}: its station is !HardwareStationConfig "
                             "(the real arm, gripper and pads); this command simulates: run "
                             "it on the devices with `tegrasp hardware`, or give a scenario "
                             "without that station")
        print(f"tegrasp: {where}: its station is !HardwareStationConfig; this command "
              "simulates the scenario's object, sensors and controller (the devices' settings "
              "are not used)", file=sys.stderr, flush=True)
    return scenario


def add_events_argument(parser, *, what: str = "read") -> None:
    parser.add_argument("--events", metavar="DIR", default=None,
                        help=f"memorized events folder to {what} (default: "
                        "$TEGRASP_EVENTS_DIR or ~/.local/share/tegrasp/events, then the "
                        "package's)")


def controller_events(scenario, events_dir):
    """The memorized events the scenario's controller needs (None for the others), or
    exits with the message (which folder, which file, what to do)."""
    check_events_folder(events_dir)
    if scenario.controller.events_folder is None:
        return None
    from tegrasp_drake.scenario.scenario_events import (another_worlds_events,
                                                       load_controller_events)
    from tegrasp_drake.events import MemorizedEventError
    try:
        events = load_controller_events(scenario, events_dir)
    except MemorizedEventError as e:
        raise SystemExit(f"{ERROR_LEAD}the {scenario.controller.name} controller needs "
                         f"the memorized "
                         f"events of '{scenario.object.name}': {e}") from None
    try:
        warning = another_worlds_events(scenario, events)
    except ConfigError as e:
        raise SystemExit(f"{ERROR_LEAD}{e}") from None
    if warning:
        logging.getLogger(__name__).warning(warning)
    return events


def corrective_events(scenario, events_dir):
    """The memorized corrective events the controller matches (None when
    controller.memorized_corrective.events is empty), `events_dir` first, or exits saying why."""
    if not scenario.controller.memorized_corrective.events:
        return None
    from tegrasp_drake.scenario.scenario_events import load_corrective_events
    from tegrasp_drake.events import MemorizedEventError
    try:
        return load_corrective_events(scenario, events_dir)
    except MemorizedEventError as e:
        raise SystemExit(f"{ERROR_LEAD}controller.memorized_corrective.events needs the "
                         f"corrective events of '{scenario.object.name}': {e}") from None
