"""`tegrasp hardware --config FILE`: the grasp on the real devices (or their emulators), the
controller diagram unchanged on MakeHardwareStation in real time (runs/hardware_run.py).
Exit code: 0 finished without a fault, 2 after a fault or Failed, 1 a device did not come
up. The run's result goes beside its LCM log: run.result.json."""

import argparse
import contextlib
import dataclasses
import datetime
import os
import pathlib
import logging
import sys

from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.commands.run_folder import (result_path_beside_log, staging_file_beside,
                                               write_result)
from tegrasp_drake.rig.files import interruptions_deferred, output_file_problem
from tegrasp_drake.rig.ranges import HARDWARE_RUN_DURATION, shorten
from tegrasp_drake.rig.number_text import count_text
from tegrasp_drake.commands.scenario_args import (add_events_argument, add_scenario_arguments,
                                                  controller_events, corrective_events,
                                                  scenario_from_arguments)
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controllers_help

logger = logging.getLogger(__name__)


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
                        help=f"{controllers_help()} (default: the scenario's, its "
                             "controller tag, memorized)")
    parser.add_argument("--log", metavar="FILE", default=None,
                        help="LCM log to write (default: out/hardware/run-<time>.lcmlog)")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace the --log FILE (and its result) if it exists")
    parser.add_argument("--duration", type=duration_seconds, default=None,
                        help="stop after this many seconds, at most "
                        f"{MAX_DURATION_S:g} (default: when the grasp ends)")
    parser.set_defaults(func=run)


# The longest real-time run [s] (rig/ranges.py).
MAX_DURATION_S = HARDWARE_RUN_DURATION.high


def duration_seconds(text: str) -> float:
    """--duration: a number of seconds in (0, MAX_DURATION_S]."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds") from None
    if not HARDWARE_RUN_DURATION.contains(value):  # also refuses nan
        raise argparse.ArgumentTypeError(f"{text}: give a duration in (0, {MAX_DURATION_S:g}] "
                                         "seconds")
    return value


def _events_folder(events, args, scenario) -> str:
    """The folder the events were read from, for the run's log ("" without events)."""
    if not events:
        return ""
    from tegrasp_drake.events.events_folder import events_folder_of
    from tegrasp_drake.rig import paths
    return str(events_folder_of(paths.events_search_path(args.events), scenario.object.name))


def commit_hardware_run(staged, log, result_path, result: dict) -> None:
    """Renames the staged log over --log and writes the result beside it, Ctrl-C and SIGTERM held
    back, so the old log and result are replaced together (without a log, the result alone)."""
    with interruptions_deferred():
        if pathlib.Path(staged).exists():
            os.replace(staged, log)
        write_result(result_path, result)


def keep_incomplete_log(staged, log) -> pathlib.Path | None:
    """An unfinished run's staged log, kept as LOG.incomplete-<pid>.lcmlog beside --log (never
    over the earlier run's); None when there was none."""
    staged, log = pathlib.Path(staged), pathlib.Path(log)
    if not staged.exists():
        return None
    kept = log.with_name(f"{log.stem}.incomplete-{os.getpid()}{log.suffix}")
    with contextlib.suppress(OSError):
        os.replace(staged, kept)
        return kept
    with contextlib.suppress(OSError):
        staged.unlink()
    return None


