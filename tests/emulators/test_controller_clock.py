"""ControllerClock: the controller's time from its commands' utime, extrapolated."""

import pytest

from tegrasp_drake.emulators.controller_clock import ControllerClock


class FakeTime:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def test_clock_is_zero_until_the_first_command_and_counts_from_it():
    wall = FakeTime()
    clock = ControllerClock(now=wall)
    assert clock() == 0.0 and not clock.started.is_set()
    clock.on_command(5_000_000)
    assert clock.started.is_set() and clock() == 0.0
    wall.now += 0.004
    assert clock() == pytest.approx(0.004)


def test_clock_extrapolates_at_the_controllers_rate_for_one_period_at_most():
    wall = FakeTime()
    clock = ControllerClock(now=wall)
    for k in range(100):  # the controller runs at half real time
        wall.now += 0.020
        clock.on_command(k * 10_000)
    wall.now += 0.010
    assert clock() == pytest.approx(0.99 + 0.005, abs=1e-3)
    wall.now += 1.0
    assert clock() == pytest.approx(0.99 + 0.010)


def test_clock_never_runs_backwards():
    wall = FakeTime()
    clock = ControllerClock(now=wall)
    clock.on_command(0)
    wall.now += 0.010
    ahead = clock()
    clock.on_command(5_000)  # the controller had only got to 5 ms
    assert clock() == ahead
