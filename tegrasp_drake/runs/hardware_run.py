"""A grasp on the real devices (or their emulators) in real time, with a replayable log.

`run_on_hardware` builds the controller diagram around MakeHardwareStation as around the simulated
station (grasp_diagram.py), waits for the devices and runs the Simulator at real-time rate 1. It
prints and publishes each transition (TEGRASP_TRANSITION) and device fault (TEGRASP_FAULT: the
station holds the arm still, the state machine goes to Failed), prints each device's first malformed
message of a kind and counts them all, and ends END_MARGIN_S after Done, Failed or a fault, or at
the time limit. A udpm:// bus is logged whole (first TEGRASP_RUN_INFO: scenario, hardware config,
controller), which hardware_log_reader.py reads and `tegrasp replay` re-runs."""

import dataclasses
import json
import logging
import os
import pathlib
import signal
import subprocess
import tempfile
import time
from typing import Annotated
from collections.abc import Callable

import lcm
from pydrake.systems.framework import EventStatus
from pydrake.lcm import DrakeLcm

from tegrasp_drake.hardware.device_log_messages import (
    FAULT_CHANNEL, RUN_INFO_CHANNEL, TRANSITION_CHANNEL)
from tegrasp_drake.hardware.lcm_time import utime_from_time
from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram, MakeSimulator, is_finished
from tegrasp_drake.control.grasp_modes import Transition
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.hardware.realtime import realtime_scheduling
from tegrasp_drake.hardware.station import MakeHardwareStation
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.files import free_bytes, os_error_text
from tegrasp_drake.lcmtypes import (lcmt_tegrasp_fault, lcmt_tegrasp_run_info,
                                    lcmt_tegrasp_transition)
from tegrasp_drake.scenario.scenario import scenario_to_yaml, with_controller
from tegrasp_drake.scenario.trial_log_writer import package_versions
from tegrasp_drake.scenario.scenario import Scenario, rechecked
from tegrasp_drake.rig.ranges import HARDWARE_RUN_DURATION
from tegrasp_drake.rig.number_text import count_text
from tegrasp_drake.rig.api_boundary import SEARCHED_FOLDER, PathLike, public_api
from tegrasp_drake.runs.hardware_log_reader import count_lcm_log_events

END_MARGIN_S = 0.5  # [s] the run goes on this long after Done, Failed or a fault
LOGGER_SUBSCRIBE_S = 0.2  # [s] given to lcm-logger to subscribe once its file exists
REPORT_PERIOD_S = 0.005  # [s] of Context time between looks at transitions and faults
# [s] of Context time between lines of a device stream's notices (a myRIO restarting its
# sequence): one that keeps restarting, every RESTART_RUN = 8 frames at 108 Hz, would say 13
# lines a second; it says 4, each with its count.
NOTICE_PERIOD_S = 0.25
PROGRESS_PERIOD_S = 0.25  # [s] of Context time between calls of `progress`
LOG_CHECK_PERIOD_S = 0.1  # [s] of Context time between looks at the LCM log's health
# Free space [bytes] below which the log counts as stopped: ten seconds of the ~100 kB/s bus
# (1 kHz tactile frames, arm and gripper status), the margin to stop and write the result.
LOG_MIN_FREE_BYTES = 1_000_000

logger = logging.getLogger(__name__)


