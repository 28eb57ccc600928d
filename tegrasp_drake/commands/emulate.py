"""`tegrasp emulate {jaco,robotiq,myrio,all}`: the devices, emulated on this host
(tegrasp_drake/emulators/launcher.py says what each does).

jaco: the JACO2 simulation on LCM; robotiq: the 2F-85 on a pseudo-terminal, the scenario's
object between its fingers; myrio: the tactile stream on a pseudo-terminal replaying
`--trial NPZ`; all: the three in one process (--sync follow, --follow-gripper). Each prints
where it listens, a line "devices: {JSON}" (emulators/emulator_process.py reads it) and
"ready"; `--write-config FILE` writes the hardware config. They run until SIGINT, SIGTERM or SIGHUP
(STOP_SIGNALS), then print "stopped" and end with 128 + N, as every command a signal stops."""

import argparse
import logging
import math
import pathlib
import re
import signal

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.scenario_args import add_scenario_arguments, scenario_from_arguments
from tegrasp_drake.hardware.robotiq.modbus_client import quiet_modbus_library
from tegrasp_drake.emulators.launcher import DEVICES as EMULATED_DEVICES
from tegrasp_drake.emulators.launcher import (SYNC_MODES, WRITTEN_BY_EMULATE, Emulators,
                                              FaultInjection)
from tegrasp_drake.hardware.config import (default_lcm_url, lcm_url_option, lcm_url_origin,
                                           shared_lcm_url_problem)
from tegrasp_drake.rig.ranges import FAULT_DELAY
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.hardware.realtime import (EMULATOR_PRIORITY, SCHEDULING_POLICIES,
                                              raise_scheduling)
from tegrasp_drake.rig.files import existing_file_head, output_file_problem, os_error_text

logger = logging.getLogger(__name__)

# The signals that stop the devices, which then close before the command ends with 128 + N.
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)

DEVICES = (*EMULATED_DEVICES, "all")
GFLT_MAX = 0xF  # the Robotiq status register's fault field is 4 bits
# The options only some devices use, by `dest`: refused, not ignored, for the others.
DEVICE_OPTIONS = {"trial": ("--trial", "myrio"), "sync": ("--sync", "myrio"),
                  "follow_gripper": ("--follow-gripper", "myrio"),
                  "inject_fault": ("--inject-fault", "robotiq")}


