"""The emulated 2F-85's request framer (emulators/modbus_request_framer.py): addressing and
resynchronisation by the Modbus serial line rules."""

from pymodbus.framer.rtu import FramerRTU

from tegrasp_drake.emulators.modbus_request_framer import ModbusRequestFramer
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator, RobotiqEmulatorConfig
from tegrasp_drake.hardware.message_boundary import MessageBoundary

SLAVE = 9


def frame(body: bytes) -> bytes:
    return body + FramerRTU.compute_CRC(body).to_bytes(2, "big")


def status_read(address: int) -> bytes:
    return frame(bytes([address, 4, 0x07, 0xD0, 0, 3]))


def command_write(address: int) -> bytes:
    return frame(bytes([address, 16, 0x03, 0xE8, 0, 3, 6, 9, 0, 0, 255, 32, 46]))


def test_a_request_for_another_slave_is_framed_and_not_passed_on():
    framer = ModbusRequestFramer(MessageBoundary("robotiq"), address=SLAVE)
    assert framer.feed(status_read(10)) == []
    assert framer.feed(status_read(SLAVE)) == [status_read(SLAVE)]
    assert framer.other_addresses == 1


def test_a_broadcast_is_never_passed_on_to_be_answered():
    framer = ModbusRequestFramer(MessageBoundary("robotiq"), address=SLAVE)
    assert framer.feed(command_write(0) + status_read(SLAVE)) == [status_read(SLAVE)]
    anyone = ModbusRequestFramer(MessageBoundary("robotiq"))  # no address: still no broadcast
    assert anyone.feed(command_write(0)) == [] and anyone.other_addresses == 1


def test_the_emulated_gripper_frames_for_its_own_slave_address():
    emulator = RobotiqEmulator(RobotiqEmulatorConfig(device_id=SLAVE + 3))
    assert emulator._framer.address == SLAVE + 3


def test_the_request_after_a_burst_of_plausible_headers_is_answered_at_once():
    # 500 function-16 headers promising 123 registers (246 bytes) each, then one valid read:
    # the read is a whole request after them, so the promise is given up at once.
    header = command_write(SLAVE)[:4] + bytes([0, 123, 246])
    boundary = MessageBoundary("robotiq")
    framer = ModbusRequestFramer(boundary, address=SLAVE)
    received = [request for _ in range(500) for request in framer.feed(header)]
    assert received == []
    assert framer.feed(status_read(SLAVE)) == [status_read(SLAVE)]
    assert boundary.counters().rejected_total >= 1  # the dropped run, counted once


def test_a_write_arriving_byte_by_byte_still_arrives_whole_and_once():
    framer = ModbusRequestFramer(MessageBoundary("robotiq"), address=SLAVE)
    write = command_write(SLAVE)
    assert [r for byte in write for r in framer.feed(bytes([byte]))] == [write]