class BusLogWriter:
    """Records every message on the bus at `url` to an LCM log with lcm-logger in its own process
    (here, a Python all-channel subscriber slows the loop by a third, DrakeLcm's drops messages,
    and a callback on the Simulator's DrakeLcm is unsafe: hardware/lcm_boundary.py). A memq://
    bus cannot be heard from outside this process: nothing is recorded, `unrecorded` says so."""

    def __init__(self, url: str, path, *, start_timeout: float = 5.0):
        self.path = pathlib.Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._process = None
        self.unrecorded = None
        if url.startswith("memq"):
            self.unrecorded = (f"no LCM log: the bus {url} lives inside this process, where "
                               "lcm-logger cannot hear it (a udpm:// URL can be logged)")
            return
        self.path.unlink(missing_ok=True)
        # Its words go to a file, not the user's terminal (it says "Logger exiting" on every
        # stop); what it said is quoted when it fails.
        self._output = tempfile.TemporaryFile()
        self._process = subprocess.Popen(
            [str(pathlib.Path(lcm.LCM_BIN_DIR) / "lcm-logger"), "--quiet", "--force",
             f"--lcm-url={url}", str(self.path)],
            stdin=subprocess.DEVNULL, stdout=self._output, stderr=subprocess.STDOUT,
            preexec_fn=_stopped_when_this_thread_ends())
        deadline = time.monotonic() + start_timeout
        while not self.path.exists():
            if self._process.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"lcm-logger did not start on {url} (exit code "
                                   f"{self._process.poll()}){self._said()}")
            time.sleep(0.01)
        time.sleep(LOGGER_SUBSCRIBE_S)

    def _said(self) -> str:
        """": what lcm-logger said" on one line (its goodbye left out), or ""."""
        from tegrasp_drake.rig.files import one_line
        from tegrasp_drake.rig.echo import shorten
        if self._output.closed:
            return ""
        self._output.seek(0)
        lines = [line.strip() for line in self._output.read(4096).decode(
            "utf-8", "replace").splitlines() if line.strip() and line.strip() != "Logger exiting"]
        return f": {shorten(one_line('; '.join(lines)), 200)}" if lines else ""

    def problem(self) -> str | None:
        """Why the log stopped (None while it records, or records nothing): lcm-logger exited, or
        its disk has less than LOG_MIN_FREE_BYTES left."""
        if self._process is None:
            return None
        if not self.path.exists():  # lcm-logger would go on writing a file nobody can open
            return f"the LCM log {self.path} stopped: it was removed during the run"
        if self._process.poll() is not None:
            return (f"the LCM log {self.path} stopped: lcm-logger exited with code "
                    f"{self._process.returncode}{self._said()}")
        try:
            free = free_bytes(self.path.parent)
        except OSError as e:
            return f"the LCM log {self.path} stopped: {os_error_text(e)}"
        if free < LOG_MIN_FREE_BYTES:
            return (f"the LCM log {self.path} stopped: the disk holding it has less than "
                    f"{LOG_MIN_FREE_BYTES // 10**6} MB free")
        return None

    def close(self, linger: float = 0.1) -> int:
        """Stops after `linger` [s] more of the bus; returns the messages recorded."""
        if self._process is not None and self._process.poll() is None:
            time.sleep(linger)
            self._process.send_signal(signal.SIGINT)
            try:
                self._process.wait(5.0)
            except subprocess.TimeoutExpired:
                self._process.kill()
                self._process.wait()
        if self._process is not None:
            self._output.close()
        return self.messages

    @property
    def messages(self) -> int:
        """The messages the log holds whole; 0 when nothing was recorded or the file was
        removed (problem() says so). Counted by count_lcm_log_events, which bounds each event
        by the bytes read; lcm.EventLog allocates an event's declared length first and
        crashes the process on a corrupt one (a data length of 2^31-1)."""
        if self._process is None:
            return 0
        try:
            return count_lcm_log_events(self.path)
        except FileNotFoundError:
            return 0


PR_SET_PDEATHSIG = 1  # prctl(2): the signal a child gets when the thread that forked it ends


def _stopped_when_this_thread_ends():
    """A Popen preexec_fn giving the child SIGINT (lcm-logger's way to stop, its log closed
    whole) when the thread that starts it ends, also when this process is killed past its
    handlers (SIGKILL): a logger left running would go on writing a killed run's log. The
    writer is made and closed by one call in one thread (_run). None without prctl(2) (not
    Linux): the logger then outlives a killed run."""
    import ctypes
    import sys
    if not sys.platform.startswith("linux"):
        return None
    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl  # looked up before the fork
    except (OSError, AttributeError):
        return None
    parent = os.getpid()

    def in_the_child():
        prctl(PR_SET_PDEATHSIG, int(signal.SIGINT))
        if os.getppid() != parent:  # the parent ended before prctl took effect
            os._exit(1)
    return in_the_child


def fault_message(fault, now: float) -> lcmt_tegrasp_fault:
    message = lcmt_tegrasp_fault()
    message.utime = utime_from_time(now)
    message.device, message.kind, message.code = fault.device, fault.kind, int(fault.code)
    message.description = fault.description
    message.since_utime = utime_from_time(fault.since_sim_time)
    message.since_wall_utime = utime_from_time(fault.since_wall_time)
    return message


