"""`tegrasp hardware --config FILE`: the grasp on the real devices (or their emulators).

The controller diagram runs unchanged on MakeHardwareStation, in real time, against the
devices the config names (hardware/config.py; `tegrasp emulate ... --write-config FILE`
writes one for the emulators). State transitions and device faults are printed as they
happen; everything on the bus goes to an LCM log (runs/hardware_log_reader.py; `tegrasp replay
LOG`, `lcm-logplayer LOG`). Exit code: 0 when the grasp finished without a fault, 2 after a
fault or a Failed state machine, 1 when a device did not come up. The run's result
(transitions, faults, times, device counters) goes beside the log: run.result.json.
"""

import argparse
import datetime
import pathlib

from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.commands.run_folder import result_path_beside_log, write_result
from tegrasp_drake.commands.scenario_args import (add_events_argument, add_scenario_arguments,
                                                  controller_events, corrective_events,
                                                  quiet_modbus_library, scenario_from_arguments)
from tegrasp_drake.control.controller_config import CONTROLLER_NAMES


DESCRIPTION = """\
The grasp on the real devices (or their emulators), in real time: the controller diagram of
`tegrasp trial` on MakeHardwareStation. Prints each state transition and device fault as it
happens, logs the whole LCM bus (tegrasp replay LOG, lcm-logplayer LOG) and writes the
result beside the log (run.lcmlog -> run.result.json). Exit code 0: the grasp finished
without a fault; 2: a fault or a Failed state machine; 1: a device did not come up."""

EPILOG = """\
examples:
  tegrasp hardware --config hw.yaml --scenario-name box --log out/run.lcmlog
  tegrasp hardware --config hw.yaml --config-set tactile.port=/dev/ttyACM1 --duration 20

`tegrasp emulate all --trial out/demo/trial.npz --write-config hw.yaml` writes hw.yaml for
emulated devices. An existing --log FILE is refused unless --overwrite."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "hardware", help="run the grasp in real time on the devices of a hardware config",
        description=DESCRIPTION, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--config", metavar="FILE",
                        help="hardware config YAML (HardwareStationConfig fields); default: "
                        "the scenario's `station: !HardwareStationConfig {...}`")
    parser.add_argument("--config-set", dest="config_overrides", action="append", default=[],
                        metavar="KEY=VALUE", help="override a hardware config field, e.g. "
                        "--config-set tactile.port=/dev/ttyACM1")
    add_scenario_arguments(parser)
    add_events_argument(parser)
    parser.add_argument("--controller", default=None, choices=CONTROLLER_NAMES,
                        help="default: the scenario's (its controller tag, memorized)")
    parser.add_argument("--log", metavar="FILE", default=None,
                        help="LCM log to write (default: out/hardware/run-<time>.lcmlog)")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace the --log FILE (and its result) if it exists")
    parser.add_argument("--duration", type=float, default=None,
                        help="stop after this many seconds (default: when the grasp ends)")
    parser.set_defaults(func=run)


def _events_folder(events, args, scenario) -> str:
    """The folder the events were read from, for the run's log ("" without events)."""
    if not events:
        return ""
    from tegrasp_drake.events.events_folder import events_folder_of
    from tegrasp_drake.rig import paths
    return str(events_folder_of(paths.events_search_path(args.events), scenario.object.name))


def run(args) -> int:
    quiet_modbus_library()
    from tegrasp_drake.hardware.config import LoadHardwareConfig
    from tegrasp_drake.runs.hardware_run import run_on_hardware
    from tegrasp_drake.hardware.station import HardwareNotReadyError
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.hardware.config import HardwareStationConfig
    scenario = scenario_from_arguments(args)
    if args.controller:
        from tegrasp_drake.scenario.scenario import with_controller
        scenario = with_controller(scenario, args.controller)
    if args.config:
        try:
            config = LoadHardwareConfig(args.config, args.config_overrides)
        except ConfigError as e:
            raise SystemExit(f"tegrasp: error: {e}") from None
    elif isinstance(scenario.station, HardwareStationConfig):
        config = scenario.station
    else:
        raise SystemExit("tegrasp: error: give --config FILE, or a scenario whose `station` "
                         "is `!HardwareStationConfig {...}`")
    events = controller_events(scenario, args.events)
    corrective = corrective_events(scenario, args.events)
    log = args.log or (f"out/hardware/run-"
                       f"{datetime.datetime.now().strftime('%Y%m%d-%H%M%S')}.lcmlog")
    result_path = result_path_beside_log(log)
    for taken in (pathlib.Path(log), result_path):
        if taken.exists() and not args.overwrite:
            raise SystemExit(f"tegrasp: error: {taken} already holds a run's "
                             f"{'log' if taken == pathlib.Path(log) else 'result'}; give "
                             "another --log, or --overwrite to replace it")
    # The earlier result stays until this run's replaces it (write_result, at the end).
    try:
        with SimulatedTimeBar("hardware", enabled=progress_wanted(args)) as progress:
            result = run_on_hardware(scenario, config=config, events=events, corrective_events=corrective,
                                     events_dir=_events_folder(events, args, scenario),
                                     log_path=log, duration=args.duration,
                                     out=progress.write, progress=progress)
    except HardwareNotReadyError as e:
        print(f"tegrasp: error: {e}", flush=True)
        return 1
    write_result(result_path, dict(result.as_dict(), result=str(result_path)))
    print(f"ran {result.sim_time:.2f} s in {result.wall_time:.2f} s (real-time rate "
          f"{result.realtime_rate:.3f}); {len(result.transitions)} transitions, "
          f"{len(result.faults)} faults; log {result.log_path} ({result.log_messages} "
          f"messages), result {result_path}", flush=True)
    failed = result.faults or (result.transitions
                               and result.transitions[-1]["to"] == "Failed")
    return 2 if failed else 0
