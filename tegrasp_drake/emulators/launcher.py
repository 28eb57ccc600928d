"""The emulated devices of one `tegrasp emulate`, started together in this process: the JACO2 as a
real-time Drake simulation on LCM (jaco_arm_emulator.py), the 2F-85 on a pseudo-terminal with the
scenario's object between its fingers (robotiq_emulator.py; it publishes its state for a myRIO
emulator elsewhere, gripper_link.py) and the myRIO replaying a recorded trial (myrio_emulator.py) in
step with the arm's commands and, if asked, the gripper (docs/hardware.md, "The commands").

What the devices receive crosses a MessageBoundary; `Emulators` reports each kind of rejected
message once and the counts at close. `devices_line()` gives the devices' HardwareStationConfig
fields as one JSON line for programs (`devices_from_line`)."""

import dataclasses
import json
import logging
import pathlib
import threading
import time

from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.robotiq import units
from tegrasp_drake.rig.files import write_atomically

# The first line of a hardware config that `tegrasp emulate --write-config` wrote.
WRITTEN_BY_EMULATE = "# written by `tegrasp emulate --write-config`; the next one replaces it"

# [s] The watchdog timeout the written config gives each emulated device. The emulators are
# threads of one Python process on a general-purpose host that they share with the control
# loop, so one stall of that process (the interpreter lock, a loaded CPU) silences them all at
# once: on a loaded 2-core host the arm and the tactile stream fell silent together for 54 ms,
# past the real devices' 50 ms. Ten of those real timeouts is what the emulators, which have
# no processor of their own, are given; a real device keeps its 50-100 ms (DEFAULT_TIMEOUTS).
EMULATED_WATCHDOG_TIMEOUT_S = 0.5

DEVICES = ("jaco", "robotiq", "myrio")
# The watchdog's name (DeviceWatchdogConfig.<device>_timeout) of each emulated device.
_WATCHDOG_DEVICE = {"jaco": "arm", "robotiq": "gripper", "myrio": "tactile"}
SYNC_MODES = ("none", "start", "follow")
DEVICES_LINE_PREFIX = "devices: "

logger = logging.getLogger(__name__)


def devices_from_line(line: str) -> dict | None:
    """The {config section: {field: value}} of a `devices_line`, or None for another line."""
    if not line.startswith(DEVICES_LINE_PREFIX):
        return None
    return json.loads(line[len(DEVICES_LINE_PREFIX):])


def hardware_config_for(devices: dict) -> HardwareStationConfig:
    """The default HardwareStationConfig with the fields of `devices` ({"arm": {"lcm_url":
    ...}, "gripper": {"port": ...}, "tactile": {"port": ...}}, any of them) set."""
    config = HardwareStationConfig()
    for section, fields in devices.items():
        for name, value in fields.items():
            setattr(getattr(config, section), name, value)
    return config


@dataclasses.dataclass(frozen=True)
class FaultInjection:
    """Set gFLT to `code` `delay` [s] after the gripper's activation completes."""
    code: int
    delay: float


