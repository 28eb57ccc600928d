"""The Robotiq Modbus RTU client and driver system against the emulator on a pty."""

import time

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator

from tegrasp_drake.robotiq import units
from tegrasp_drake.hardware.device_fault import DEVICE_FAULT, DRIVER_ERROR, describe_faults
from tegrasp_drake.hardware.robotiq.robotiq_driver import RobotiqDriver
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator, RobotiqEmulatorConfig
from tegrasp_drake.hardware.robotiq.modbus_client import (
    RobotiqActivationError, RobotiqModbusClient, RobotiqModbusConfig)

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

ACTIVATION = 0.05  # [s], the emulated activation (the real one takes seconds)


def wait_for(predicate, timeout=3.0):
    """Polls `predicate` every 10 ms; returns its last value."""
    deadline = time.monotonic() + timeout
    while not (value := predicate()) and time.monotonic() < deadline:
        time.sleep(0.01)
    return value


@pytest.fixture
def emulator():
    with RobotiqEmulator(RobotiqEmulatorConfig(activation_duration=ACTIVATION)) as emulator:
        yield emulator


@pytest.fixture
def client(emulator):
    with RobotiqModbusClient(RobotiqModbusConfig(port=emulator.port,
                                                 activation_timeout=2.0)) as client:
        client.wait_until_active(3.0)
        yield client


def status_of(client):
    return client.latest_status().status


def test_activation_sequence_completes(emulator):
    with RobotiqModbusClient(RobotiqModbusConfig(port=emulator.port)) as client:
        assert not client.is_active
        sample = client.wait_until_active(3.0)
        assert sample.status[units.STATUS_ACT] == 1
        assert sample.status[units.STATUS_STA] == units.ActivationStatus.ACTIVE
        assert client.counters().writes == 2  # zeros, then rACT = 1
        assert client.counters().errors == 0


def test_status_read_with_function_3_follows_the_gripper(emulator):
    # Some manual versions and firmware read the status as holding registers (function 3).
    with RobotiqModbusClient(RobotiqModbusConfig(port=emulator.port, read_function=3,
                                                 activation_timeout=2.0)) as client:
        client.wait_until_active(3.0)
        client.set_command([128, 255, 100])
        assert wait_for(lambda: status_of(client)[units.STATUS_OBJ]
                        == units.ObjectStatus.AT_REQUESTED_POSITION)
        assert status_of(client)[units.STATUS_PO] == 128
        assert client.counters().errors == 0


def test_activation_timeout_names_the_port():
    config = RobotiqEmulatorConfig(activation_duration=60.0)
    with RobotiqEmulator(config) as emulator, RobotiqModbusClient(RobotiqModbusConfig(
            port=emulator.port, activation_timeout=0.2)) as client:
        with pytest.raises(RobotiqActivationError, match=emulator.port):
            client.wait_until_active(3.0)
        assert "gSTA = 1" in client.error


def test_a_gripper_that_never_activates_is_said_with_its_status_and_what_to_check():
    """It answers Modbus, but its status never reaches activation complete: the error says
    what arrived (the gSTA values, the last status's fields) and what to check, in one line."""
    config = RobotiqEmulatorConfig(activation_duration=60.0)
    with RobotiqEmulator(config) as emulator, RobotiqModbusClient(RobotiqModbusConfig(
            port=emulator.port, activation_timeout=0.2)) as client:
        with pytest.raises(RobotiqActivationError) as refused:
            client.wait_until_active(30.0)
    message = str(refused.value)
    assert "\n" not in message and "Modbus Error" not in message, message
    assert "status read(s) answered, gSTA = 1 (activating);" in message, message
    assert "the last status gACT 1, gGTO 0, gSTA 1, gOBJ 0, gFLT 0x00" in message, message
    assert "Check the gripper's power" in message and "activation request" in message, message
    assert "gripper.device_id (9)" in message, message


def test_a_gripper_that_does_not_answer_is_said_without_pymodbus_words():
    """Another unit id than the 2F-85's: no answer, said in the package's words (pymodbus's
    hold a line break and its own advice), with what to check."""
    with RobotiqEmulator(RobotiqEmulatorConfig()) as emulator, RobotiqModbusClient(
            RobotiqModbusConfig(port=emulator.port, device_id=3,
                                activation_timeout=0.2)) as client:
        with pytest.raises(RobotiqActivationError) as refused:
            client.wait_until_active(30.0)
    message = str(refused.value)
    assert "\n" not in message and "Modbus Error" not in message, message
    assert "no answer: nothing came back to a function 16 request" in message, message
    assert "Check the gripper's power" in message and "gripper.device_id (3" in message


def test_no_device_on_the_port_is_an_activation_error():
    with RobotiqModbusClient(RobotiqModbusConfig(port="/dev/does-not-exist")) as client:
        with pytest.raises(RobotiqActivationError, match="/dev/does-not-exist"):
            client.wait_until_active(3.0)


