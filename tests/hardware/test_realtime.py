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


def test_an_emulator_process_runs_at_the_emulators_priority_from_its_start():
    """Its start-up (importing Drake, building the arm's simulation) must not be starved
    on a busy host: the parent raises the child at once. (The child here is not given
    --scheduling, so what it runs at is the parent's doing.)"""
    from tegrasp_drake.emulators.emulator_process import EmulatorProcess
    with realtime.realtime_scheduling("fifo", 10) as got:
        if "refused" in got:
            pytest.skip(f"this host refuses SCHED_FIFO: {got}")
    process = EmulatorProcess("robotiq", "--scenario-name", "box", wait=False,
                              scheduling="fifo")
    try:
        process.wait_until_ready(60.0)
        assert os.sched_getscheduler(process.pid) == os.SCHED_FIFO
        assert os.sched_getparam(process.pid).sched_priority == realtime.EMULATOR_PRIORITY
    finally:
        process.stop()