def transition_message(transition: dict) -> lcmt_tegrasp_transition:
    message = lcmt_tegrasp_transition()
    message.utime = utime_from_time(transition["t"])
    message.from_mode = str(transition["from"])
    message.to_mode = str(transition["to"])
    message.trigger = str(transition.get("trigger", ""))
    message.reason = str(transition.get("reason", ""))
    return message


def format_transition(transition: Transition) -> str:
    why = "; ".join(part for part in (transition.decided_by, transition.reason) if part)
    trigger = f"  ({why})" if why else ""
    return (f"[{transition.t:8.3f} s] {transition.from_mode.label} -> "
            f"{transition.to_mode.label}{trigger}")


def format_counters(counters: dict) -> str:
    gripper, tactile = counters["gripper"], counters["tactile"]
    reasons = ", ".join(f"{reason} {count}" for reason, count
                        in sorted(gripper.rejected.items()))
    arm = counters.get("arm")
    return (f"gripper: {gripper.reads} status reads, {gripper.writes} writes, "
            f"{gripper.errors} failed transactions"
            + (f" ({reasons}; last: {gripper.last_error})" if gripper.errors else "")
            + f"; tactile: {tactile.decoder.summary()}, {tactile.queue_overflows} overflowed"
            + (f"; arm: {arm.summary('status messages')}" if arm is not None else ""))


def format_fault(fault, now: float) -> str:
    return f"[{now:8.3f} s] FAULT {fault}; the arm is held still"


class RunReporter:
    """A Simulator monitor: prints and publishes new transitions and faults, and ends the
    run END_MARGIN_S after the state machine is done or failed, or after a fault."""

    def __init__(self, *, diagram, station, grasp, drake_lcm, out=print, progress=None,
                 end_time: float = float("inf"), log_problem=None, boundaries=()):
        self._diagram = diagram
        self._station = station
        self._grasp = grasp
        self._lcm = drake_lcm
        self._out = out
        self._progress = progress
        self._end_time = end_time  # [s] the run's end unless the grasp ends first
        self._next_look = 0.0
        self._next_progress = 0.0
        self.transitions = []  # Transition
        self.faults = []
        self.ended_at = None
        self._boundaries = tuple(boundaries)  # MessageBoundary: said once per new reason
        self._log_problem = log_problem  # () -> str | None: the log has stopped recording
        self._next_log_check = 0.0
        self._next_notices = 0.0
        self.log_fault = None  # why the run stopped when its log stopped recording

    def __call__(self, root_context) -> EventStatus:
        now = root_context.get_time()
        if now < self._next_look:
            return EventStatus.DidNothing()
        self._next_look = now + REPORT_PERIOD_S
        for transition in self._grasp.transitions(root_context)[len(self.transitions):]:
            self.transitions.append(transition)
            self._out(format_transition(transition))
            message = transition_message(transition.as_dict())  # the JSON form's fields
            self._lcm.Publish(TRANSITION_CHANNEL, message.encode())
        faults = self._station.GetOutputPort(ports.FAULT).Eval(
            self._station.GetMyContextFromRoot(root_context))
        for fault in faults[len(self.faults):]:
            self.faults.append(fault)
            self.ended_at = self.ended_at or now
            self._out(format_fault(fault, now))
            self._lcm.Publish(FAULT_CHANNEL, fault_message(fault, now).encode())
        for boundary in self._boundaries:
            for rejection in boundary.new_rejections():
                self._out(f"[{now:8.3f} s] {boundary.describe(rejection)}")
        if now >= self._next_notices:
            self._next_notices = now + NOTICE_PERIOD_S
            for boundary in self._boundaries:
                for notice in boundary.new_notices():
                    self._out(f"[{now:8.3f} s] {notice}")
        if self.log_fault is not None:  # said once; Initialize and AdvanceTo both look
            return EventStatus.ReachedTermination(self._diagram, self.log_fault)
        if self._log_problem is not None and now >= self._next_log_check:
            self._next_log_check = now + LOG_CHECK_PERIOD_S
            problem = self._log_problem()
            if problem is not None:
                # A run nobody records is a run nobody can check: stop at once, as a fault.
                self.log_fault = problem
                # The problem itself is the run's closing error (result.log_fault), said once.
                self._out(f"{now:7.3f} s  FAULT  the LCM log stopped recording; the run stops")
                return EventStatus.ReachedTermination(self._diagram, problem)
        if is_finished(self.transitions) and self.ended_at is None:
            self.ended_at = now
        if self._progress is not None and now >= self._next_progress:
            self._next_progress = now + PROGRESS_PERIOD_S
            end = self._end_time if self.ended_at is None else min(
                self._end_time, self.ended_at + END_MARGIN_S)
            self._progress(now, end)
        if self.ended_at is not None and now >= self.ended_at + END_MARGIN_S:
            return EventStatus.ReachedTermination(self._diagram, "the grasp has ended")
        return EventStatus.Succeeded()


