"""`tegrasp emulate ...` in a child process, as the real devices are outside the controller's
process: start it, read where it listens, stop or kill it (tests, benchmarks, scripts).

Where the child's devices listen comes as data: the launcher's "devices: {JSON}" line,
decoded by `launcher.devices_from_line`; the rest of its output is for people.
"""

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
    """`python -m tegrasp_drake emulate DEVICE ARGS...`; use as a context manager.

    `devices` holds the HardwareStationConfig fields of the devices it emulates (e.g.
    {"gripper": {"port": "/dev/pts/3"}}) once it is ready; `output` is all it printed so
    far (read_output() collects more)."""

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
            # The child's own --scheduling applies once it has started; this covers its
            # start-up too (where the OS refuses, the child says so in its output).
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
    """The three devices, each emulated in its own process (`tegrasp emulate jaco`,
    `robotiq` and `myrio --sync <myrio_sync> --follow-gripper`, all on `lcm_url`), started
    together; `config` points a hardware station at them. Use as a context manager; `myrio`,
    `robotiq` and `jaco` are the EmulatorProcess of each (e.g. to kill one).

    scheduling: the emulators' `--scheduling`. Real devices have processors of their own;
    on a shared host the default, "fifo", keeps their stand-ins on time when the host is
    busy, so that what a busy host delays is the controller under test."""

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