class Emulators:
    """The emulated devices (module docstring); close() stops them all. lcm_url: the arm's bus;
    out: takes each line saying where a device listens or what it does."""

    def __init__(self, *, lcm_url: str, out=print):
        self.lcm_url = lcm_url
        self.stop = threading.Event()
        self._out = out
        self._devices = {}
        self._closers = []
        self._jaco = None  # (DrakeLcm, emulator Diagram, its command boundary)
        self._robotiq = None  # RobotiqEmulator
        self._boundaries = []  # MessageBoundary of every inbound path, for the counts
        self._started = []  # the DEVICES started, in DEVICES order

    def start(self, devices, scenario, *, trial=None, sync: str = "none",
              follow_gripper: bool = False,
              inject_fault: FaultInjection | None = None) -> "Emulators":
        """Starts `devices` (in DEVICES order) at the scenario's arm start pose and object; `trial`
        is the TrialLog .npz the myRIO replays."""
        unknown = set(devices) - set(DEVICES)
        if unknown:
            raise ValueError(f"unknown devices {sorted(unknown)}; known: {DEVICES}")
        if sync not in SYNC_MODES:
            raise ValueError(f"sync must be one of {SYNC_MODES}, got {sync!r}")
        if "myrio" in devices and trial is None:
            raise ValueError("the myRIO needs a trial to replay")
        if "jaco" in devices:
            self._start_jaco(scenario)
            logger.info(f"emulate: jaco up on {self.lcm_url}")
        if "robotiq" in devices:
            self._start_robotiq(scenario, inject_fault, publish="myrio" not in devices)
            logger.info(f"emulate: robotiq up on {self._devices['gripper']['port']}")
        if "myrio" in devices:
            self._start_myrio(trial, sync, follow_gripper)
            logger.info(f"emulate: myrio up on {self._devices['tactile']['port']}, replaying "
                        f"{trial}")
        self._started = [device for device in DEVICES if device in devices]
        for section, fields in self._devices.items():
            logger.debug(f"emulate: the station's {section}: "
                         + ", ".join(f"{name}={value}" for name, value in fields.items()))
        return self

    @property
    def devices(self) -> dict:
        """The HardwareStationConfig fields of the devices emulated: {section: {field: value}}."""
        return {section: dict(fields) for section, fields in self._devices.items()}

    def devices_line(self) -> str:
        """`devices` as one line for programs (read it back with `devices_from_line`)."""
        return DEVICES_LINE_PREFIX + json.dumps(self.devices, sort_keys=True)

    def hardware_config(self) -> HardwareStationConfig:
        """The config of a station on these devices, the arm on `lcm_url`, each emulated
        device's watchdog timeout EMULATED_WATCHDOG_TIMEOUT_S."""
        config = hardware_config_for({**self.devices, "arm": {"lcm_url": self.lcm_url}})
        for device in self._started:
            setattr(config.watchdog, f"{_WATCHDOG_DEVICE[device]}_timeout",
                    EMULATED_WATCHDOG_TIMEOUT_S)
        return config

    def write_hardware_config(self, path) -> None:
        """Writes `hardware_config()` atomically, under the first line WRITTEN_BY_EMULATE, making
        its folder if need be (as `plot --out` and `trial --html` do)."""
        pathlib.Path(path).parent.mkdir(parents=True, exist_ok=True)
        write_atomically(path, f"{WRITTEN_BY_EMULATE}\n"
                         + hardware_config_to_yaml(self.hardware_config()),
                         start=WRITTEN_BY_EMULATE.encode("utf-8"))

    def run_until_stopped(self) -> None:
        """Runs the arm's simulation in real time (or waits) until `stop`, reporting rejections."""
        if self._jaco is None:
            while not self.stop.wait(0.2):
                self.report_rejections()
            return
        from pydrake.systems.analysis import Simulator
        simulator = Simulator(self._jaco[1])
        simulator.set_target_realtime_rate(1.0)
        simulator.Initialize()
        context = simulator.get_context()
        while not self.stop.is_set():
            simulator.AdvanceTo(context.get_time() + 0.05)
            self.report_rejections()

    def report_rejections(self) -> None:
        """One line through `out` for each new kind of message a device skipped."""
        for boundary in self._boundaries:
            for rejection in boundary.new_rejections():
                self._out(boundary.describe(rejection))

    def message_counts(self) -> list[str]:
        """One line per inbound path: what it accepted and what it skipped, by reason."""
        return [f"{boundary.source}: {boundary.counters().summary()}"
                for boundary in self._boundaries]

    def close(self) -> None:
        self.stop.set()
        for closer in reversed(self._closers):
            closer()
        self._closers.clear()
        self.report_rejections()
        for line in self.message_counts():
            self._out(line)
        self._boundaries.clear()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _start_jaco(self, scenario):
        from pydrake.lcm import DrakeLcm

        from tegrasp_drake.emulators.controller_clock import command_boundary
        from tegrasp_drake.emulators.jaco_arm_emulator import MakeJacoArmEmulator
        from tegrasp_drake.hardware.jaco.jaco_lcm import (
            JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL)
        from tegrasp_drake.simulation.station import initial_arm_positions
        drake_lcm = DrakeLcm(self.lcm_url)
        boundary = command_boundary("jaco")
        diagram = MakeJacoArmEmulator(lcm=drake_lcm, command_boundary=boundary,
                                      initial_positions=initial_arm_positions(scenario.arm))
        self._boundaries.append(boundary)
        self._jaco = (drake_lcm, diagram, boundary)
        self._devices["arm"] = {"lcm_url": self.lcm_url}
        self._out(f"jaco: JACO2 simulation on {self.lcm_url}: executes {JACO_COMMAND_CHANNEL}, "
                  f"answers {JACO_STATUS_CHANNEL} at 100 Hz")

    def _start_robotiq(self, scenario, inject_fault: FaultInjection | None, publish: bool):
        from tegrasp_drake.emulators.robotiq_emulator import (
            RobotiqEmulator, RobotiqEmulatorConfig)
        from tegrasp_drake.emulators.gripper_link import (GRIPPER_STATE_CHANNEL,
                                                          publish_gripper_state)
        width = scenario.object.width_along_stroke()
        emulator = RobotiqEmulator(RobotiqEmulatorConfig(object_opening=width)).start()
        self._closers.append(emulator.stop)
        self._boundaries.append(emulator.request_boundary)
        self._robotiq = emulator
        self._devices["gripper"] = {"port": emulator.port}
        if publish:
            publish_gripper_state(self.lcm_url, emulator.model, self.stop)
        self._out(f"robotiq: Robotiq 2F-85 (Modbus RTU, slave 9, 115200 8N1) on "
                  f"{emulator.port}, object {width * 1000:.1f} mm wide between the fingers"
                  + (f"; its state on {GRIPPER_STATE_CHANNEL} of {self.lcm_url}" if publish
                     else ""))
        if inject_fault is not None:
            threading.Thread(target=self._inject_fault_after_activation,
                             args=(emulator, inject_fault), daemon=True).start()

    def _inject_fault_after_activation(self, emulator, fault: FaultInjection):
        while not self.stop.is_set():
            status = emulator.model.status(time.monotonic())
            if status[units.STATUS_STA] == units.ActivationStatus.ACTIVE:
                break
            self.stop.wait(0.01)
        if not self.stop.wait(fault.delay):
            emulator.inject_fault(fault.code)
            self._out(f"robotiq: injected fault 0x{fault.code:02X}")

    def _start_myrio(self, trial_path, sync: str, follow_gripper: bool):
        from tegrasp_drake.emulators.controller_clock import ControllerClock
        from tegrasp_drake.emulators.myrio_emulator import (
            MyRioEmulator, MyRioEmulatorConfig, gripper_command_changes, load_tactile_recording)
        recording = load_tactile_recording(trial_path)
        clock = ControllerClock() if sync in ("start", "follow") else None
        gripper_request = self._gripper_request() if follow_gripper else None
        emulator = MyRioEmulator(recording, MyRioEmulatorConfig(
            start_on_trigger=clock is not None, hold_at_end=True),
            trial_clock=clock if sync == "follow" else None,
            gripper_request=gripper_request).start()
        self._closers.append(emulator.stop)
        self._devices["tactile"] = {"port": emulator.port}
        if clock is not None:
            self._feed_controller_clock(clock)
            threading.Thread(target=self._start_trial_on_first_command,
                             args=(emulator, clock, sync == "follow"),
                             daemon=True).start()
        when = {"none": "now", "start": "from the arm's first command",
                "follow": "on the arm commands' clock (from its beginning for each run)"}[sync]
        self._out(f"myrio: tactile stream (1 kHz frames) on {emulator.port}, replaying "
                  f"{trial_path} ({recording.duration:.2f} s) {when}, then holding its last "
                  "values")
        if follow_gripper:
            changes = gripper_command_changes(recording.gripper_times,
                                              recording.gripper_requests)
            source = ("the Robotiq emulator here" if self._robotiq is not None
                      else f"EMULATED_ROBOTIQ on {self.lcm_url}")
            self._out("myrio: " + (
                "the trial holds no gripper command; nothing to follow" if not changes else
                "at the recording's gripper commands (" + ", ".join(
                    f"{'open' if c.after < c.before else 'close'} after {c.hold_time:.2f} s"
                    for c in changes) + f") the replay waits for the gripper ({source}) "
                "to be commanded likewise"))

    def _gripper_request(self):
        """The emulated gripper's position request: from the model here, else EMULATED_ROBOTIQ."""
        from tegrasp_drake.emulators.gripper_link import follow_gripper_state, request_of_model
        if self._robotiq is not None:
            return request_of_model(self._robotiq.model)
        follower = follow_gripper_state(self.lcm_url, self.stop)
        self._boundaries.append(follower.boundary)
        return follower

    def _feed_controller_clock(self, clock):
        """Feeds `clock` the arm's commands: those the emulated arm takes when it runs here
        (its command boundary's listener: no second subscription on its DrakeLcm, see
        hardware/lcm_boundary.py), else from a thread listening on `lcm_url`."""
        if self._jaco is not None:
            self._jaco[2].add_listener(lambda command: clock.on_command(command.utime))
            return
        from tegrasp_drake.emulators.controller_clock import (
            command_boundary, follow_jaco_commands)
        boundary = command_boundary()
        follow_jaco_commands(self.lcm_url, clock, self.stop, boundary)
        self._boundaries.append(boundary)

    def _start_trial_on_first_command(self, emulator, clock, follow: bool):
        """Starts the replay at the arm's first command; following the arm commands' clock,
        says when a run's commands stop (the stream holds) and when the next run's begin
        (its replay starts from the beginning)."""
        while not clock.started.wait(0.2):
            if self.stop.is_set():
                return
        emulator.start_trial()
        run, idle = clock.run, False
        while follow and not self.stop.wait(0.2):
            if clock.run != run:
                run, idle = clock.run, False
                self._out("myrio: a new run's arm commands: replaying the trial from its "
                          "beginning")
            elif clock.idle() and not idle:
                idle = True
                self._out("myrio: the arm commands stopped: streaming on, holding the "
                          "replay's values until the next run's commands")