def run(args) -> int:
    from tegrasp_drake.hardware.config import LoadHardwareConfig
    from tegrasp_drake.runs.hardware_run import run_on_hardware
    from tegrasp_drake.hardware.station import HardwareNotReadyError
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.hardware.config import HardwareStationConfig
    scenario = scenario_from_arguments(args)
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
    from tegrasp_drake.hardware.config import lcm_url_origin, shared_lcm_url_problem
    problem = shared_lcm_url_problem(config.arm.lcm_url)  # the arm's driver is another process
    if problem:
        where = args.config or "the scenario's station"
        origin = lcm_url_origin(config.arm.lcm_url, "field 'arm.lcm_url'")
        raise SystemExit(f"tegrasp: error: {where}: {origin} {problem}, got "
                         f"{shorten(repr(config.arm.lcm_url))}")
    source = args.config or "the scenario's station"
    logger.info(f"hardware: devices checked ({source}): arm "
                f"on {config.arm.lcm_url}, gripper on {config.gripper.port}, tactile on "
                f"{config.tactile.port}")
    events = controller_events(scenario, args.events)
    corrective = corrective_events(scenario, args.events)
    log = args.log or (f"out/hardware/run-"
                       f"{datetime.datetime.now().strftime('%Y%m%d-%H%M%S')}.lcmlog")
    result_path = result_path_beside_log(log)
    for taken in (pathlib.Path(log), result_path):
        # The write rule first: --overwrite replaces a file, never a folder (of the user's
        # files), a device or a FIFO, so such a path is refused as such whether it exists
        # or not, before it is said to hold an earlier run.
        problem = output_file_problem(taken)
        if problem:
            where = "" if taken == pathlib.Path(log) else f": {taken}"
            raise SystemExit(f"tegrasp: error: --log {log}{where} {problem}")
        if taken.exists() and not args.overwrite:
            raise SystemExit(f"tegrasp: error: {taken} already holds a run's "
                             f"{'log' if taken == pathlib.Path(log) else 'result'}; give "
                             "another --log, or --overwrite to replace it")
    earlier = [taken for taken in (pathlib.Path(log), result_path) if taken.exists()]
    pathlib.Path(log).parent.mkdir(parents=True, exist_ok=True)
    # The run logs to a hidden file beside --log; the earlier log and result stay whole
    # until this run's replace them together at the end (commit_hardware_run). A killed
    # run's staging file is removed by the next run logging to the same --log.
    from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START
    staged = staging_file_beside(log, LCM_LOG_START)
    try:
        with SimulatedTimeBar("hardware", enabled=progress_wanted(args)) as progress:
            result = run_on_hardware(scenario, config=config, events=events,
                                     corrective_events=corrective,
                                     events_dir=_events_folder(events, args, scenario),
                                     log_path=staged, duration=args.duration,
                                     out=progress.write, progress=progress)
    except HardwareNotReadyError as e:
        staged.unlink(missing_ok=True)
        print(f"tegrasp: error: {e}", file=sys.stderr, flush=True)
        return 1
    except BaseException:
        kept = keep_incomplete_log(staged, log)
        if kept:
            print(f"tegrasp: the run did not finish; what its log recorded is in {kept}",
                  file=sys.stderr, flush=True)
        raise
    logged = staged.exists()  # none when the bus could not be recorded
    try:
        commit_hardware_run(staged, log, result_path,
                            dict(result.as_dict(), log=str(log), result=str(result_path)))
    except OSError as e:
        kept = keep_incomplete_log(staged, log)
        raise SystemExit(f"tegrasp: error: cannot write the run's result to {result_path}: "
                         f"{e.strerror or e}" + (f"; its log is in {kept}" if kept else ""))
    logger.info(f"hardware: wrote {f'the log {log} and ' if logged else ''}the result "
                f"{result_path}")
    if earlier:
        logger.info("hardware: replaced the earlier run's "
                    + " and ".join(f"{'log' if taken == pathlib.Path(log) else 'result'} "
                                   f"{taken}" for taken in earlier))
    result = dataclasses.replace(result, log_path=pathlib.Path(log))
    faults = len(result.faults) + bool(result.log_fault)  # a log that stops is a fault
    print(f"ran {result.sim_time:.2f} s in {result.wall_time:.2f} s (real-time rate "
          f"{result.realtime_rate:.3f}); {len(result.transitions)} transitions, "
          f"{count_text(faults, 'fault')}"
          f"{' (the log stopped)' if result.log_fault else ''}; log {result.log_path} "
          f"({result.log_messages} messages), result {result_path}", flush=True)
    if result.log_fault:
        print(f"tegrasp: error: {result.log_fault}; the run was stopped", file=sys.stderr,
              flush=True)
    failed = result.faults or result.log_fault or (result.transitions
                               and result.transitions[-1]["to"] == "Failed")
    return 2 if failed else 0
