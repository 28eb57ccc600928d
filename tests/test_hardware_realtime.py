"""Scheduling of the real-time loop (hardware/realtime.py): raised for the run, restored
after it, inherited by the device threads, and a fallback that says what the OS refused."""

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


def test_threads_started_inside_inherit_the_loops_scheduling():
    seen = []
    with realtime.realtime_scheduling("fifo", 10) as got:
        thread = threading.Thread(target=lambda: seen.append(
            (os.sched_getscheduler(0), os.sched_getparam(0).sched_priority)))
        thread.start()
        thread.join()
    if "refused" in got:
        pytest.skip(f"this host refuses SCHED_FIFO: {got}")
    assert seen == [(os.SCHED_FIFO, 10)]


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
