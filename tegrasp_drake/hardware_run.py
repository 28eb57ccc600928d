"""A grasp on the real devices (or their emulators) in real time, with a replayable log.

`run_on_hardware` builds the controller diagram around MakeHardwareStation exactly as
around the simulated station (grasp_diagram.py), waits for the devices, and runs the
Simulator at real-time rate 1 until the state machine is done or failed. On the way:
- every state transition is printed as it happens and published on TEGRASP_TRANSITION;
- every device fault is printed (which device, what, since when) and published on
  TEGRASP_FAULT; the station holds the arm still at once, and the run ends
  `AFTER_FAULT_S` later (the state machine should have gone to Failed);
- every message on the bus (the arm's KINOVA_JACO_*, the station's TEGRASP_TACTILE and
  TEGRASP_GRIPPER, the run's own) is written to an LCM log file, which lcm-logplayer
  plays back and `tegrasp replay` re-runs the event matcher on (run_log.py). The first
  message is TEGRASP_RUN_INFO: the scenario, the hardware config and the controller.
"""

import dataclasses
import json
import pathlib
import sys
import threading
import time

import lcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import EventStatus

from tegrasp_drake.drivers.device_log_messages import (
    FAULT_CHANNEL, RUN_INFO_CHANNEL, TRANSITION_CHANNEL, utime)
from tegrasp_drake.grasp_diagram import DEFAULT_CONTROLLER, build_grasp_diagram, is_finished
from tegrasp_drake.hardware_config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.hardware_station import MakeHardwareStation
from tegrasp_drake.lcmtypes import (lcmt_tegrasp_fault, lcmt_tegrasp_run_info,
                                    lcmt_tegrasp_transition)
from tegrasp_drake.scenario import scenario_to_yaml
from tegrasp_drake.trial_diagram import package_versions

AFTER_FAULT_S = 0.5      # [s] the run goes on this long after the first fault
# The device threads (tactile reader, Modbus client) need the GIL within a few
# milliseconds while the 1 kHz loop holds it most of the time: ask for it sooner than
# Python's default 5 ms.
THREAD_SWITCH_INTERVAL_S = 0.0005
REPORT_PERIOD_S = 0.002  # [s] of Context time between looks at transitions and faults