# The entries every run's result.json holds (HardwareRunResult.as_dict), by which a file is
# known as one (commands/hardware.earlier_run_file_problem).
HARDWARE_RESULT_KEYS = ("transitions", "faults", "log", "device_counters")


@dataclasses.dataclass
class HardwareRunResult:
    transitions: list          # [{t, from, to, trigger, ...}]: Transition.as_dict()
    faults: tuple              # DeviceFault
    sim_time: float            # [s] Context time at the end
    wall_time: float           # [s] from Initialize to the end
    log_path: pathlib.Path | None
    log_messages: int
    device_counters: dict      # {"gripper": RobotiqModbusCounters, "tactile": ...Counters,
                               #  "arm": MessageCounters}
    log_fault: str | None = None  # why the run stopped early: its LCM log stopped recording

    @property
    def realtime_rate(self) -> float:
        return self.sim_time / self.wall_time if self.wall_time > 0 else float("nan")

    def as_dict(self) -> dict:
        """The JSON form (result.json beside the log): times in s, faults and counters as dicts."""
        return {"transitions": self.transitions,
                "faults": [dataclasses.asdict(fault) for fault in self.faults],
                "sim_time_s": self.sim_time, "wall_time_s": self.wall_time,
                "realtime_rate": self.realtime_rate if self.wall_time > 0 else None,
                "log": None if self.log_path is None else str(self.log_path),
                "log_messages": self.log_messages, "log_fault": self.log_fault,
                "device_counters": {device: dataclasses.asdict(counters) for device, counters
                                    in self.device_counters.items()}}


def run_info_message(scenario, config, controller: str, events_dir: str):
    """The TEGRASP_RUN_INFO message of a run."""
    message = lcmt_tegrasp_run_info()
    message.utime = int(time.time() * 1e6)
    message.scenario_yaml = scenario_to_yaml(scenario)
    message.hardware_yaml = hardware_config_to_yaml(config)
    message.controller = controller
    message.object_name = scenario.object.name
    message.events_dir = events_dir
    message.versions_json = json.dumps(package_versions(), sort_keys=True)
    return message


@public_api
def run_on_hardware(scenario: Scenario, *, config: HardwareStationConfig | None = None,
                    controller: str | None = None, events: dict | None = None,
                    corrective_events: dict | None = None,
                    events_dir: Annotated[PathLike | None, SEARCHED_FOLDER] = None,
                    log_path: PathLike | None = None,
                    duration: Annotated[float | None, HARDWARE_RUN_DURATION] = None,
                    drake_lcm: DrakeLcm | None = None, out: Callable = print,
                    progress: Callable | None = None) -> HardwareRunResult:
    """Runs the grasp on the devices of `config` (default: the scenario's `station`, then a
    HardwareStationConfig) in real time (module docstring). controller, events,
    corrective_events: default the scenario's and the package's; events_dir: the folder
    `events` were read from, recorded in the run's log for its replay (None: none given, the
    replay searches the default folders); drake_lcm: instead of one on the config's URL; out:
    prints a line; progress: progress(t, end) [s of Context time]."""
    scenario = rechecked(scenario, "run_on_hardware: scenario")  # changed after loading?
    config = config or scenario.station
    if not isinstance(config, HardwareStationConfig):
        raise ValueError("run_on_hardware needs a HardwareStationConfig (the scenario's "
                         f"station is {type(config).__name__})")
    if controller is not None:
        scenario = with_controller(scenario, controller)
    with realtime_scheduling(config.scheduling, config.realtime_priority) as scheduling:
        out(f"control loop: {scheduling}")
        events_folder = "" if events_dir is None else os.fspath(events_dir)  # the log's field
        return _run(scenario, config, events, corrective_events, events_folder,
                    log_path, duration, drake_lcm, out, progress)


