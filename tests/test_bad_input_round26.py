"""Bad inputs the fourteenth hostile pass found, one test per rule."""

import types

import pytest
from pymodbus.pdu.register_message import ReadInputRegistersResponse

from tegrasp_drake.hardware.robotiq import modbus_client
from tegrasp_drake.hardware.robotiq.modbus_client import RobotiqModbusClient, RobotiqModbusConfig
from tegrasp_drake.robotiq import registers, units


def _words(gACT=1, gGTO=1, gSTA=3, gOBJ=3, gFLT=0, gPR=100, gPO=100, gCU=0):
    status = [0.0] * units.STATUS_SIZE
    for name, value in dict(gACT=gACT, gGTO=gGTO, gSTA=gSTA, gOBJ=gOBJ, gFLT=gFLT, gPR=gPR,
                            gPO=gPO, gCU=gCU).items():
        status[units.STATUS_NAMES.index(name)] = value
    return registers.status_registers(status)


def _with_byte(words, index, value):
    """`words` with status byte `index` (0..5, first byte high) set to `value`."""
    out = list(words)
    shift = 8 if index % 2 == 0 else 0
    out[index // 2] = (out[index // 2] & ~(0xFF << shift)) | (value << shift)
    return out


class _Gripper:
    """A bus answering each status read with the next of `answers` (register lists), on a
    clock the test moves: a read takes 2 ms."""

    def __init__(self, monkeypatch):
        self.now = 0.0
        self.answers = []
        monkeypatch.setattr(modbus_client, "time",
                            types.SimpleNamespace(monotonic=lambda: self.now))
        self.bus = types.SimpleNamespace(read_input_registers=self._answer)

    def _answer(self, *args, **kwargs):
        self.now += 0.002
        return ReadInputRegistersResponse(registers=self.answers.pop(0))

    def read(self, client, words, after=0.003):
        """The sample `client` reads `after` seconds from now when the gripper sends `words`."""
        self.now += after
        self.answers.append(words)
        return client._read(self.bus)


def _client():
    return RobotiqModbusClient(RobotiqModbusConfig(port="/dev/null"))


# Rule: a 2F-85 status the manual's register map makes impossible (a reserved bit set, gSTA 2
# "not used", activation in progress or complete while gACT says reset) is counted under its
# reason and skipped; the client keeps the last good status.
@pytest.mark.parametrize("words, named", [
    (_words(gACT=0, gGTO=0, gSTA=3), "gSTA = 3 with gACT = 0"),
    (_words(gACT=0, gGTO=0, gSTA=1), "gSTA = 1 with gACT = 0"),
    (_words(gSTA=2), "gSTA = 2"),
    (_with_byte(_words(), 0, 0x02 | 0x01 | 0x08 | 0x30 | 0xC0), "reserved"),
    (_with_byte(_words(), 0, 0x04 | 0x01 | 0x08 | 0x30 | 0xC0), "reserved"),
    (_with_byte(_words(), 1, 0x80), "reserved"),
])
def test_a_status_the_register_map_makes_impossible_is_counted_and_skipped(
        monkeypatch, words, named):
    gripper, client = _Gripper(monkeypatch), _client()
    good = gripper.read(client, _words())
    assert good is not None
    assert gripper.read(client, words) is None
    assert client.latest_status() is good
    counters = client.counters()
    assert counters.rejected == {modbus_client.IMPOSSIBLE_STATUS: 1}
    assert named in counters.last_error


# The states a 2F-85 does report are taken: reset, reset with a go-to request (gGTO echoes
# rGTO, fault 0x07), activation in progress, active with each gOBJ, a major fault.
@pytest.mark.parametrize("words", [
    _words(gACT=0, gGTO=0, gSTA=0, gOBJ=0),
    _words(gACT=0, gGTO=1, gSTA=0, gOBJ=0, gFLT=units.FAULT_NOT_ACTIVATED),
    _words(gACT=1, gGTO=0, gSTA=1, gOBJ=0),
    _words(gACT=1, gGTO=0, gSTA=0, gOBJ=0, gFLT=0x0B),
    *[_words(gOBJ=obj) for obj in range(4)],
    _with_byte(_words(), 2, 0xA0),  # the high nibble is kFLT, the controller's fault
])
def test_a_status_the_register_map_allows_is_taken(monkeypatch, words):
    gripper, client = _Gripper(monkeypatch), _client()
    assert gripper.read(client, words) is not None
    assert client.counters().rejected == {}


# Rule: a gPO step between two accepted statuses farther than the 2F-85's fingers can move
# at their top speed in between is counted and skipped (the fingers crossing the whole
# stroke between two 5 ms reads); the client keeps the last good status.
def test_a_position_jump_faster_than_the_fingers_is_counted_and_skipped(monkeypatch):
    gripper, client = _Gripper(monkeypatch), _client()
    good = gripper.read(client, _words(gPO=3))
    for position in (255, 230, 255):
        assert gripper.read(client, _words(gPO=position)) is None
        assert client.latest_status() is good
    counters = client.counters()
    assert counters.rejected == {modbus_client.POSITION_JUMP: 3}
    assert "gPO" in counters.last_error and "150 mm/s" in counters.last_error


# The fingers moving at their top speed are taken, and a long silence allows the distance
# covered in it; the first status, and the first after a (re)activation (gSTA not 3: the
# fingers stroke to calibrate), have nothing to be compared with.
def test_a_position_the_fingers_can_reach_is_taken(monkeypatch):
    gripper, client = _Gripper(monkeypatch), _client()
    # [counts/s] the top speed, were the whole byte range the stroke (more counts per mm than
    # the encoder's 3..230: the fastest the counts can change)
    rate = units.SPEED_MAX_MPS / units.STROKE_M * units.BYTE_MAX
    position = 3.0
    assert gripper.read(client, _words(gPO=255)) is not None  # the first status
    assert gripper.read(client, _words(gPO=3), after=1.0) is not None  # a second later
    for _ in range(20):  # a read every 5 ms at full speed
        position += rate * 0.005
        assert gripper.read(client, _words(gPO=round(position))) is not None
    assert gripper.read(client, _words(gSTA=1, gGTO=0, gPO=40)) is not None  # reactivation
    assert gripper.read(client, _words(gPO=200)) is not None
    assert client.counters().rejected == {}
