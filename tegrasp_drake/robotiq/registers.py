"""Robotiq 2F-85 Modbus RTU register map and pure encode/decode (manual, "Control"):
3 command registers written at 1000 (function 16), 3 status registers read at 2000
(function 4; some firmware 3), 16 bits each, first byte high; the bit fields below."""

import numpy as np

from tegrasp_drake.robotiq import units

BAUDRATE = 115200  # 8N1 (manual)
DEVICE_ID = 9  # the manual's default slave id
COMMAND_ADDRESS = 1000
STATUS_ADDRESS = 2000
REGISTER_COUNT = 3
READ_FUNCTION = 4

# Modbus RTU on the wire (Modbus over serial line specification and implementation guide
# V1.02, 2.5.1): 10 bits a character at 8N1 (start, 8 data, stop), and a silence of 3.5
# characters that ends each frame. A status read of REGISTER_COUNT registers is a request of
# 8 bytes (address, function, start, count, CRC) and an answer of 5 + 2 per register
# (address, function, byte count, data, CRC); a command write (function 16) a request of
# 9 + 2 per register (..., count, byte count, data, CRC) and an answer of 8.
BITS_PER_CHARACTER = 10
FRAME_SILENCE_CHARACTERS = 3.5
READ_BYTES = 8 + 5 + 2 * REGISTER_COUNT
WRITE_BYTES = 9 + 2 * REGISTER_COUNT + 8


def transaction_seconds(transaction_bytes: int, baudrate: float) -> float:
    """[s] a request and its answer, `transaction_bytes` together, take on the wire at
    `baudrate` [baud], with the silence that ends each of the two frames."""
    characters = transaction_bytes + 2 * FRAME_SILENCE_CHARACTERS
    return characters * BITS_PER_CHARACTER / baudrate

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
# Status bits the manual marks "Reserved": byte 0 bits 1-2 and all of byte 1 (byte 2's high
# nibble is kFLT, the controller's fault, not reserved). A gripper leaves them clear.
STATUS_RESERVED_BITS = (0x06, 0xFF, 0x00, 0x00, 0x00, 0x00)  # a mask per status byte


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


def status_contradiction(words) -> str | None:
    """What in the 3 status registers the manual's register map makes impossible, or None.
    The manual ("Gripper status"): reserved bits (STATUS_RESERVED_BITS); gSTA 0x02 "Not used";
    gACT is the echo of rACT, 0 "Gripper reset", and a gripper in reset reports gSTA 0x00
    "Gripper is in reset (or automatic release) state": activation in progress (gSTA 1) or
    completed (gSTA 3) needs rACT = 1. gGTO echoes rGTO, which may be set while in reset
    (fault 0x07), so gGTO with gACT = 0 is possible and not refused."""
    b = _bytes_from_words(words)
    for index, (byte, mask) in enumerate(zip(b, STATUS_RESERVED_BITS)):
        if byte & mask:
            return (f"reserved bits 0x{byte & mask:02X} set in status byte {index} "
                    f"(0x{byte:02X}); the 2F-85 leaves them clear")
    active_bit = (b[0] >> STATUS_ACT_BIT) & 1
    activation = (b[0] >> STATUS_STA_SHIFT) & 3
    if activation == units.ActivationStatus.UNUSED:
        return "gSTA = 2, a value the 2F-85 does not use"
    if activation != units.ActivationStatus.RESET and not active_bit:
        return f"gSTA = {activation} with gACT = 0: a gripper in reset reports gSTA = 0"
    return None


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
