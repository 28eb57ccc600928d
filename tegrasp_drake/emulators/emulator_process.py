"""`tegrasp emulate ...` in a child process, as real devices are outside the controller's
process: start it, read where it listens (its "devices: {JSON}" line), stop or kill it."""

import os
import select
import signal
import subprocess
import sys
import time

from tegrasp_drake.emulators.launcher import devices_from_line, hardware_config_for
from tegrasp_drake.hardware.realtime import EMULATOR_PRIORITY, raise_scheduling

READY_LINE = "ready"


class EmulatorProcessError(RuntimeError):
    """The emulator did not come up; the message holds what it printed."""


class EmulatorProcess:
    """`python -m tegrasp_drake emulate DEVICE ARGS...`; use as a context manager. `devices`:
    the HardwareStationConfig fields of its devices once ready; `output`: all it printed so far."""

    def __init__(self, device: str, *args: str, wait: bool = True, timeout: float = 30.0,
                 env=None, scheduling: str = "normal"):
        self.device = device
        self.devices = {}
        self.output = []
        self._process = subprocess.Popen(
            [sys.executable, "-m", "tegrasp_drake", "emulate", device, *args],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1,
            env=env or dict(os.environ))
        if scheduling != "normal":
            # Covers the child's start-up too; its own --scheduling applies after.
            raise_scheduling(scheduling, EMULATOR_PRIORITY, pid=self._process.pid)
        os.set_blocking(self._process.stdout.fileno(), False)
        self._buffer = ""
        if wait:
            self.wait_until_ready(timeout)

    def wait_until_ready(self, timeout: float = 30.0) -> "EmulatorProcess":
        """Blocks until it printed "ready"; EmulatorProcessError (and stopped) if not."""
        deadline = time.monotonic() + timeout
        while READY_LINE not in self.output:
            if self._process.poll() is not None or time.monotonic() > deadline:
                self.stop(timeout=0.0)
                raise EmulatorProcessError(f"`tegrasp emulate {self.device}` did not get "
                                           "ready:\n" + "\n".join(self.output))
            self.read_output(0.1)
        return self

    @property
    def pid(self) -> int:
        return self._process.pid

    def read_output(self, wait: float = 0.0) -> list[str]:
        """Collects the lines printed since the last call (waits up to `wait` [s])."""
        stream = self._process.stdout
        if stream.closed:
            return []
        readable, _, _ = select.select([stream], [], [], wait)
        if readable:
            self._buffer += stream.read() or ""
        *lines, self._buffer = self._buffer.split("\n")
        for line in lines:
            self.output.append(line)
            devices = devices_from_line(line)
            if devices is not None:
                self.devices.update(devices)
        return lines

    def stop(self, timeout: float = 5.0) -> int | None:
        """SIGTERM, as Ctrl-C would; returns the exit code."""
        if self._process.poll() is None:
            self._process.send_signal(signal.SIGTERM)
            try:
                self._process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.kill()
        self.read_output()
        self._process.stdout.close()
        return self._process.returncode

    def kill(self):
        """SIGKILL: the device dies without a word (a pulled cable, a crashed device)."""
        if self._process.poll() is None:
            self._process.kill()
            self._process.wait()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


class EmulatedDevices:
    """The three devices, each in its own process on `lcm_url`; `config` points a hardware
    station at them. A context manager. `scheduling` defaults to "fifo": real devices have
    processors of their own, so on a busy host the controller under test should be delayed."""

    def __init__(self, *, lcm_url: str, trial, scenario_args=("--scenario-name", "box"),
                 robotiq_args=(), myrio_sync: str = "follow", timeout: float = 30.0,
                 scheduling: str = "fifo"):
        self.jaco = self.robotiq = self.myrio = None
        common = ("--scheduling", scheduling)
        try:
            self.jaco = EmulatorProcess("jaco", *scenario_args, "--lcm-url", lcm_url,
                                        *common, wait=False, scheduling=scheduling)
            self.robotiq = EmulatorProcess("robotiq", *scenario_args, *robotiq_args,
                                           "--lcm-url", lcm_url, *common, wait=False,
                                           scheduling=scheduling)
            self.myrio = EmulatorProcess("myrio", "--trial", str(trial), "--sync", myrio_sync,
                                         "--follow-gripper", "--lcm-url", lcm_url, *common,
                                         wait=False, scheduling=scheduling)
            for process in self.processes:
                process.wait_until_ready(timeout)
        except BaseException:
            self.stop()
            raise
        self.config = hardware_config_for(
            {**self.jaco.devices, **self.robotiq.devices, **self.myrio.devices})

    @property
    def processes(self) -> list:
        return [p for p in (self.jaco, self.robotiq, self.myrio) if p is not None]

    def stop(self):
        for process in self.processes:
            process.stop()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
