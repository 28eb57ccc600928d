"""Scheduling of the real-time loop (hardware/realtime.py): raised for the run, restored
after it, device threads above the loop, and a fallback that says what the OS refused."""

import os
import threading

import pytest

from tegrasp_drake.hardware import realtime


def test_the_scheduling_is_restored_after_the_block():
    before = (os.sched_getscheduler(0), os.sched_getparam(0).sched_priority,
              os.getpriority(os.PRIO_PROCESS, 0))
    with realtime.realtime_scheduling("fifo", 10) as got:
        if "SCHED_FIFO, priority 10" in got:
            assert os.sched_getscheduler(0) == os.SCHED_FIFO
        else:
            assert "SCHED_FIFO refused" in got
    assert (os.sched_getscheduler(0), os.sched_getparam(0).sched_priority,
            os.getpriority(os.PRIO_PROCESS, 0)) == before


def test_device_threads_run_above_the_loop_when_it_is_real_time():
    seen = []

    def device_thread():
        realtime.raise_io_thread_priority()
        seen.append((os.sched_getscheduler(0), os.sched_getparam(0).sched_priority))

    with realtime.realtime_scheduling("fifo", 10) as got:
        thread = threading.Thread(target=device_thread)
        thread.start()
        thread.join()
    if "SCHED_FIFO" not in got or "refused" in got:
        pytest.skip(f"this host refuses SCHED_FIFO: {got}")
    assert seen == [(os.SCHED_FIFO, 10 + realtime.IO_PRIORITY_BOOST)]


def test_a_refused_real_time_class_falls_back_and_says_so(monkeypatch):
    def refuse(*args):
        raise PermissionError(1, "Operation not permitted")
    monkeypatch.setattr(realtime, "_set_fifo", refuse)
    with realtime.realtime_scheduling("fifo", 10) as got:
        assert got.startswith(("raised priority (nice -10)", "normal scheduling"))
        assert "SCHED_FIFO refused: Operation not permitted" in got


def test_an_unknown_policy_is_refused():
    with pytest.raises(ValueError, match="'deadline' is not one of fifo, nice, normal"):
        realtime.raise_scheduling("deadline")