def test_position_command_reaches_the_requested_position(client):
    client.set_command([128, 255, 100])
    assert wait_for(lambda: status_of(client)[units.STATUS_OBJ]
                    == units.ObjectStatus.AT_REQUESTED_POSITION)
    status = status_of(client)
    assert status[units.STATUS_PO] == 128 and status[units.STATUS_PR] == 128
    assert status[units.STATUS_GTO] == 1


def test_closing_on_an_object_reports_contact(emulator, client):
    emulator.set_object_opening(0.04)
    client.set_command([255, 255, 150])
    assert wait_for(lambda: status_of(client)[units.STATUS_OBJ]
                    == units.ObjectStatus.STOPPED_ON_CONTACT_CLOSING)
    status = status_of(client)
    assert status[units.STATUS_PO] == round(units.position_from_opening(0.04))
    assert status[units.STATUS_CU] == 0  # the screw holds (the manual's finished grasp)


def test_status_reads_stay_within_200_hz(client):
    before = client.counters().reads
    time.sleep(0.3)
    assert 0 < client.counters().reads - before <= 0.3 * 200 + 1


def _driver_simulator(client):
    driver = RobotiqDriver(client, stale_timeout=0.1)
    simulator = Simulator(driver)
    simulator.set_target_realtime_rate(1.0)
    return driver, simulator


def test_driver_command_port_moves_the_gripper(client):
    driver, simulator = _driver_simulator(client)
    context = simulator.get_mutable_context()
    driver.GetInputPort("command").FixValue(context, [200.0, 255.0, 50.0])
    simulator.AdvanceTo(1.0)
    status = driver.GetOutputPort("status").Eval(context)
    assert status[units.STATUS_PO] == 200
    assert status[units.STATUS_OBJ] == units.ObjectStatus.AT_REQUESTED_POSITION
    assert driver.GetOutputPort("stale").Eval(context)[0] == 0
    assert driver.GetOutputPort("fault").Eval(context) == ()


def test_driver_reports_a_gripper_fault_by_name(emulator, client):
    driver, simulator = _driver_simulator(client)
    context = simulator.get_mutable_context()
    driver.GetInputPort("command").FixValue(context, [3.0, 255.0, 50.0])
    simulator.AdvanceTo(0.05)
    emulator.inject_fault(0x0E)
    simulator.AdvanceTo(0.2)
    faults = driver.GetOutputPort("fault").Eval(context)
    assert len(faults) == 1
    assert (faults[0].device, faults[0].kind, faults[0].code) == ("gripper", DEVICE_FAULT, 0x0E)
    assert faults[0].description == "overcurrent triggered"
    assert "overcurrent triggered" in describe_faults(faults)
    assert 0.05 <= faults[0].since_sim_time <= 0.2


def test_driver_marks_status_stale_when_the_gripper_stops_talking(emulator, client):
    driver, simulator = _driver_simulator(client)
    context = simulator.get_mutable_context()
    simulator.AdvanceTo(0.05)
    assert driver.GetOutputPort("stale").Eval(context)[0] == 0
    emulator.disconnect()
    simulator.AdvanceTo(0.1)
    last_arrival = driver.GetOutputPort("time_measured").Eval(context)[0]
    simulator.AdvanceTo(0.35)
    assert driver.GetOutputPort("stale").Eval(context)[0] == 1
    assert driver.GetOutputPort("time_measured").Eval(context)[0] == last_arrival
    assert client.counters().errors > 0
    emulator.reconnect()
    simulator.AdvanceTo(0.8)
    assert driver.GetOutputPort("stale").Eval(context)[0] == 0
    assert driver.GetOutputPort("time_measured").Eval(context)[0] > last_arrival


def test_driver_outputs_are_stale_before_the_first_status():
    client = RobotiqModbusClient(RobotiqModbusConfig(port="/dev/null-never-started"))
    driver = RobotiqDriver(client)
    simulator = Simulator(driver)
    simulator.AdvanceTo(0.01)
    context = simulator.get_context()
    assert driver.GetOutputPort("stale").Eval(context)[0] == 1
    np.testing.assert_array_equal(driver.GetOutputPort("status").Eval(context), np.zeros(8))


def test_driver_reports_an_activation_failure_naming_the_port():
    with RobotiqModbusClient(RobotiqModbusConfig(port="/dev/does-not-exist")) as client:
        assert wait_for(lambda: client.error)
        driver = RobotiqDriver(client)
        simulator = Simulator(driver)
        simulator.AdvanceTo(0.01)
        (fault,) = driver.GetOutputPort("fault").Eval(simulator.get_context())
        assert fault.kind == DRIVER_ERROR and "/dev/does-not-exist" in fault.description
