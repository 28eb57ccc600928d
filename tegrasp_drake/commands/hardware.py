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

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.commands.run_folder import (result_path_beside_log, staging_file_beside,
                                               write_result)
from tegrasp_drake.rig.files import (error_line, existing_file_head, free_space_problem,
                                     interruptions_deferred, output_file_problem)
from tegrasp_drake.rig.ranges import HARDWARE_RUN_DURATION
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.rig.number_text import (NumberTextError, TypedNumber, count_text,
                                            read_number)
from tegrasp_drake.rig.typed_yaml import config_set_option
from tegrasp_drake.commands.scenario_args import (add_events_argument, add_scenario_arguments,
                                                  controller_events, corrective_events,
                                                  scenario_from_arguments)
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controllers_help
from tegrasp_drake.rig.usage_parser import AppendSettings

logger = logging.getLogger(__name__)


DESCRIPTION = """\
The grasp on the real devices (or their emulators), in real time: the controller diagram of
`tegrasp trial` on MakeHardwareStation. Prints each state transition and device fault as it
happens, logs the whole LCM bus (tegrasp replay LOG, lcm-logplayer LOG) and writes the
result beside the log (run.lcmlog -> run.result.json). Exit code 0: the grasp finished
without a fault; 2: a fault or a Failed state machine; 1: a device did not come up or is in
use by another run, or --log is being written by another run."""

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
    parser.add_argument("--config-set", dest="config_overrides", action=AppendSettings,
                        default=[],
                        type=config_set_option, metavar="KEY=VALUE", help="override a hardware config field, e.g. "
                        "--config-set tactile.port=/dev/ttyACM1")
    add_scenario_arguments(parser)
    add_events_argument(parser)
    parser.add_argument("--controller", default=None, choices=CONTROLLER_NAMES,
                        help=f"{controllers_help()} (default: the scenario's, its "
                             "controller tag, memorized)")
    parser.add_argument("--log", metavar="FILE", default=None,
                        help="LCM log to write (default: out/hardware/run-<time>.lcmlog)")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace the --log FILE (and its result) if it exists; a run "
                        "that fails keeps them and writes its own beside them as "
                        "LOG.failed.lcmlog, replacing an earlier failed run's")
    parser.add_argument("--duration", type=duration_seconds, default=None,
                        help="stop after this many seconds, at most "
                        f"{MAX_DURATION_S:g} (default: when the grasp ends)")
    parser.set_defaults(func=run)


# The longest real-time run [s] (rig/ranges.py).
MAX_DURATION_S = HARDWARE_RUN_DURATION.high


def duration_seconds(text: str) -> float:
    """--duration's number of seconds (rig.number_text.number_option, the text kept for its
    messages): text that is not a number does not parse (exit 2); its range is checked by
    duration_problem when the command runs (bad input, exit 1)."""
    try:
        return TypedNumber(read_number(text), text)
    except NumberTextError as e:
        raise argparse.ArgumentTypeError(f"{shown(text)} {e}; give a number of "
                                         "seconds") from None


def _seconds(duration) -> float | None:
    """--duration as a plain float (its typed text kept for the messages no further)."""
    return None if duration is None else float(duration)


def duration_problem(value: float) -> str | None:
    """Why --duration `value` is refused, or None: a number of seconds in [one arm command
    period, MAX_DURATION_S]: a shorter run would end before the controller sent the arm its
    first command (the JACO2 driver's 100 Hz, hardware/jaco/jaco_lcm.py)."""
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_LCM_PERIOD
    if not HARDWARE_RUN_DURATION.contains(value):  # also refuses nan
        return (f"--duration {shown(value)}: give a duration in (0, {MAX_DURATION_S:g}] "
                "seconds")
    if value < JACO_LCM_PERIOD:
        return (f"--duration {shown(value)}: give at least {JACO_LCM_PERIOD:g} s, one period of the "
                "arm's commands (a shorter run ends before the arm is commanded)")
    return None


def _events_folder(events, args, scenario) -> str | None:
    """The folder the events were read from, for the run's log (None without events)."""
    if not events:
        return None
    from tegrasp_drake.events.events_folder import events_folder_of
    from tegrasp_drake.rig import paths
    return str(events_folder_of(paths.events_search_path(args.events), scenario.object.name))


