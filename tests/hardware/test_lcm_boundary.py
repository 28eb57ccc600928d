"""LCM messages cross the boundary inside the diagram only: no Python callback on a DrakeLcm
that a Simulator pumps (pydrake builds the callback's bytes without the GIL, which
Simulator.AdvanceTo has released), a wait before the run that counts nothing, and a
boundary's listeners that see the checked messages."""

import ast
import pathlib
import time

import pytest
from drake import lcmt_jaco_status
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem

from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_STATUS_CHANNEL, check_jaco_status, make_jaco_status)
from tegrasp_drake.hardware.lcm_boundary import (
    CheckedLcmSubscriber, WaitTally, wait_for_checked_message)
from tegrasp_drake.hardware.message_boundary import MessageBoundary

PACKAGE = pathlib.Path(__file__).resolve().parents[2] / "tegrasp_drake"
DRAKE_LCM_SUBSCRIPTIONS = {"Subscribe", "SubscribeMultichannel", "SubscribeAllChannels"}
ZERO = [0.0] * 6


def test_the_package_subscribes_no_python_callback_on_a_drake_lcm():
    calls = []
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and node.func.attr in DRAKE_LCM_SUBSCRIPTIONS):
                calls.append(f"{path.relative_to(PACKAGE)}:{node.lineno}")
    assert calls == []


POSE = [0.0, 2.8, 0.9, 0.0, 0.0, 0.0]  # [rad] inside the JACO2's joint ranges


def _status(utime) -> bytes:
    return make_jaco_status(utime, POSE, ZERO, ZERO).encode()


def _subscribed_diagram():
    lcm = DrakeLcm("memq://")
    boundary = MessageBoundary("arm: KINOVA_JACO_STATUS", check_jaco_status)
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    subscriber = builder.AddSystem(CheckedLcmSubscriber(
        channel=JACO_STATUS_CHANNEL, lcm_type=lcmt_jaco_status, boundary=boundary, lcm=lcm))
    return lcm, boundary, subscriber, builder.Build()


def test_the_wait_finds_a_good_status_counts_nothing_and_the_run_counts_it_once():
    lcm, boundary, subscriber, diagram = _subscribed_diagram()
    lcm.Publish(JACO_STATUS_CHANNEL, b"\x00" * 3)
    lcm.Publish(JACO_STATUS_CHANNEL, _status(1000))
    assert wait_for_checked_message(lcm, subscriber, time.monotonic() + 5.0)
    assert boundary.counters().accepted == 0 and boundary.counters().rejected == {}
    simulator = Simulator(diagram)
    simulator.Initialize()
    context = subscriber.GetMyContextFromRoot(simulator.get_context())
    assert subscriber.get_output_port().Eval(context).utime == 1000
    assert boundary.counters().accepted == 1


def test_a_bus_of_malformed_statuses_is_not_ready_and_counts_nothing():
    lcm, boundary, subscriber, _ = _subscribed_diagram()
    start = time.monotonic()
    for _ in range(5):
        lcm.Publish(JACO_STATUS_CHANNEL, _status(1000)[:30])
    assert not wait_for_checked_message(lcm, subscriber, start + 0.3)
    assert boundary.counters().accepted == 0 and boundary.counters().rejected == {}


def test_a_wait_given_a_tally_counts_what_came_and_why_it_was_refused():
    lcm, boundary, subscriber, _ = _subscribed_diagram()
    lcm.Publish(JACO_STATUS_CHANNEL, b"\x00" * 3)
    lcm.Publish(JACO_STATUS_CHANNEL, _status(1000)[:30])
    tally = WaitTally()
    assert not wait_for_checked_message(lcm, subscriber, time.monotonic() + 2.0, tally)
    assert tally.arrived == 2 and tally.accepted == 0 and tally.rejected_total >= 1
    assert tally.first_rejection.startswith(("too short", "truncated")), tally
    assert boundary.counters().rejected == {}  # the run's counts start at the run


def test_each_message_the_running_diagram_takes_is_counted_and_heard_once():
    lcm, boundary, subscriber, diagram = _subscribed_diagram()
    heard = []
    boundary.add_listener(lambda status: heard.append(status.utime))
    simulator = Simulator(diagram)
    simulator.Initialize()
    for k in range(1, 11):
        lcm.Publish(JACO_STATUS_CHANNEL, _status(1000 * k) if k % 2 else b"garbage")
        simulator.AdvanceTo(0.01 * k)
    assert heard == [1000, 3000, 5000, 7000, 9000]
    assert boundary.counters().accepted == 5
    assert sum(boundary.counters().rejected.values()) == 5


@pytest.mark.parametrize("message", [b"", b"\x01" * 7])
def test_a_listener_never_sees_a_rejected_message(message):
    boundary = MessageBoundary("arm", check_jaco_status)
    heard = []
    boundary.add_listener(heard.append)
    assert boundary.accept(message) is None
    assert heard == []
