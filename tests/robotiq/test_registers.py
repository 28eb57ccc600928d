"""Robotiq 2F-85 register encoding (no serial line)."""

import numpy as np
import pytest

from tegrasp_drake.robotiq.registers import (
    command_registers, command_registers_from_vector, decode_command_registers,
    status_from_registers, status_registers)


def test_command_registers_follow_the_manual_layout():
    # rACT | rGTO = 0x09 in byte 0, rPR in byte 3, rSP byte 4, rFR byte 5.
    assert command_registers(0xC8, 0xFF, 0x32) == [0x0900, 0x00C8, 0xFF32]
    assert command_registers(0, 0, 0, activate=False, go_to=False) == [0, 0, 0]
    assert command_registers_from_vector([200.0, 255.0, 50.0]) == [0x0900, 0x00C8, 0xFF32]


def test_command_registers_reject_values_that_are_not_bytes():
    with pytest.raises(ValueError, match="rSP"):
        command_registers(10, 300, 10)


def test_command_registers_decode_back():
    fields = decode_command_registers(command_registers(12, 34, 56, auto_release=True))
    assert fields == {"rACT": 1, "rGTO": 1, "rATR": 1, "rARD": 0, "rPR": 12, "rSP": 34,
                      "rFR": 56}


def test_status_registers_decode_to_the_status_vector():
    # gACT=1, gGTO=1, gSTA=3, gOBJ=2 -> 0b10_11_1_00_1 = 0xB9; gFLT 0x0E; gPR, gPO, gCU.
    words = [0xB900, 0x0EFF, 0x7B18]
    status = status_from_registers(words)
    np.testing.assert_array_equal(status, [1, 1, 3, 2, 0x0E, 255, 123, 24])
    assert status_registers(status) == words