class BusLogWriter:
    """lcm-logger in a thread: every message on the bus at `url` goes to an LCM log file
    (event timestamps are wall-clock microseconds of reception, as lcm-logger writes
    them). It has its own LCM instance, as lcm-logger does: DrakeLcm's all-channel
    subscription drops messages when it is pumped in step with its own publications.
    A memq:// bus lives inside one LCM instance, so there `drake_lcm` is subscribed."""

    def __init__(self, url: str, path, *, drake_lcm=None):
        self.path = pathlib.Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._log = lcm.EventLog(str(self.path), "w", overwrite=True)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self.messages = 0
        self._thread = None
        if url.startswith("memq"):
            drake_lcm.SubscribeAllChannels(self._write)
            return
        self._bus = lcm.LCM(url)
        self._bus.subscribe(".*", self._write)
        self._thread = threading.Thread(target=self._run, name="bus log", daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.is_set():
            self._bus.handle_timeout(20)

    def _write(self, channel: str, data: bytes):
        with self._lock:
            if self._log is not None:
                self._log.write_event(int(time.time() * 1e6), channel, data)
                self.messages += 1

    def close(self, linger: float = 0.05):
        """Stops after `linger` [s] more of the bus (the last messages in flight)."""
        if self._thread is not None:
            self._stop.wait(linger)
            self._stop.set()
            self._thread.join(1.0)
        with self._lock:
            if self._log is not None:
                self._log.close()
                self._log = None


def fault_message(fault, now: float) -> lcmt_tegrasp_fault:
    message = lcmt_tegrasp_fault()
    message.utime = utime(now)
    message.device, message.kind, message.code = fault.device, fault.kind, int(fault.code)
    message.description = fault.description
    message.since_utime = utime(fault.since_sim_time)
    message.since_wall_utime = utime(fault.since_wall_time)
    return message


def transition_message(transition: dict) -> lcmt_tegrasp_transition:
    message = lcmt_tegrasp_transition()
    message.utime = utime(transition["t"])
    message.from_mode = str(transition["from"])
    message.to_mode = str(transition["to"])
    message.trigger = str(transition.get("trigger", ""))
    return message


def format_transition(transition: dict) -> str:
    trigger = f"  ({transition['trigger']})" if transition.get("trigger") else ""
    return f"[{transition['t']:8.3f} s] {transition['from']} -> {transition['to']}{trigger}"


def format_fault(fault, now: float) -> str:
    return f"[{now:8.3f} s] FAULT {fault}; the arm is held still"


class RunReporter:
    """A Simulator monitor: prints and publishes new transitions and faults, and ends the
    run when the state machine is done or failed, or AFTER_FAULT_S after a fault."""

    def __init__(self, *, diagram, station, grasp, drake_lcm, out=print):
        self._diagram = diagram
        self._station = station
        self._grasp = grasp
        self._lcm = drake_lcm
        self._out = out
        self._next_look = 0.0
        self.transitions = []
        self.faults = []
        self.first_fault_time = None

    def __call__(self, root_context) -> EventStatus:
        now = root_context.get_time()
        if now < self._next_look:
            return EventStatus.DidNothing()
        self._next_look = now + REPORT_PERIOD_S
        for transition in self._grasp.transition_log(root_context)[len(self.transitions):]:
            self.transitions.append(transition)
            self._out(format_transition(transition))
            self._lcm.Publish(TRANSITION_CHANNEL, transition_message(transition).encode())
        faults = self._station.GetOutputPort("fault").Eval(
            self._station.GetMyContextFromRoot(root_context))
        for fault in faults[len(self.faults):]:
            self.faults.append(fault)
            self.first_fault_time = self.first_fault_time or now
            self._out(format_fault(fault, now))
            self._lcm.Publish(FAULT_CHANNEL, fault_message(fault, now).encode())
        if is_finished(self.transitions):
            return EventStatus.ReachedTermination(self._diagram, "the grasp is finished")
        if self.first_fault_time is not None and now >= self.first_fault_time + AFTER_FAULT_S:
            return EventStatus.ReachedTermination(self._diagram, "stopped after a fault")
        return EventStatus.Succeeded()


@dataclasses.dataclass
class HardwareRunResult:
    transitions: list          # [{t, from, to, trigger}]
    faults: tuple              # DeviceFault
    sim_time: float            # [s] Context time at the end
    wall_time: float           # [s] from Initialize to the end
    log_path: pathlib.Path | None
    log_messages: int

    @property
    def realtime_rate(self) -> float:
        return self.sim_time / self.wall_time if self.wall_time > 0 else float("nan")


def run_info_message(scenario, config, controller: str, events_dir: str):
    message = lcmt_tegrasp_run_info()
    message.utime = int(time.time() * 1e6)
    message.scenario_yaml = scenario_to_yaml(scenario)
    message.hardware_yaml = hardware_config_to_yaml(config)
    message.controller = controller
    message.object_name = scenario.object.name
    message.events_dir = events_dir
    message.versions_json = json.dumps(package_versions(), sort_keys=True)
    return message


def run_on_hardware(scenario, *, config: HardwareStationConfig | None = None,
                    controller: str = DEFAULT_CONTROLLER, events=None, events_dir: str = "",
                    log_path=None, duration: float | None = None, drake_lcm=None,
                    out=print) -> HardwareRunResult:
    """Runs the grasp on the devices of `config` (default: the scenario's `station`, which
    must then be a HardwareStationConfig) in real time; see the module docstring.

    drake_lcm: a DrakeLcm to use instead of one on the config's URL."""
    config = config or scenario.station
    if not isinstance(config, HardwareStationConfig):
        raise ValueError("run_on_hardware needs a HardwareStationConfig (the scenario's "
                         f"station is {type(config).__name__})")
    switch_interval = sys.getswitchinterval()
    sys.setswitchinterval(THREAD_SWITCH_INTERVAL_S)
    try:
        return _run(scenario, config, controller, events, events_dir, log_path, duration,
                    drake_lcm, out)
    finally:
        sys.setswitchinterval(switch_interval)


def _run(scenario, config, controller, events, events_dir, log_path, duration, drake_lcm,
         out) -> HardwareRunResult:
    with MakeHardwareStation(config, lcm=drake_lcm) as station:
        parts, builder = build_grasp_diagram(scenario, station=station, controller=controller,
                                             events=events)
        diagram = builder.Build()
        writer = (BusLogWriter(station.lcm.get_lcm_url(), log_path, drake_lcm=station.lcm)
                  if log_path else None)
        try:
            station.lcm.Publish(RUN_INFO_CHANNEL, run_info_message(
                scenario, config, controller, events_dir).encode())
            out(f"waiting for the devices: arm on {station.lcm.get_lcm_url()}, gripper on "
                f"{config.gripper.port}, tactile on {config.tactile.port}")
            station.wait_until_ready()
            simulator = Simulator(diagram)
            simulator.set_target_realtime_rate(1.0)
            reporter = RunReporter(diagram=diagram, station=parts.station, grasp=parts.grasp,
                                   drake_lcm=station.lcm, out=out)
            simulator.set_monitor(reporter)
            simulator.Initialize()
            out("devices ready; running in real time")
            start = time.monotonic()
            simulator.AdvanceTo(duration if duration is not None else parts.duration)
            wall = time.monotonic() - start
        finally:
            if writer is not None:
                writer.close()
        context = simulator.get_context()
        return HardwareRunResult(
            transitions=list(reporter.transitions), faults=tuple(reporter.faults),
            sim_time=context.get_time(), wall_time=wall,
            log_path=writer.path if writer else None,
            log_messages=writer.messages if writer else 0)
