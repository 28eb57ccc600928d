"""Robotiq 2F-85 register bytes (manual, "Control") and SI units, shared by sim and
hardware; `gripper.command` and `gripper.status` carry the bytes as floats."""

import enum

import numpy as np

# Datasheet: stroke 85 mm, closing speed 20-150 mm/s, grip force 20-235 N; the encoder reads
# about 3 fully open and about 230 fully closed.
STROKE_M = 0.085
SPEED_MIN_MPS = 0.020
SPEED_MAX_MPS = 0.150
FORCE_MIN_N = 20.0
FORCE_MAX_N = 235.0
POSITION_OPEN_BYTE = 3.0
POSITION_CLOSED_BYTE = 230.0
POSITION_SPAN_BYTES = POSITION_CLOSED_BYTE - POSITION_OPEN_BYTE  # the stroke in position bytes

# The registers are bytes: every request and status value lies in [0, BYTE_MAX].
BYTE_MAX = 255.0

# gripper.command = [rPR, rSP, rFR]
COMMAND_NAMES = ("rPR", "rSP", "rFR")
COMMAND_SIZE = len(COMMAND_NAMES)
COMMAND_POSITION, COMMAND_SPEED, COMMAND_FORCE = range(COMMAND_SIZE)

# gripper.status = [gACT, gGTO, gSTA, gOBJ, gFLT, gPR, gPO, gCU]
STATUS_NAMES = ("gACT", "gGTO", "gSTA", "gOBJ", "gFLT", "gPR", "gPO", "gCU")
STATUS_SIZE = len(STATUS_NAMES)
(STATUS_ACT, STATUS_GTO, STATUS_STA, STATUS_OBJ, STATUS_FLT, STATUS_PR, STATUS_PO,
 STATUS_CU) = range(STATUS_SIZE)


class ObjectStatus(enum.IntEnum):
    """gOBJ: the object-detection status."""
    MOVING = 0
    STOPPED_ON_CONTACT_OPENING = 1
    STOPPED_ON_CONTACT_CLOSING = 2
    AT_REQUESTED_POSITION = 3


class ActivationStatus(enum.IntEnum):
    """gSTA: the activation status."""
    RESET = 0
    ACTIVATING = 1
    UNUSED = 2
    ACTIVE = 3


# gFLT codes; from FIRST_MAJOR_FAULT on the fingers stop until the next activation (manual).
FAULT_ACTION_DELAYED = 0x05
FAULT_NOT_ACTIVATED = 0x07
FIRST_MAJOR_FAULT = 0x0A

FAULT_NAMES = {
    0x00: "no fault",
    FAULT_ACTION_DELAYED: "action delayed: activation (reactivation) must complete first",
    0x06: "priority fault",
    FAULT_NOT_ACTIVATED: "the activation bit must be set before any action",
    0x08: "maximum operating temperature exceeded",
    0x09: "no communication during at least 1 second",
    FIRST_MAJOR_FAULT: "under minimum operating voltage",
    0x0B: "automatic release in progress",
    0x0C: "internal processor fault",
    0x0D: "activation fault",
    0x0E: "overcurrent triggered",
    0x0F: "automatic release completed",
}


def fault_name(code: int) -> str:
    """Returns the manual's name for a gFLT fault code."""
    return FAULT_NAMES.get(int(code), f"unknown fault 0x{int(code):02X}")


# gCU [x 10 mA]: the manual's examples read 0x10 moving and 0x00 stopped (the screw holds);
# no current-force curve is published, so 600 mA at 235 N, in proportion, is an assumption.
MOVING_CURRENT = 16.0
MAX_GRIPPING_CURRENT = 60.0


def current_byte(force_n: float, moving: bool) -> float:
    """gCU [x 10 mA] of a motor pushing each pad with force_n [N] while the fingers move
    (at least the free-motion current), and 0 once they stop."""
    if not moving:
        return 0.0
    pushing = MAX_GRIPPING_CURRENT * min(max(force_n, 0.0), FORCE_MAX_N) / FORCE_MAX_N
    return float(max(MOVING_CURRENT, round(pushing)))


def opening_from_position_byte(position_byte):
    """Finger opening [m] (pad to pad) for an rPR/gPO byte; linear between open and closed."""
    fraction = (POSITION_CLOSED_BYTE - np.clip(position_byte, POSITION_OPEN_BYTE,
                                               POSITION_CLOSED_BYTE))
    return STROKE_M * fraction / POSITION_SPAN_BYTES


def position_from_opening(opening_m):
    """The finger position on the rPR/gPO byte scale for an opening [m] (pad to pad), unrounded
    (a finger stands between two bytes); linear between open and closed."""
    fraction = np.clip(np.asarray(opening_m) / STROKE_M, 0.0, 1.0)
    return POSITION_CLOSED_BYTE - fraction * POSITION_SPAN_BYTES


def position_byte_from_opening(opening_m):
    """The rPR/gPO byte for a finger opening [m], rounded to the nearest integer."""
    return np.rint(position_from_opening(opening_m))


def speed_from_byte(speed_byte):
    """Finger closing speed [m/s] (pad to pad) for an rSP byte."""
    return SPEED_MIN_MPS + np.clip(speed_byte, 0, 255) / 255.0 * (SPEED_MAX_MPS - SPEED_MIN_MPS)


def position_bytes_per_second(speed_byte) -> float:
    """Finger speed on the position byte scale [bytes/s] for an rSP byte."""
    return float(speed_from_byte(speed_byte)) / STROKE_M * POSITION_SPAN_BYTES


def speed_byte_from_speed(speed_mps):
    """The rSP byte for a closing speed [m/s]."""
    fraction = (np.asarray(speed_mps) - SPEED_MIN_MPS) / (SPEED_MAX_MPS - SPEED_MIN_MPS)
    return np.rint(np.clip(fraction, 0.0, 1.0) * 255.0)


def force_from_byte(force_byte):
    """Grip force limit [N] for an rFR byte."""
    return FORCE_MIN_N + np.clip(force_byte, 0, 255) / 255.0 * (FORCE_MAX_N - FORCE_MIN_N)


def force_byte_from_force(force_n):
    """The rFR byte for a grip force [N]."""
    fraction = (np.asarray(force_n) - FORCE_MIN_N) / (FORCE_MAX_N - FORCE_MIN_N)
    return np.rint(np.clip(fraction, 0.0, 1.0) * 255.0)