EPILOG = """\
examples:
  tegrasp emulate all --trial out/demo/trial.npz --write-config hw.yaml
  tegrasp emulate robotiq --scenario-name box --inject-fault 0x0E@3

Then `tegrasp hardware --config hw.yaml` in another shell; Ctrl-C stops the emulators."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "emulate", help="emulate the Jaco (LCM), the Robotiq 2F-85 (Modbus RTU on a pty) "
        "and the myRIO tactile stream (pty) for `tegrasp hardware`",
        description=__doc__.split("\n\n")[0], epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("device", choices=DEVICES)
    add_scenario_arguments(parser)
    lcm_url = parser.add_argument(
        "--lcm-url", default=default_lcm_url(), type=lcm_url_option,
        help="the arm's LCM bus, which also carries the emulated gripper's state "
        "(default: %(default)s)")
    lcm_url.default_origin = lcm_url_origin  # LCM_DEFAULT_URL's, named as such

    parser.add_argument("--trial", metavar="NPZ",
                        help="myrio/all: the recorded trial to replay (a TrialLog .npz)")
    parser.add_argument("--sync", choices=SYNC_MODES, default=None,
                        help="myrio: replay at once (none), from the first "
                        "KINOVA_JACO_COMMAND on --lcm-url (start), or on the commands' "
                        "clock (follow; the default with `all`, else none)")
    parser.add_argument("--follow-gripper", action=argparse.BooleanOptionalAction,
                        default=None,
                        help="myrio: at each gripper command of the trial (its grip, its "
                        "release), hold the replay until the emulated gripper is commanded "
                        "likewise (`emulate robotiq` on --lcm-url, or the one of `all`), so "
                        "the pads never show a release the controller has not commanded "
                        "(default: on with `all`, else off)")
    parser.add_argument("--inject-fault", type=fault_option, metavar="CODE@SECONDS",
                        help="robotiq/all: set gFLT to CODE (hexadecimal with 0x, e.g. "
                        "0x0E, or decimal, e.g. 14) SECONDS after the gripper's activation "
                        "completes")
    parser.add_argument("--write-config", metavar="FILE",
                        help="write the hardware config for `tegrasp hardware --config`")
    parser.add_argument("--scheduling", choices=SCHEDULING_POLICIES, default="fifo",
                        help="the emulators' scheduling: a real device has its own "
                        "processor, so by default the stand-ins run at real-time priority "
                        "(SCHED_FIFO, falling back to nice, then normal, where the OS "
                        "refuses), as the tests run them (default: %(default)s)")
    parser.set_defaults(func=run)


def config_written_line(emulators, path) -> str:
    """What --write-config wrote: the file, and the ports it holds that are no emulated
    device's (the config's defaults, for the devices emulated elsewhere or real ones)."""
    config = emulators.hardware_config()
    kept = [f"{section}.port {getattr(config, section).port}"
            for section in ("gripper", "tactile") if section not in emulators.devices]
    defaults = (f" ({', '.join(kept)}: the defaults, for devices not emulated here; set them "
                "to your devices' ports)" if kept else "")
    return f"config: wrote {path}{defaults}; run `tegrasp hardware --config {path}`"


# CODE: hexadecimal with 0x (as the 2F-85 manual writes gFLT codes) or decimal, nothing else
# (int(text, 0) would also take 0b1110, 0o16 and 1_4).
FAULT_CODE = re.compile(r"\s*(0[xX][0-9a-fA-F]+|[0-9]+)\s*")


def _fault_parts(text: str) -> tuple[int, float]:
    """(CODE, SECONDS) of CODE@SECONDS, SECONDS read as every number option reads its text
    (rig.number_text.read_number); ValueError when `text` is not of that form."""
    from tegrasp_drake.rig.number_text import read_number
    code, at = text.split("@")
    if not FAULT_CODE.fullmatch(code):
        raise ValueError(code)
    return int(code, 0 if code.strip()[:2].lower() == "0x" else 10), read_number(at)


def fault_option(text: str) -> str:
    """--inject-fault's text, once it is of the form CODE@SECONDS (text of another form does
    not parse: exit 2); CODE and SECONDS are checked against their ranges by _parse_fault
    when the command runs (bad input, exit 1)."""
    from tegrasp_drake.rig.number_text import NumberTextError
    try:
        _fault_parts(text)
    except NumberTextError as e:  # of the form, its SECONDS no number a float holds
        raise argparse.ArgumentTypeError(
            f"{shown(text)}: SECONDS {shown(text.split('@')[1])} {e}") from None
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{shown(text)}: expected CODE@SECONDS, CODE hexadecimal with 0x or decimal, "
            "e.g. 0x0E@3.5 or 14@3.5") from None
    return text


def _parse_fault(text) -> FaultInjection:
    """CODE@SECONDS (its form checked by fault_option): CODE a gFLT fault (4 bits, not 0x0,
    which is no fault: 0x1..0xF, or decimal 1..15), SECONDS in FAULT_DELAY."""
    code, at = _fault_parts(text)
    if not 0 < code <= GFLT_MAX:
        raise SystemExit(f"{ERROR_LEAD}--inject-fault {shown(text)}: the 2F-85's "
                         f"fault register gFLT holds 4 bits, 0x0 being no fault; give a CODE "
                         f"from 0x1 to {GFLT_MAX:#x} (decimal 1 to {GFLT_MAX})")
    if not (math.isfinite(at) and FAULT_DELAY.contains(at)):
        raise SystemExit(f"{ERROR_LEAD}--inject-fault {shown(text)}: SECONDS "
                         f"{FAULT_DELAY.words(at)}, got {shorten(text.split('@')[1])}")
    return FaultInjection(code, at)


def _check_config_target(path) -> None:
    """Exits before any device starts when --write-config would replace a file that
    `tegrasp emulate` did not write, or cannot be written."""
    path = pathlib.Path(path)
    if path.is_dir():
        raise SystemExit(f"{ERROR_LEAD}--write-config {path} is a folder; give a file "
                         "name, e.g. hw.yaml")
    problem = output_file_problem(path)  # a missing folder is made, as plot --out's is
    if problem:
        raise SystemExit(f"{ERROR_LEAD}--write-config {path} {problem}")
    if path.exists():
        try:  # the first line only: a huge file is no config emulate wrote, and not read
            head = existing_file_head(path, len(WRITTEN_BY_EMULATE.encode()) + 1) or b""
            first = head.decode("utf-8", errors="replace").split("\n", 1)[0]
        except OSError as e:
            raise SystemExit(f"{ERROR_LEAD}--write-config {path}: cannot read it "
                             f"({os_error_text(e)}); give another file name") from None
        if first != WRITTEN_BY_EMULATE:
            raise SystemExit(f"{ERROR_LEAD}--write-config {path} exists and was not "
                             "written by `tegrasp emulate` (its first line is not the one "
                             "emulate writes); give another file name, or remove it yourself")


def _refuse_unused_options(args, devices) -> None:
    """Exits naming the first option given that none of `devices` uses (DEVICE_OPTIONS)."""
    for dest, (option, device) in DEVICE_OPTIONS.items():
        if getattr(args, dest) is not None and device not in devices:
            raise SystemExit(f"{ERROR_LEAD}{option} applies to `emulate {device}` and "
                             f"`emulate all`; `emulate {args.device}` does not use it, so "
                             f"leave {option} out")


def run(args) -> int:
    from tegrasp_drake.emulators.myrio_emulator import TactileRecordingError
    quiet_modbus_library()
    def out(line):
        print(line, flush=True)

    _refuse_unused_options(args, EMULATED_DEVICES if args.device == "all" else (args.device,))
    scenario = scenario_from_arguments(args)
    if args.write_config:
        _check_config_target(args.write_config)
    if args.device in ("myrio", "all") and not args.trial:
        raise SystemExit(f"{ERROR_LEAD}emulate myrio/all needs --trial NPZ (a trial log; "
                         "`tegrasp demo --out DIR` writes DIR/trial.npz)")
    devices = EMULATED_DEVICES if args.device == "all" else (args.device,)
    inject_fault = (_parse_fault(args.inject_fault)
                    if args.inject_fault and "robotiq" in devices else None)
    if "myrio" in devices:
        from tegrasp_drake.emulators.myrio_emulator import load_tactile_recording
        try:
            # checked before the process is raised; a trial log, never a bare recording
            load_tactile_recording(args.trial, bare=False)
        except TactileRecordingError as e:
            raise SystemExit(f"{ERROR_LEAD}{e}") from None
    sync = args.sync or ("follow" if args.device == "all" else "none")
    follow_gripper = (args.follow_gripper if args.follow_gripper is not None
                      else args.device == "all")
    if "jaco" in devices or "robotiq" in devices or sync == "follow" or (
            follow_gripper and "myrio" in devices):  # they open --lcm-url
        problem = shared_lcm_url_problem(args.lcm_url)  # the check `tegrasp hardware` makes
        if problem:
            raise SystemExit(f"{ERROR_LEAD}{lcm_url_origin(args.lcm_url, '--lcm-url')} "
                             f"{shown(args.lcm_url)} {problem}")
    # Every argument is checked above; only now is the whole process raised.
    logger.info(f"emulate: arguments checked; starting {', '.join(devices)} (LCM "
                f"{args.lcm_url}, sync {sync})")
    out(f"scheduling: {raise_scheduling(args.scheduling, EMULATOR_PRIORITY)}")
    emulators = Emulators(lcm_url=args.lcm_url, out=out)
    stopped_by = []  # the signals that stopped the devices, first first

    def stop(signal_number, _frame):
        stopped_by.append(signal.Signals(signal_number).name)
        emulators.stop.set()

    for signal_number in STOP_SIGNALS:
        signal.signal(signal_number, stop)
    try:
        emulators.start(devices, scenario, trial=args.trial, sync=sync,
                        follow_gripper=follow_gripper and "myrio" in devices,
                        inject_fault=inject_fault)
        if args.write_config:
            replaced = pathlib.Path(args.write_config).exists()
            emulators.write_hardware_config(args.write_config)
            if replaced:
                logger.info(f"emulate: replaced the earlier config {args.write_config}")
            out(config_written_line(emulators, args.write_config))
        out(emulators.devices_line())
        out("ready")
        emulators.run_until_stopped()
    except TactileRecordingError as e:
        raise SystemExit(f"{ERROR_LEAD}{e}") from None
    finally:
        emulators.close()
        logger.info("emulate: the devices stopped")
    out("stopped")
    if stopped_by:  # the devices closed: now 128 + N, as every command a signal stops (cli.py)
        raise KeyboardInterrupt(stopped_by[0])
    return 0
