"""`tegrasp emulate {jaco,robotiq,myrio,all}`: the devices, emulated on this host.

- jaco: a Drake simulation of the JACO2 on LCM (drivers/jaco_arm_emulator.py) at the
  scenario's start pose, in real time: it executes lcmt_jaco_command joint velocities and
  answers lcmt_jaco_status at 100 Hz on KINOVA_JACO_COMMAND / KINOVA_JACO_STATUS.
- robotiq: a Robotiq 2F-85 answering Modbus RTU (slave 9, 115200 8N1) on a pseudo-terminal,
  with the scenario's object between its fingers (drivers/robotiq_emulator.py).
- myrio: the myRIO tactile stream (drivers/TACTILE_FRAME.md) on a pseudo-terminal,
  replaying a recorded trial (a TrialLog .npz: `tegrasp demo --out DIR` writes one) at its
  real rate, then holding its last values. With --sync start it streams quiet pads until
  the first KINOVA_JACO_COMMAND, so the replay starts with the controller; with --sync
  follow it also follows the controller's clock (the commands' utime, ControllerClock),
  so the replay stays in step with a controller that runs behind real time.
- all: the three in one process, with --sync follow by default.

Each prints where it listens, `--write-config FILE` writes the hardware config that
points `tegrasp hardware --config FILE` at them, and the line "ready" when they are up.
They run until Ctrl-C (SIGINT) or SIGTERM.
"""

import signal
import threading

import numpy as np

from tegrasp_drake.commands.scenario_args import (add_scenario_arguments, quiet_modbus_library,
                                                   scenario_from_arguments)
from tegrasp_drake.hardware.config import DEFAULT_LCM_URL

DEVICES = ("jaco", "robotiq", "myrio", "all")


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "emulate", help="emulate the Jaco (LCM), the Robotiq 2F-85 (Modbus RTU on a pty) "
        "and the myRIO tactile stream (pty) for `tegrasp hardware`")
    parser.add_argument("device", choices=DEVICES)
    add_scenario_arguments(parser)
    parser.add_argument("--lcm-url", default=DEFAULT_LCM_URL,
                        help="the arm's LCM bus (default: %(default)s)")
    parser.add_argument("--trial", metavar="NPZ",
                        help="myrio/all: the recorded trial to replay (a TrialLog .npz)")
    parser.add_argument("--sync", choices=("none", "start", "follow"), default=None,
                        help="myrio: replay at once (none), from the first "
                        "KINOVA_JACO_COMMAND on --lcm-url (start), or on the commands' "
                        "clock (follow; the default with `all`, else none)")
    parser.add_argument("--inject-fault", metavar="CODE@SECONDS",
                        help="robotiq/all: set gFLT to CODE (e.g. 0x0E) SECONDS after the "
                        "gripper's activation completes")
    parser.add_argument("--write-config", metavar="FILE",
                        help="write the hardware config for `tegrasp hardware --config`")
    parser.set_defaults(func=run)


def load_tactile_trial(path):
    """The myRIO replay of a TrialLog .npz: taxel forces (t_sa, taxels) and pad
    accelerations (t_ra, pad_acceleration); no other array is needed."""
    from tegrasp_drake.emulators.myrio_emulator import TactileTrial
    try:
        with np.load(path, allow_pickle=False) as data:
            t_sa, taxels = data["t_sa"], data["taxels"]
            t_ra, acceleration = data["t_ra"], data["pad_acceleration"]
    except (OSError, KeyError, ValueError) as e:
        raise SystemExit(f"tegrasp: error: '{path}' is not a trial log with t_sa, taxels, "
                         f"t_ra and pad_acceleration: {e}") from None
    return TactileTrial(t_sa, taxels[:, :12], taxels[:, 12:], t_ra, acceleration[:, :3],
                        acceleration[:, 3:])


def _parse_fault(text):
    try:
        code, at = text.split("@")
        return int(code, 0), float(at)
    except ValueError:
        raise SystemExit(f"tegrasp: error: --inject-fault '{text}': expected CODE@SECONDS, "
                         "e.g. 0x0E@3.5") from None


class Emulators:
    """The emulators started by one command; close() stops them all."""

    def __init__(self):
        self.config_fields = {}
        self._closers = []
        self.stop = threading.Event()

    def add_closer(self, closer):
        self._closers.append(closer)

    def close(self):
        self.stop.set()
        for closer in reversed(self._closers):
            closer()