def commit_hardware_run(staged, log, result_path, result: dict) -> None:
    """Writes the result to a staging file beside `result_path`, then renames the staged log
    over `log` and the result over `result_path`, Ctrl-C and SIGTERM held back: the old log
    and result are replaced together, and stay whole when the result cannot be written (a
    full disk). Without a staged log (the bus was not recorded, or the file was removed), the
    result alone. The folder is made again if it was removed during the run."""
    from tegrasp_drake.rig.files import JSON_OBJECT_START
    result_path = pathlib.Path(result_path)
    result_path.parent.mkdir(parents=True, exist_ok=True)
    pending = staging_file_beside(result_path, JSON_OBJECT_START)
    with interruptions_deferred():
        try:
            write_result(pending, result)
            if pathlib.Path(staged).exists():
                os.replace(staged, log)
            os.replace(pending, result_path)
        finally:
            pending.unlink(missing_ok=True)


def failed_run_path(log) -> pathlib.Path:
    """Where a failed run's log goes when --overwrite would have replaced an earlier run's:
    LOG.failed.lcmlog beside it (its result: LOG.failed.result.json), the newest failed
    run's only: --overwrite replaces a failed run's pair as it does any run's, while the
    earlier run that did not fail stays. A LOG without a suffix gets .lcmlog there, so the
    failed result is never named as LOG's own (result_path_beside_log takes the stem)."""
    log = pathlib.Path(log)
    return log.with_name(f"{log.stem}.failed{log.suffix or '.lcmlog'}")


def incomplete_run_path(log) -> pathlib.Path:
    """Where a run that broke off keeps what its log recorded: LOG.incomplete.lcmlog beside
    --log, the newest such run's only (as failed_run_path keeps the newest failed run's)."""
    log = pathlib.Path(log)
    return log.with_name(f"{log.stem}.incomplete{log.suffix or '.lcmlog'}")


def _earlier_version_runs(log, kind: str) -> list[str]:
    """The names of LOG.<kind>-<pid>.lcmlog beside `log`: what an earlier version kept of
    each failed or broken-off run, named by its process id (their results left out)."""
    log = pathlib.Path(log)
    prefix = f"{log.stem}.{kind}-"
    return sorted(path.name for path in log.parent.glob(f"{prefix}*{log.suffix}")
                  if path.name[len(prefix):][:1].isdigit()
                  and not path.name.endswith(".result.json"))  # a LOG without a suffix


def earlier_version_runs_words(log, kind: str = "failed") -> str:
    """'; N failed runs' logs of an earlier version are beside it (LOG.failed-<pid>.lcmlog,
    ...)', or '' (`kind` "incomplete": of runs that broke off): those are the user's to keep
    or delete; this version neither replaces nor removes them."""
    older = _earlier_version_runs(log, kind)
    if not older:
        return ""
    what = "earlier failed run" if kind == "failed" else "earlier unfinished run's log"
    return (f"; {count_text(len(older), what)} kept beside it by an earlier "
            f"version ({older[0]}{', ...' if len(older) > 1 else ''}) stay: delete them when "
            "you no longer need them")


def _replaceable_incomplete_log(path: pathlib.Path) -> bool:
    """Whether `path` may be replaced by a newer unfinished run's log: absent, or what
    keep_incomplete_log keeps there, an LCM log (or an empty file) with no result beside it.
    A completed run's log under that name (given as --log: its result is beside it), a link
    or another file is never replaced."""
    if not (path.exists() or path.is_symlink()):
        return True
    from tegrasp_drake.rig.files import file_starts_with
    from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START
    return (file_starts_with(path, LCM_LOG_START)
            and not result_path_beside_log(path).exists())


def keep_incomplete_log(staged, log) -> tuple[pathlib.Path | None, bool]:
    """An unfinished run's staged log, kept beside --log as LOG.incomplete.lcmlog
    (incomplete_run_path), replacing an earlier unfinished run's there (never the earlier
    run's --log itself, nor a completed run's log of that name: then as
    LOG.incomplete-<pid>.lcmlog); (where it was kept, whether it replaced one), (None, False)
    when there was none."""
    staged, log = pathlib.Path(staged), pathlib.Path(log)
    if not staged.exists():
        return None, False
    kept = incomplete_run_path(log)
    if not _replaceable_incomplete_log(kept):
        kept = log.with_name(f"{log.stem}.incomplete-{os.getpid()}{log.suffix or '.lcmlog'}")
    replaced = kept.exists()
    with contextlib.suppress(OSError):
        os.replace(staged, kept)
        return kept, replaced
    with contextlib.suppress(OSError):
        staged.unlink()
    return None, False


def incomplete_log_words(kept: pathlib.Path, replaced: bool, log) -> str:
    """How a run that broke off says where its log is kept (keep_incomplete_log)."""
    return (f"{kept}" + (" (it replaces the earlier unfinished run's log there: copy one "
                         "elsewhere first to keep it)" if replaced else "")
            + earlier_version_runs_words(log, "incomplete"))