# [s] listened to the arm's command channel before a run: 20 commands of another controller
# at the JACO2 driver's 100 Hz (jaco_lcm.py), yet short beside a device's ready_timeout.
OTHER_CONTROLLER_LISTEN_S = 0.2


def arm_commands_heard(url: str, listen_s: float = OTHER_CONTROLLER_LISTEN_S) -> int:
    """How many KINOVA_JACO_COMMAND messages another process publishes on the bus at `url` in
    `listen_s` [s] (0 for a memq:// bus, which no other process can reach): before a run
    starts, any is another controller commanding the arm."""
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL
    if url.startswith("memq"):
        return 0
    heard = []
    bus = lcm.LCM(url)
    subscription = bus.subscribe(JACO_COMMAND_CHANNEL, lambda channel, data: heard.append(1))
    try:
        deadline = time.monotonic() + listen_s
        while (left := deadline - time.monotonic()) > 0:
            bus.handle_timeout(max(1, int(left * 1000)))
    finally:
        bus.unsubscribe(subscription)
    return len(heard)


def _run(scenario, config, events, corrective_events, events_dir, log_path,
         duration, drake_lcm, out, progress) -> HardwareRunResult:
    url = drake_lcm.get_lcm_url() if drake_lcm is not None else config.arm.lcm_url
    heard = arm_commands_heard(url)
    if heard:
        from tegrasp_drake.hardware.station import HardwareNotReadyError
        raise HardwareNotReadyError(
            f"arm: another controller is commanding it ({heard} KINOVA_JACO_COMMAND messages "
            f"on {url} in {OTHER_CONTROLLER_LISTEN_S:g} s before this run); end it first")
    with MakeHardwareStation(config, lcm=drake_lcm) as station:
        parts = MakeGraspDiagram(scenario, station=station, events=events,
                                 corrective_events=corrective_events, log=False)
        diagram = parts.diagram
        writer = (BusLogWriter(station.lcm.get_lcm_url(), log_path)
                  if log_path else None)
        if writer is not None and writer.unrecorded:
            out(writer.unrecorded)
        elif writer is not None:
            logger.info(f"hardware: lcm-logger records the bus "
                        f"{station.lcm.get_lcm_url()} to {writer.path}")
        try:
            station.lcm.Publish(RUN_INFO_CHANNEL, run_info_message(
                scenario, config, scenario.controller.name, events_dir).encode())
            out(f"waiting for the devices: arm on {station.lcm.get_lcm_url()}, gripper on "
                f"{config.gripper.port}, tactile on {config.tactile.port}")
            station.wait_until_ready()
            simulator = MakeSimulator(diagram, scenario, realtime=True)
            end_time = duration if duration is not None else parts.time_limit
            reporter = RunReporter(diagram=diagram, station=parts.station,
                                   grasp=parts.controller,
                                   drake_lcm=station.lcm, out=out, progress=progress,
                                   end_time=end_time,
                                   log_problem=writer.problem if writer else None,
                                   boundaries=station.message_boundaries().values())
            simulator.set_monitor(reporter)
            simulator.Initialize()
            out("devices ready; running in real time")
            logger.info(f"hardware: the run started (controller "
                        f"{scenario.controller.name}, object {scenario.object.name}; it ends "
                        f"at {end_time:g} s at the latest)")
            start = time.monotonic()
            simulator.AdvanceTo(end_time)
            wall = time.monotonic() - start
            logger.info(f"hardware: the run ended at {simulator.get_context().get_time():.2f} "
                        f"s after {wall:.2f} s; {len(reporter.transitions)} transitions, "
                        f"{count_text(len(reporter.faults), 'fault')}")
            counters = {"gripper": station.gripper_client.counters(),
                        "tactile": station.tactile_reader.counters(),
                        "arm": station.arm_status_boundary.counters()}
            out(format_counters(counters))
        finally:
            messages = writer.close() if writer is not None else 0
            if writer is not None and writer.unrecorded is None:
                logger.info(f"hardware: lcm-logger stopped; {messages} messages in "
                            f"{writer.path}")
        context = simulator.get_context()
        return HardwareRunResult(
            transitions=[transition.as_dict() for transition in reporter.transitions],
            faults=tuple(reporter.faults),
            sim_time=context.get_time(), wall_time=wall,
            log_path=writer.path if writer else None,
            log_messages=messages, device_counters=counters, log_fault=reporter.log_fault)
