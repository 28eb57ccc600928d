"""MakeHardwareStation against in-process emulators: the simulated station's ports, the
fault latch and the device_fault text the state machine reads."""

import numpy as np
import pytest
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator

from tegrasp_drake.hardware.device_fault import DEVICE_FAULT, SILENT, DeviceFault
from tegrasp_drake.hardware.fault_latch import FaultLatch, latched_faults
from tegrasp_drake.emulators.myrio_emulator import MyRioEmulator, TactileRecording
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.hardware.station import HardwareNotReadyError, MakeHardwareStation
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario import MakeSimulatedStation
from tegrasp_drake.rig import station_interface as ports

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

def quiet_trial():
    t = np.arange(0.0, 0.2, 1e-3)
    return TactileRecording(t, np.zeros((len(t), 12)), np.zeros((len(t), 12)), t,
                        np.zeros((len(t), 3)), np.zeros(len(t)))


@pytest.fixture
def station():
    with RobotiqEmulator() as gripper, MyRioEmulator(quiet_trial()) as myrio:
        config = HardwareStationConfig()
        config.gripper.port, config.tactile.port = gripper.port, myrio.port
        with MakeHardwareStation(config, lcm=DrakeLcm("memq://")) as station:
            yield station


def test_hardware_station_has_the_simulated_station_ports(station):
    simulated = MakeSimulatedStation(LoadScenario(name="box"))
    for name, size in ports.CONTROLLER_INPUTS.items():
        assert station.GetInputPort(name).size() == simulated.GetInputPort(name).size() == size
    for name, size in ports.CONTROLLER_OUTPUTS.items():
        assert station.GetOutputPort(name).size() == simulated.GetOutputPort(name).size() == size
    assert station.num_input_ports() == len(ports.CONTROLLER_INPUTS)
    for name in (ports.FAULT, ports.DEVICE_FAULT, ports.STOP, ports.ARM_COMMANDED_STATE,
                 ports.ARM_TIME_MEASURED, ports.GRIPPER_TIME_MEASURED,
                 ports.TACTILE_TIME_MEASURED, ports.TACTILE_STALE, ports.TACTILE_ZEROING,
                 ports.TACTILE_PAD_ACCELERATION_SAMPLES):
        assert station.HasOutputPort(name)


def test_no_arm_on_the_bus_is_named_when_waiting_for_the_devices(station):
    with pytest.raises(HardwareNotReadyError, match="arm: no lcmt_jaco_status on "
                       "KINOVA_JACO_STATUS at memq://"):
        station.wait_until_ready(timeout=0.2)


def test_an_arm_whose_every_status_is_refused_is_said_with_the_count_and_the_reason(station):
    """Statuses that come but are all refused are not "no status": the error says how many
    arrived, were read and refused, why (the first in words) and what to check."""
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_STATUS_CHANNEL, make_jaco_status
    bad = make_jaco_status(1000, [0.0, 2.8, 0.9, 0.0, 0.0, float("nan")], [0.0] * 6,
                           [0.0] * 6).encode()
    for _ in range(5):  # queued on memq://, handled by the wait's first pump
        station.lcm.Publish(JACO_STATUS_CHANNEL, bad)
    with pytest.raises(HardwareNotReadyError) as refused:
        station.wait_until_ready(timeout=2.0)
    message = str(refused.value)
    assert "\n" not in message and "no lcmt_jaco_status" not in message, message
    assert message.startswith("arm: 5 messages on KINOVA_JACO_STATUS at memq://"), message
    assert "none a status the JACO2 can send" in message and "read and refused (not finite" in message
    assert "the first: not finite: " in message and "check that the Kinova driver" in message


def test_a_missing_tactile_port_is_named():
    with RobotiqEmulator() as gripper:
        config = HardwareStationConfig()
        config.gripper.port, config.tactile.port = gripper.port, "/dev/no-such-myrio"
        with pytest.raises(HardwareNotReadyError, match="field 'tactile.port' "
                           "'/dev/no-such-myrio': No such file or directory: plug in"):
            MakeHardwareStation(config, lcm=DrakeLcm("memq://"))


SILENT_ARM = DeviceFault("arm", SILENT, "no new data for more than 50 ms", since_sim_time=1.0)
GRIPPER_OVERCURRENT = DeviceFault("gripper", DEVICE_FAULT, "overcurrent triggered", 0x0E,
                                  since_sim_time=2.0)


def test_faults_are_kept_once_seen_in_order():
    faults = latched_faults((), [SILENT_ARM])
    faults = latched_faults(faults, [GRIPPER_OVERCURRENT, SILENT_ARM])
    assert latched_faults(faults, []) == (SILENT_ARM, GRIPPER_OVERCURRENT)


def test_fault_latch_stops_and_names_every_fault():
    latch = FaultLatch(["watchdog", "gripper"])
    simulator = Simulator(latch)
    context = simulator.get_mutable_context()
    latch.GetInputPort("watchdog_fault").FixValue(context, ())
    latch.GetInputPort("gripper_fault").FixValue(context, ())
    simulator.AdvanceTo(0.002)
    assert latch.GetOutputPort("stop").Eval(context)[0] == 0
    assert latch.GetOutputPort("message").Eval(context) == ""
    latch.GetInputPort("gripper_fault").FixValue(context, (GRIPPER_OVERCURRENT,))
    simulator.AdvanceTo(0.004)
    latch.GetInputPort("gripper_fault").FixValue(context, ())  # the code cleared: kept
    simulator.AdvanceTo(0.006)
    assert latch.GetOutputPort("stop").Eval(context)[0] == 1
    assert latch.GetOutputPort("fault").Eval(context) == (GRIPPER_OVERCURRENT,)
    assert latch.GetOutputPort("message").Eval(context).startswith(
        "gripper: device (code 0x0E): overcurrent triggered; since t = 2.000 s")