def run(args) -> int:
    from tegrasp_drake.hardware.config import LoadHardwareConfig
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.hardware.config import HardwareStationConfig
    problem = args.duration is not None and duration_problem(args.duration)
    if problem:  # a number outside its range: bad input, not a command line that does not parse
        raise SystemExit(f"{ERROR_LEAD}{problem}")
    scenario = scenario_from_arguments(args)
    if args.config:
        try:
            config = LoadHardwareConfig(args.config, args.config_overrides)
        except ConfigError as e:
            raise SystemExit(f"{ERROR_LEAD}{e}") from None
    elif isinstance(scenario.station, HardwareStationConfig):
        config = scenario.station
    else:
        raise SystemExit(f"{ERROR_LEAD}give --config FILE, or a scenario whose `station` "
                         "is `!HardwareStationConfig {...}`")
    from tegrasp_drake.hardware.config import lcm_url_origin, shared_lcm_url_problem
    problem = shared_lcm_url_problem(config.arm.lcm_url)  # the arm's driver is another process
    if problem:
        where = args.config or "the scenario's station"
        origin = lcm_url_origin(config.arm.lcm_url, "field 'arm.lcm_url'")
        raise SystemExit(f"{ERROR_LEAD}{shorten(where)}: {origin} {problem}, got "
                         f"{shown(config.arm.lcm_url)}")
    source = args.config or "the scenario's station"
    logger.info(f"hardware: devices checked ({source}): arm "
                f"on {config.arm.lcm_url}, gripper on {config.gripper.port}, tactile on "
                f"{config.tactile.port}")
    events = controller_events(scenario, args.events)
    corrective = corrective_events(scenario, args.events)
    log = args.log or (f"out/hardware/run-"
                       f"{datetime.datetime.now().strftime('%Y%m%d-%H%M%S')}.lcmlog")
    result_path = result_path_beside_log(log)
    failed_log = failed_run_path(log)
    for taken in (pathlib.Path(log), result_path,
                  failed_log, result_path_beside_log(failed_log)):
        # The write rule first: --overwrite replaces a file, never a folder (of the user's
        # files), a device or a FIFO, so such a path is refused as such whether it exists
        # or not, before it is said to hold an earlier run. The same for where a failed
        # run's pair would go (failed_run_path).
        problem = output_file_problem(taken)
        if problem:
            where = "" if taken == pathlib.Path(log) else f": {shorten(str(taken))}"
            raise SystemExit(f"{ERROR_LEAD}--log {shorten(str(log))}{where} {problem}")
    # The folders --log needs are made for the run and, if it ends refused or failed before
    # it wrote anything, removed again (a refused run leaves nothing).
    from tegrasp_drake.rig.files import (absent_folders, made_folders_removed_if_empty,
                                         remove_made_folders_if_empty)
    made = absent_folders(pathlib.Path(log).parent)
    with made_folders_removed_if_empty(made):
        code = _run_in_log_folder(args, scenario, config, events, corrective, log,
                                  result_path)
    if code:
        remove_made_folders_if_empty(made)  # a run refused by its code wrote nothing there
    return code


def _run_in_log_folder(args, scenario, config, events, corrective, log, result_path) -> int:
    """The run, its --log's folder made, holding the log (held_file): one run at a time."""
    from tegrasp_drake.rig.files import FileHeldError, held_file
    with contextlib.ExitStack() as stack:
        pathlib.Path(log).parent.mkdir(parents=True, exist_ok=True)
        # One run at a time per --log: a second one (with --overwrite or not) would replace
        # the first one's log and result under it.
        try:
            stack.enter_context(held_file(log))
        except FileHeldError:
            raise SystemExit(f"{ERROR_LEAD}--log {shorten(str(log))}: another tegrasp "
                             "hardware run is writing it now; give another --log, or wait "
                             "for that run to end") from None
        except OSError as e:
            raise SystemExit(f"{ERROR_LEAD}--log {shorten(str(log))}: cannot make its "
                             f"lock file beside it: {os_error_text(e)}") from None
        return _run_holding_log(args, scenario, config, events, corrective, log,
                                result_path)


HARDWARE_RESULT_MAX_BYTES = 16 * 1024 * 1024  # a run's result: its transitions and counters


