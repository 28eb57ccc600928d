"""The controller's clock as its arm commands carry it (each command's `utime` is Context
time), to pace a replaying emulator (MyRioEmulator's `trial_clock`) with a controller slower
than real time: the newest command's time since the first, extrapolated at the recent rate
for at most one command period. A run's commands that stop for IDLE_AFTER leave the clock
idle (the run ended or was killed); a command after that stamped no later than the last one
(the next run's Context time starts again) begins a new run, counted in `run`."""

import threading
import time

from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_LCM_PERIOD, check_jaco_command)
from tegrasp_drake.hardware.lcm_boundary import checked_handler
from tegrasp_drake.hardware.message_boundary import MessageBoundary

RATE_SMOOTHING = 10  # [commands] rate averaging, 0.1 s at 100 Hz: smooth, yet quick
# [s] the arm commands' silence after which a run has ended: 50 command periods, far longer
# than a live controller's gaps (one 10 ms period, a few on a loaded host), far shorter than
# the start-up of the next `tegrasp hardware` (seconds: imports, the wait for the devices).
IDLE_AFTER = 0.5


class ControllerClock:
    """Seconds of controller time since its first command (0 before); thread-safe."""

    def __init__(self, *, max_extrapolation: float = JACO_LCM_PERIOD,
                 idle_after: float = IDLE_AFTER, now=time.monotonic):
        self._max_extrapolation = max_extrapolation
        self._idle_after = idle_after
        self._now = now
        self._lock = threading.Lock()
        self._first_utime = None
        self._utime = None
        self._received = 0.0
        self._rate = 1.0  # controller seconds per wall second
        self._last_value = 0.0
        self._run = 0
        self.started = threading.Event()

    def on_command(self, utime: int):
        """A command stamped `utime` [us] arrived."""
        with self._lock:
            now = self._now()
            if (self._utime is not None and utime <= self._utime
                    and now - self._received >= self._idle_after):
                self._first_utime = self._utime = None  # the next run's first command
                self._rate, self._last_value = 1.0, 0.0
                self._run += 1
            if self._first_utime is None:
                self._first_utime = utime
            if self._utime is not None and utime > self._utime and now > self._received:
                rate = (utime - self._utime) * 1e-6 / (now - self._received)
                self._rate += (min(rate, 2.0) - self._rate) / RATE_SMOOTHING
            if self._utime is None or utime > self._utime:
                self._utime, self._received = utime, now
        self.started.set()

    @property
    def run(self) -> int:
        """How many times a new run's commands began after the first run's (0 in the first)."""
        with self._lock:
            return self._run

    def idle(self) -> bool:
        """Whether no command arrived for `idle_after` [s] (or none yet): the run stopped."""
        with self._lock:
            return self._utime is None or self._now() - self._received >= self._idle_after

    def __call__(self) -> float:
        with self._lock:
            if self._utime is None:
                return 0.0
            since = min(max(self._now() - self._received, 0.0) * self._rate,
                        self._max_extrapolation)
            value = (self._utime - self._first_utime) * 1e-6 + since
            self._last_value = max(self._last_value, value)  # never backwards
            return self._last_value


def command_boundary(device: str = "myrio") -> MessageBoundary:
    """The boundary a clock's commands cross (check_jaco_command); rejected ones are ignored."""
    return MessageBoundary(f"{device}: {JACO_COMMAND_CHANNEL}", check_jaco_command)


def feed_clock(clock: ControllerClock, boundary: MessageBoundary):
    """A callback for an `lcm` package subscription feeding `clock` checked commands."""
    return checked_handler(boundary, lambda command: clock.on_command(command.utime))


def follow_jaco_commands(lcm_url: str, clock: ControllerClock, stop: threading.Event,
                         boundary: MessageBoundary | None = None):
    """A thread feeding `clock` from KINOVA_JACO_COMMAND on `lcm_url` until `stop`, the commands
    crossing `boundary` (command_boundary() by default)."""
    import lcm

    bus = lcm.LCM(lcm_url)
    bus.subscribe(JACO_COMMAND_CHANNEL, feed_clock(clock, boundary or command_boundary()))

    def run():
        while not stop.is_set():
            bus.handle_timeout(20)
    thread = threading.Thread(target=run, name="controller clock", daemon=True)
    thread.start()
    return thread
