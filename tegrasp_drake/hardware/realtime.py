"""Scheduling of the real-time control loop, so that a busy host does not delay it.

The hardware loop (hardware_run.py) runs 1 kHz Python updates at real-time rate 1. On a
host whose cores are busy with other work, the kernel's fair scheduler gives the loop only
its share of a core, the loop falls behind real time and the devices' data arrives late
(measured: with three busy processes on two cores the loop ran at 0.6 of real time and the
watchdog tripped). A real-time scheduling class puts the loop ahead of every normal process.

`realtime_scheduling(policy, priority)` is a context manager that raises the calling
thread's scheduling for its duration and restores it after; threads started inside it (the
device reader threads) inherit it. Policies, each falling back to the next when the OS
refuses (no CAP_SYS_NICE, a container without it):
- "fifo": SCHED_FIFO at `priority` (1..99). The kernel's real-time throttling
  (/proc/sys/kernel/sched_rt_runtime_us, 95 % by default) keeps a runaway loop from
  locking up a core.
- "nice": SCHED_OTHER at nice NICE_LEVEL, about 10x the CPU share of a normal process.
- "normal": unchanged.
It yields a one-line description of what it got, for the run's output.

Device I/O threads (the tactile reader, the Modbus client) inherit the loop's priority.
Not higher: they share Python's interpreter lock with the loop, and a higher-priority
thread that wakes every millisecond (pymodbus polls for a reply every 1 ms) takes the lock
from the loop each time; measured beside four CPU hogs, the loop ran at 0.76-0.84 of real
time with the device threads 5 levels above it and at 0.90-0.95 with them at its level.
Emulators of the devices (`tegrasp emulate --scheduling fifo`) use `raise_scheduling` for
their whole process, at EMULATOR_PRIORITY, above the loop's (commands/emulate.py); an
EmulatorProcess raises its child's at once, so that its start-up (importing Drake,
building the arm's simulation) is not starved on a busy host either.
"""

import contextlib
import os

SCHEDULING_POLICIES = ("fifo", "nice", "normal")
NICE_LEVEL = -10
# Emulated devices: above the control loop (hardware/config.py realtime_priority 10) and its
# I/O threads, as they stand in for devices that have processors of their own.
EMULATOR_PRIORITY = 30


def _set_fifo(priority: int, pid: int = 0) -> None:
    os.sched_setscheduler(pid, os.SCHED_FIFO, os.sched_param(priority))


def raise_scheduling(policy: str = "fifo", priority: int = 10, pid: int = 0) -> str:
    """Raises the scheduling of the calling thread, or of process `pid` (its main thread:
    set it before it starts threads, which inherit it); returns what it got, in words
    (module docstring)."""
    if policy not in SCHEDULING_POLICIES:
        raise ValueError(f"scheduling policy {policy!r} is not one of "
                         f"{', '.join(SCHEDULING_POLICIES)}")
    got, refused = "normal scheduling", []
    if policy == "fifo":
        try:
            _set_fifo(priority, pid)
            return f"real-time scheduling (SCHED_FIFO, priority {priority})"
        except (PermissionError, OSError) as e:
            refused.append(f"SCHED_FIFO refused: {e.strerror or e}")
            policy = "nice"
    if policy == "nice":
        try:
            os.setpriority(os.PRIO_PROCESS, pid, NICE_LEVEL)
            got = f"raised priority (nice {NICE_LEVEL})"
        except (PermissionError, OSError) as e:
            refused.append(f"nice {NICE_LEVEL} refused: {e.strerror or e}")
    return got + (f" ({'; '.join(refused)})" if refused else "")


@contextlib.contextmanager
def realtime_scheduling(policy: str = "fifo", priority: int = 10):
    """Raises the calling thread's scheduling for the block; yields what it got, in words."""
    old_policy, old_param = os.sched_getscheduler(0), os.sched_getparam(0)
    old_nice = os.getpriority(os.PRIO_PROCESS, 0)
    description = raise_scheduling(policy, priority)
    try:
        yield description
    finally:
        with contextlib.suppress(OSError):
            os.sched_setscheduler(0, old_policy, old_param)
        with contextlib.suppress(OSError):
            os.setpriority(os.PRIO_PROCESS, 0, old_nice)