def earlier_run_file_problem(path, *, is_log: bool,
                             remedy: str = "give another --log, or remove it yourself"
                             ) -> str | None:
    """Why --overwrite may not replace `path`, in words that follow it, or None: the earlier
    file must be what a hardware run writes there, an LCM log (empty, or starting with
    LCM_LOG_START, and its result beside it naming it: an LCM log the user recorded otherwise
    is theirs) or a run's result (a JSON object with HARDWARE_RESULT_KEYS); the user's
    notes saved under a run's name are not replaced. Only the log's head is read. `remedy`:
    what to do, ending the words."""
    from tegrasp_drake.rig.files import JsonFileError, read_json_file
    from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START
    from tegrasp_drake.runs.hardware_run import HARDWARE_RESULT_KEYS
    if is_log:
        try:
            head = existing_file_head(path, len(LCM_LOG_START)) or b""
        except OSError as error:
            return f"cannot be read to check what it is ({os_error_text(error)}); {remedy}"
        if head and head != LCM_LOG_START:
            return f"exists and is not an LCM log (its first bytes are not LCM's); {remedy}"
        beside = result_path_beside_log(path)
        unread = os.path.lexists(beside) and earlier_run_file_problem(beside, is_log=False)
        if head and not unread and not _names_log(beside, path):  # unread: said of `beside`
            # an LCM log of the user's (lcm-logger's), not a run's: no run's result names it
            return (f"exists and is an LCM log of no earlier run (no {beside.name} beside it "
                    f"names it as its log: a run writes both); {remedy}")
        return None

    def not_a_result(data) -> str | None:
        missing = [key for key in HARDWARE_RESULT_KEYS
                   if not isinstance(data, dict) or key not in data]
        return (f"is not a hardware run's result (no {', '.join(missing)})" if missing
                else None)
    try:
        read_json_file(path, limit=HARDWARE_RESULT_MAX_BYTES, kind="a hardware run's result",
                       check=not_a_result)
    except JsonFileError as error:
        return f"exists and {error.problem}; {remedy}"
    return None


def failed_pair_problem(log) -> str | None:
    """Why a run on `log` that fails could not put its log and result where it keeps them
    beside the earlier run's (failed_run_path), in words that follow "--log LOG: ", or None:
    --overwrite replaces there only an earlier failed run's pair (earlier_run_file_problem),
    never a file of the user's, so such a file is refused before the devices come up."""
    failed_log = failed_run_path(log)
    for taken in (failed_log, result_path_beside_log(failed_log)):
        if not os.path.lexists(taken):
            continue
        problem = earlier_run_file_problem(taken, is_log=taken == failed_log,
                                           remedy="move it away, or give another --log")
        if problem:
            what = "log" if taken == failed_log else "result"
            return (f"{shorten(str(taken))}, where a run that fails puts its {what} (keeping "
                    f"the earlier run's), {problem}")
    return None


def _names_log(result_path, log) -> bool:
    """Whether a hardware run's result is at `result_path` naming `log` as its log (by its
    name: the folder may have been moved since): what tells an earlier run's log from an LCM
    log of the user's."""
    from tegrasp_drake.rig.files import JsonFileError, read_json_file
    try:
        data = read_json_file(result_path, limit=HARDWARE_RESULT_MAX_BYTES,
                              kind="a hardware run's result")
    except JsonFileError:  # missing or unreadable: no run's
        return False
    logged = data.get("log") if isinstance(data, dict) else None
    return isinstance(logged, str) and pathlib.PurePath(logged).name == pathlib.Path(log).name


