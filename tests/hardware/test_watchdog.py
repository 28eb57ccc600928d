"""The device watchdog: which device went silent, since when, and the stop signal."""

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from tegrasp_drake.hardware.device_fault import SILENT
from tegrasp_drake.emulators.myrio_emulator import (
    MyRioEmulator, MyRioEmulatorConfig, TactileRecording)
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver
from tegrasp_drake.hardware.watchdog import DeviceActivity, DeviceWatchdog, next_activity

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling


def step(activity, value, t, timeout=0.05, grace=1.0):
    return next_activity(activity, value, device="arm", timeout=timeout, startup_grace=grace,
                         sim_time=t, wall_time=1000.0 + t)


def test_changing_values_keep_the_device_alive():
    activity = DeviceActivity()
    for k in range(1, 100):
        activity = step(activity, 0.01 * k, 0.01 * k)
    assert activity.fault is None and activity.since_sim_time == pytest.approx(0.99)


def test_a_value_that_stops_changing_trips_after_the_timeout():
    activity = step(DeviceActivity(), 5.0, 0.10)
    assert step(activity, 5.0, 0.15).fault is None
    fault = step(activity, 5.0, 0.16).fault
    assert (fault.device, fault.kind) == ("arm", SILENT)
    assert fault.since_sim_time == pytest.approx(0.10)
    assert fault.since_wall_time == pytest.approx(1000.10)
    assert "no new data for more than 50 ms" in str(fault)


def test_a_trip_latches_even_if_the_device_comes_back():
    tripped = step(step(DeviceActivity(), 5.0, 0.1), 5.0, 0.2)
    assert step(tripped, 6.0, 0.21).fault is tripped.fault


def test_a_device_never_heard_from_gets_the_startup_grace():
    activity = DeviceActivity(None, 0.0, 1000.0)
    assert step(activity, 0.0, 1.0).fault is None
    fault = step(activity, 0.0, 1.06).fault
    assert "never heard from" in fault.description and fault.since_sim_time == 0.0


class Clock(LeafSystem):
    """A test device whose time_measured advances until `silent_after` [s]."""

    def __init__(self, silent_after):
        super().__init__()
        self.DeclareVectorOutputPort(
            "time_measured", 1,
            lambda context, out: out.SetAtIndex(0, 100.0 + min(
                np.floor(context.get_time() / 0.01) * 0.01, silent_after)))


def test_watchdog_names_the_silent_device_and_raises_stop():
    builder = DiagramBuilder()
    watchdog = builder.AddSystem(DeviceWatchdog({"arm": 0.05, "gripper": 0.1}))
    for device, silent_after in (("arm", 1e9), ("gripper", 0.2)):
        clock = builder.AddSystem(Clock(silent_after))
        builder.Connect(clock.get_output_port(),
                        watchdog.GetInputPort(f"{device}_time_measured"))
    simulator = Simulator(builder.Build())
    context = watchdog.GetMyContextFromRoot(simulator.get_context())
    simulator.AdvanceTo(0.29)
    assert watchdog.GetOutputPort("fault").Eval(context) == ()
    assert watchdog.GetOutputPort("stop").Eval(context)[0] == 0
    simulator.AdvanceTo(0.32)
    (fault,) = watchdog.GetOutputPort("fault").Eval(context)
    assert fault.device == "gripper" and fault.kind == SILENT
    assert fault.since_sim_time == pytest.approx(0.2)
    assert watchdog.GetOutputPort("stop").Eval(context)[0] == 1


def test_watchdog_trips_when_the_tactile_stream_stops():
    """Through the real serial path in real time (at the deployment's scheduling, see the
    module's mark; a 50 ms timeout at normal scheduling tripped beside a CPU hog while the
    stream was still talking)."""
    timeout = 0.1
    times = np.arange(0.0, 3.0, 0.001)
    trial = TactileRecording(times, np.zeros((len(times), 12)), np.zeros((len(times), 12)),
                         times, np.zeros(len(times)), np.zeros(len(times)))
    with MyRioEmulator(trial, MyRioEmulatorConfig(lead_in=0.0)) as emulator, \
            TactileSerialReader(emulator.port) as reader:
        builder = DiagramBuilder()
        receiver = builder.AddSystem(TactileSerialReceiver(reader))
        watchdog = builder.AddSystem(DeviceWatchdog({"tactile": timeout}))
        builder.Connect(receiver.GetOutputPort("time_measured"),
                        watchdog.GetInputPort("tactile_time_measured"))
        simulator = Simulator(builder.Build())
        simulator.set_target_realtime_rate(1.0)
        context = watchdog.GetMyContextFromRoot(simulator.get_context())
        simulator.AdvanceTo(0.3)
        assert watchdog.GetOutputPort("fault").Eval(context) == ()
        emulator.stop_talking()
        stopped_at = simulator.get_context().get_time()
        simulator.AdvanceTo(stopped_at + 3 * timeout)
        (fault,) = watchdog.GetOutputPort("fault").Eval(context)
        assert fault.device == "tactile"
        assert stopped_at - 0.02 <= fault.since_sim_time <= stopped_at + 0.02
        assert "tactile: silent" in str(fault)
