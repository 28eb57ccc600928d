"""Scheduling of the real-time control loop, so that a busy host does not delay it:
`realtime_scheduling` raises the calling thread for a block, falling back from "fifo" to
"nice" to "normal"; emulators use `raise_scheduling`. Why: docs/hardware.md, "The real-time
loop on a busy host"."""

import contextlib
import os
from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.echo import shown

SCHEDULING_POLICIES = ("fifo", "nice", "normal")
NICE_LEVEL = -10  # about 10x a normal process's CPU share (CFS weights)
# Above the loop's 10 and its I/O threads: emulated devices have processors of their own.
EMULATOR_PRIORITY = 30


def _set_fifo(priority: int, pid: int = 0) -> None:
    os.sched_setscheduler(pid, os.SCHED_FIFO, os.sched_param(priority))


def raise_scheduling(policy: str = "fifo", priority: int = 10, pid: int = 0) -> str:
    """Raises the scheduling of the calling thread, or of process `pid` (its main thread, before
    it starts threads); returns what it got, in words."""
    if policy not in SCHEDULING_POLICIES:
        raise ValueError(f"scheduling policy {shown(policy)} is not one of "
                         f"{', '.join(SCHEDULING_POLICIES)}")
    got, refused = "normal scheduling", []
    if policy == "fifo":
        try:
            _set_fifo(priority, pid)
            return f"real-time scheduling (SCHED_FIFO, priority {priority})"
        except (PermissionError, OSError) as e:
            refused.append(f"SCHED_FIFO refused: {os_error_text(e)}")
            policy = "nice"
    if policy == "nice":
        try:
            os.setpriority(os.PRIO_PROCESS, pid, NICE_LEVEL)
            got = f"raised priority (nice {NICE_LEVEL})"
        except (PermissionError, OSError) as e:
            refused.append(f"nice {NICE_LEVEL} refused: {os_error_text(e)}")
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