def _run_holding_log(args, scenario, config, events, corrective, log, result_path) -> int:
    from tegrasp_drake.runs.hardware_run import LOG_MIN_FREE_BYTES, run_on_hardware
    from tegrasp_drake.hardware.station import DeviceAbsentError, HardwareNotReadyError
    earlier = [taken for taken in (pathlib.Path(log), result_path) if taken.exists()]
    for taken in earlier:  # --overwrite replaces a run's log and result, nothing else
        # What the file is, first: one that is not a run's log or result (a trial's
        # result.json given as --log) is said as such, with or without --overwrite.
        problem = earlier_run_file_problem(taken, is_log=taken == pathlib.Path(log))
        if problem:
            where = "" if taken == pathlib.Path(log) else f": {shorten(str(taken))}"
            raise SystemExit(f"{ERROR_LEAD}--log {shorten(str(log))}{where} {problem}")
    for taken in earlier:
        if not args.overwrite:
            raise SystemExit(f"{ERROR_LEAD}{shorten(str(taken))} already holds a run's "
                             f"{'log' if taken == pathlib.Path(log) else 'result'}; give "
                             "another --log, or --overwrite to replace it")
    problem = earlier and failed_pair_problem(log)
    if problem:
        raise SystemExit(f"{ERROR_LEAD}--log {shorten(str(log))}: {problem}")
    problem = free_space_problem(  # before the devices come up
        pathlib.Path(log).parent, LOG_MIN_FREE_BYTES, "its log (ten seconds of the bus)")
    if problem:
        raise SystemExit(f"{ERROR_LEAD}--log {shorten(str(log))} {problem}")
    # The run logs to a hidden file beside --log; the earlier log and result stay whole
    # until this run's replace them together at the end (commit_hardware_run), and a run
    # that fails keeps them (its own go beside them, failed_run_path). A killed run's
    # staging file is removed by the next run logging to the same --log.
    from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START
    staged = staging_file_beside(log, LCM_LOG_START)
    try:
        with SimulatedTimeBar("hardware", enabled=progress_wanted(args)) as progress:
            result = run_on_hardware(scenario, config=config, events=events,
                                     corrective_events=corrective,
                                     events_dir=_events_folder(events, args, scenario),
                                     log_path=staged, duration=_seconds(args.duration),
                                     out=progress.write, progress=progress)
    except HardwareNotReadyError as e:
        staged.unlink(missing_ok=True)
        # a device's port is a field of the hardware config: the line names where it is
        config_file = args.config or "the scenario's station"
        where = f"{config_file}: " if isinstance(e, DeviceAbsentError) else ""
        print(f"{ERROR_LEAD}{error_line(f'{where}{e}')}", file=sys.stderr, flush=True)
        return 1
    except BaseException:
        kept, replaced = keep_incomplete_log(staged, log)
        if kept:
            print("tegrasp: the run did not finish; what its log recorded is in "
                  + incomplete_log_words(kept, replaced, log), file=sys.stderr, flush=True)
        raise
    failed = bool(result.faults or result.log_fault or (
        result.transitions and result.transitions[-1]["to"] == "Failed"))
    keep_earlier = failed and earlier
    target = failed_run_path(log) if keep_earlier else pathlib.Path(log)
    target_result = result_path_beside_log(target)
    replaced_failed = ([taken for taken in (target, target_result) if taken.exists()]
                       if keep_earlier else [])
    logged = staged.exists()  # none when the bus could not be recorded, or was removed
    kept_words = ("; the earlier run's " + " and ".join(str(taken) for taken in earlier)
                  + " are kept" if earlier else "")
    try:
        commit_hardware_run(staged, target, target_result,
                            dict(result.as_dict(), log=str(target) if logged else None,
                                 result=str(target_result)))
    except OSError as e:
        kept, replaced = keep_incomplete_log(staged, log)
        raise SystemExit(f"{ERROR_LEAD}cannot write the run's result to "
                         f"{shorten(str(target_result))}: "
                         f"{os_error_text(e)}"
                         + (f"; its log is in {incomplete_log_words(kept, replaced, log)}"
                            if kept else "") + kept_words)
    logger.info(f"hardware: wrote {f'the log {target} and ' if logged else ''}the result "
                f"{target_result}")
    if earlier and not keep_earlier:
        logger.info("hardware: replaced the earlier run's "
                    + " and ".join(f"{'log' if taken == pathlib.Path(log) else 'result'} "
                                   f"{taken}" for taken in earlier))
    older_failed_words = earlier_version_runs_words(log) if keep_earlier else ""
    log = target
    result_path = target_result
    result = dataclasses.replace(result, log_path=pathlib.Path(log))
    faults = len(result.faults) + bool(result.log_fault)  # a log that stops is a fault
    logged_words = (f"log {result.log_path} ({result.log_messages} messages)" if logged
                    else "no log")
    print(f"ran {result.sim_time:.2f} s in {result.wall_time:.2f} s (real-time rate "
          f"{result.realtime_rate:.3f}); {len(result.transitions)} transitions, "
          f"{count_text(faults, 'fault')}"
          f"{' (the log stopped)' if result.log_fault else ''}; {logged_words}, "
          f"result {result_path}", flush=True)
    if result.log_fault:
        print(f"{ERROR_LEAD}{error_line(str(result.log_fault))}; the run was stopped",
              file=sys.stderr,
              flush=True)
    if keep_earlier:
        replaced_words = ("; they replace the earlier failed run's "
                          + " and ".join(str(taken) for taken in replaced_failed)
                          if replaced_failed else "")
        print(f"tegrasp: the run failed{kept_words}; this run's are {log} and {result_path}"
              f"{replaced_words}{older_failed_words}",
              file=sys.stderr, flush=True)
    return 2 if failed else 0