def start_robotiq(emulators, scenario, inject_fault, out):
    import time

    from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator, RobotiqEmulatorConfig
    width = scenario.object.width_along_stroke()
    emulator = RobotiqEmulator(RobotiqEmulatorConfig(object_opening=width)).start()
    emulators.add_closer(emulator.stop)
    emulators.config_fields["gripper"] = {"port": emulator.port}
    out(f"robotiq: Robotiq 2F-85 (Modbus RTU, slave 9, 115200 8N1) on {emulator.port}, "
        f"object {width * 1000:.1f} mm wide between the fingers")
    if inject_fault:
        code, delay = _parse_fault(inject_fault)

        def inject():
            while not emulators.stop.is_set():
                if emulator.model.status(time.monotonic())[2] == 3:  # gSTA: active
                    break
                emulators.stop.wait(0.01)
            if not emulators.stop.wait(delay):
                emulator.inject_fault(code)
                out(f"robotiq: injected fault 0x{code:02X}")
        threading.Thread(target=inject, daemon=True).start()
    return emulator


def start_myrio(emulators, trial_path, sync, out):
    """The myRIO emulator; with sync start/follow, its ControllerClock (feed it commands)."""
    from tegrasp_drake.emulators.controller_clock import ControllerClock
    from tegrasp_drake.emulators.myrio_emulator import MyRioEmulator, MyRioEmulatorConfig
    trial = load_tactile_trial(trial_path)
    clock = ControllerClock() if sync in ("start", "follow") else None
    emulator = MyRioEmulator(trial, MyRioEmulatorConfig(
        start_on_trigger=clock is not None, hold_at_end=True),
        trial_clock=clock if sync == "follow" else None).start()
    emulators.add_closer(emulator.stop)
    emulators.config_fields["tactile"] = {"port": emulator.port}
    if clock is not None:
        def start_on_first_command():
            while not clock.started.wait(0.2):
                if emulators.stop.is_set():
                    return
            emulator.start_trial()
        threading.Thread(target=start_on_first_command, daemon=True).start()
    when = {"none": "now", "start": "from the arm's first command",
            "follow": "on the arm commands' clock"}[sync]
    out(f"myrio: tactile stream (1 kHz frames) on {emulator.port}, replaying {trial_path} "
        f"({trial.duration:.2f} s) {when}, then holding its last values")
    return emulator, clock


def make_jaco(scenario, lcm_url, out):
    from pydrake.lcm import DrakeLcm

    from tegrasp_drake.emulators.jaco_arm_emulator import MakeJacoArmEmulator
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL
    from tegrasp_drake.simulation.station import initial_arm_positions
    drake_lcm = DrakeLcm(lcm_url)
    diagram = MakeJacoArmEmulator(lcm=drake_lcm,
                                  initial_positions=initial_arm_positions(scenario))
    out(f"jaco: JACO2 simulation on {lcm_url}: executes {JACO_COMMAND_CHANNEL}, answers "
        f"{JACO_STATUS_CHANNEL} at 100 Hz")
    return drake_lcm, diagram


def run_jaco_until_stopped(diagram, stop: threading.Event):
    from pydrake.systems.analysis import Simulator
    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(1.0)
    simulator.Initialize()
    context = simulator.get_context()
    while not stop.is_set():
        simulator.AdvanceTo(context.get_time() + 0.05)


def write_config(path, fields: dict, lcm_url: str, out):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    config = HardwareStationConfig()
    config.arm.lcm_url = lcm_url
    config.gripper.port = fields.get("gripper", {}).get("port", config.gripper.port)
    config.tactile.port = fields.get("tactile", {}).get("port", config.tactile.port)
    text = hardware_config_to_yaml(config)
    if path:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        out(f"config: wrote {path}; run `tegrasp hardware --config {path}`")


def run(args) -> int:
    quiet_modbus_library()
    def out(line):
        print(line, flush=True)

    scenario = scenario_from_arguments(args)
    if args.device in ("myrio", "all") and not args.trial:
        raise SystemExit("tegrasp: error: emulate myrio/all needs --trial NPZ (a trial log; "
                         "`tegrasp demo --out DIR` writes DIR/trial.npz)")
    emulators = Emulators()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signal_number, lambda *_: emulators.stop.set())
    try:
        jaco = None
        if args.device in ("jaco", "all"):
            jaco = make_jaco(scenario, args.lcm_url, out)
        if args.device in ("robotiq", "all"):
            start_robotiq(emulators, scenario, args.inject_fault, out)
        if args.device in ("myrio", "all"):
            sync = args.sync or ("follow" if args.device == "all" else "none")
            _, clock = start_myrio(emulators, args.trial, sync, out)
            if clock is not None and jaco is not None:
                from drake import lcmt_jaco_command

                from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL
                jaco[0].Subscribe(JACO_COMMAND_CHANNEL, lambda data: clock.on_command(
                    lcmt_jaco_command.decode(data).utime))
            elif clock is not None:
                from tegrasp_drake.emulators.controller_clock import follow_jaco_commands
                follow_jaco_commands(args.lcm_url, clock, emulators.stop)
        write_config(args.write_config, emulators.config_fields, args.lcm_url, out)
        out("ready")
        if jaco is not None:
            run_jaco_until_stopped(jaco[1], emulators.stop)
        else:
            while not emulators.stop.wait(0.2):
                pass
    finally:
        emulators.close()
    out("stopped")
    return 0
