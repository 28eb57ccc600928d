"""Robotiq 2F-85 Modbus RTU register map and pure encode/decode (manual, "Control").
Registers are 16 bits, first byte in the high half.

Command, 3 registers written with function 16 at 1000: byte 0 action (bit0 rACT, bit3
rGTO, bit4 rATR, bit5 rARD), bytes 1-2 reserved, then rPR, rSP, rFR.
Status, 3 registers read with function 4 (some firmware: 3) at 2000: byte 0 (bit0 gACT,
bit3 gGTO, bits 4-5 gSTA, bits 6-7 gOBJ), byte 1 reserved, byte 2 gFLT (low nibble), then
gPR, gPO, gCU (x 10 mA).
"""

import numpy as np

from tegrasp_drake.robotiq import units

BAUDRATE = 115200  # 8N1 (manual)
DEVICE_ID = 9  # the manual's default slave id
COMMAND_ADDRESS = 1000
STATUS_ADDRESS = 2000
REGISTER_COUNT = 3
READ_FUNCTION = 4

# Action request bits (command byte 0).
ACTION_ACT = 0x01
ACTION_GTO = 0x08
ACTION_ATR = 0x10
ACTION_ARD = 0x20
# Gripper status fields (status byte 0).
STATUS_ACT_BIT = 0
STATUS_GTO_BIT = 3
STATUS_STA_SHIFT = 4
STATUS_OBJ_SHIFT = 6


def _words_from_bytes(six_bytes) -> list[int]:
    b = [int(x) & 0xFF for x in six_bytes]
    return [(b[0] << 8) | b[1], (b[2] << 8) | b[3], (b[4] << 8) | b[5]]


def _bytes_from_words(words) -> list[int]:
    if len(words) != REGISTER_COUNT:
        raise ValueError(f"expected {REGISTER_COUNT} registers, got {len(words)}")
    out = []
    for word in words:
        out += [(int(word) >> 8) & 0xFF, int(word) & 0xFF]
    return out


def _byte(value, name) -> int:
    byte = int(round(float(value)))
    if not 0 <= byte <= 255:
        raise ValueError(f"{name} must be a byte 0..255, got {value}")
    return byte


def command_registers(position, speed, force, *, activate=True, go_to=True,
                      auto_release=False, release_open=False) -> list[int]:
    """The 3 registers written at 1000 for rPR, rSP, rFR (bytes) and the action bits."""
    action = ((ACTION_ACT if activate else 0) | (ACTION_GTO if go_to else 0)
              | (ACTION_ATR if auto_release else 0) | (ACTION_ARD if release_open else 0))
    return _words_from_bytes([action, 0, 0, _byte(position, "rPR"), _byte(speed, "rSP"),
                              _byte(force, "rFR")])


def command_registers_from_vector(command) -> list[int]:
    """Registers for a `gripper.command` vector [rPR, rSP, rFR] (activated, rGTO = 1)."""
    return command_registers(command[units.COMMAND_POSITION], command[units.COMMAND_SPEED],
                             command[units.COMMAND_FORCE])


def decode_command_registers(words) -> dict:
    """The fields of the 3 command registers: rACT, rGTO, rATR, rARD, rPR, rSP, rFR."""
    b = _bytes_from_words(words)
    return {"rACT": b[0] & 1, "rGTO": (b[0] >> 3) & 1, "rATR": (b[0] >> 4) & 1,
            "rARD": (b[0] >> 5) & 1, "rPR": b[3], "rSP": b[4], "rFR": b[5]}


def status_registers(status) -> list[int]:
    """The 3 status registers read at 2000 for a status vector (emulator side)."""
    s = [int(round(float(x))) for x in status]
    gripper_status = ((s[units.STATUS_ACT] & 1) << STATUS_ACT_BIT
                      | (s[units.STATUS_GTO] & 1) << STATUS_GTO_BIT
                      | (s[units.STATUS_STA] & 3) << STATUS_STA_SHIFT
                      | (s[units.STATUS_OBJ] & 3) << STATUS_OBJ_SHIFT)
    return _words_from_bytes([gripper_status, 0, s[units.STATUS_FLT] & 0x0F,
                              s[units.STATUS_PR], s[units.STATUS_PO], s[units.STATUS_CU]])


def status_from_registers(words) -> np.ndarray:
    """The `gripper.status` vector [gACT, gGTO, gSTA, gOBJ, gFLT, gPR, gPO, gCU]."""
    b = _bytes_from_words(words)
    status = np.zeros(units.STATUS_SIZE)
    status[units.STATUS_ACT] = (b[0] >> STATUS_ACT_BIT) & 1
    status[units.STATUS_GTO] = (b[0] >> STATUS_GTO_BIT) & 1
    status[units.STATUS_STA] = (b[0] >> STATUS_STA_SHIFT) & 3
    status[units.STATUS_OBJ] = (b[0] >> STATUS_OBJ_SHIFT) & 3
    status[units.STATUS_FLT] = b[2] & 0x0F
    status[units.STATUS_PR] = b[3]
    status[units.STATUS_PO] = b[4]
    status[units.STATUS_CU] = b[5]
    return status
