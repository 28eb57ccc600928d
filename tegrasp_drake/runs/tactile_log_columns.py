"""A run log's TEGRASP_TACTILE messages decoded straight into columns (numpy arrays), one row
a message: the fields the replay reads (times, the SA and RA channels, the flags and host
clocks) and what the reader's value check needs (tactile_value_check), 100 bytes a message
in all, never a Python object a message. Messages are gathered in blocks of their encoded
bytes (at most BLOCK_MESSAGES), each block decoded by numpy at once."""

import array
import struct

import numpy as np

from tegrasp_drake.lcmtypes import lcmt_tegrasp_tactile
from tegrasp_drake.rig.channels import TAXELS_PER_PAD

_FINGERPRINT = lcmt_tegrasp_tactile._get_packed_fingerprint()
# An encoded lcmt_tegrasp_tactile of 12 taxels a pad (lcmt_tegrasp_tactile.lcm), big-endian.
ENCODED_TACTILE = np.dtype([
    ("fingerprint", "S8"), ("utime", ">i8"), ("device_utime", ">i8"), ("stale", "i1"),
    ("zeroing", "i1"), ("arrival_s", ">f8"), ("tick_s", ">f8"), ("num_taxels", ">i4"),
    ("left_taxel_forces", ">f8", (TAXELS_PER_PAD,)),
    ("right_taxel_forces", ">f8", (TAXELS_PER_PAD,)),
    ("left_pad_acceleration", ">f8", (3,)), ("right_pad_acceleration", ">f8", (3,))])
_NUM_TAXELS_AT = ENCODED_TACTILE.fields["num_taxels"][1]
_NUM_TAXELS = struct.pack(">i", TAXELS_PER_PAD)
# A message of another taxel count, held with not-a-number values: the value check refuses
# it as it refuses any message not of 12 taxels a pad, its times still count as its
# neighbours' (tactile_time_check).
_OTHER_SHAPE = struct.Struct(">8sqqbbddi%dd" % (2 * TAXELS_PER_PAD + 6))
BLOCK_MESSAGES = 16384

# name -> (dtype, per-message shape): the columns a block decodes into.
COLUMNS = {"utime": (np.int64, ()), "device_utime": (np.int64, ()), "wall_us": (np.int64, ()),
           "stale": (bool, ()), "zeroing": (bool, ()), "arrival_s": (float, ()),
           "tick_s": (float, ()), "sa": (float, (2,)), "ra": (float, (2,)),
           "finite": (bool, ()), "taxel_low": (float, ()), "taxel_high": (float, ()),
           "acceleration_peak": (float, ())}
# The columns only the reader's value check reads (hardware_log_reader.tactile_value_check).
VALUE_CHECK_COLUMNS = ("finite", "taxel_low", "taxel_high", "acceleration_peak")
BYTES_PER_MESSAGE = sum(np.dtype(kind).itemsize * int(np.prod(shape))
                        for kind, shape in COLUMNS.values())


def _decoded_block(encoded: bytearray, walls: array.array) -> dict:
    """The COLUMNS of a block of encoded messages (ENCODED_TACTILE each) received at `walls`
    [us]. SA is each pad's taxel forces summed (Eq. 1), RA each pad's acceleration's norm,
    computed as RunLog computes them from rows of 24 taxels and 6 accelerations."""
    record = np.frombuffer(encoded, ENCODED_TACTILE)
    n = len(record)
    taxels = np.empty((n, 2 * TAXELS_PER_PAD))
    taxels[:, :TAXELS_PER_PAD] = record["left_taxel_forces"]
    taxels[:, TAXELS_PER_PAD:] = record["right_taxel_forces"]
    acceleration = np.empty((n, 6))
    acceleration[:, :3] = record["left_pad_acceleration"]
    acceleration[:, 3:] = record["right_pad_acceleration"]
    # values a corrupt message holds (not finite, 1e300) overflow or are invalid in the
    # sums: those messages are refused by the value check, which reads the raw values
    with np.errstate(over="ignore", invalid="ignore"):
        block = {
            "utime": record["utime"].astype(np.int64),
            "device_utime": record["device_utime"].astype(np.int64),
            "wall_us": np.array(walls, dtype=np.int64),
            "stale": record["stale"] != 0, "zeroing": record["zeroing"] != 0,
            "arrival_s": record["arrival_s"].astype(float),
            "tick_s": record["tick_s"].astype(float),
            "sa": np.column_stack([taxels[:, :TAXELS_PER_PAD].sum(axis=1),
                                   taxels[:, TAXELS_PER_PAD:].sum(axis=1)]),
            "ra": np.column_stack([np.linalg.norm(acceleration[:, :3], axis=1),
                                   np.linalg.norm(acceleration[:, 3:], axis=1)]),
            "finite": np.isfinite(taxels).all(axis=1) & np.isfinite(acceleration).all(axis=1),
            "taxel_low": taxels.min(axis=1), "taxel_high": taxels.max(axis=1),
            "acceleration_peak": np.abs(acceleration).max(axis=1)}
    del record
    return block


class TactileColumns:
    """Gathers a log's TEGRASP_TACTILE messages (add) and gives their COLUMNS (columns)."""

    def __init__(self):
        self._encoded, self._walls, self._blocks = bytearray(), array.array("q"), []

    def add(self, wall_us: int, data: bytes) -> bool:
        """Takes the message `data` received at `wall_us` [us]; False (not taken) when it does
        not decode as lcmt_tegrasp_tactile."""
        if (len(data) >= ENCODED_TACTILE.itemsize and data[:8] == _FINGERPRINT
                and data[_NUM_TAXELS_AT:_NUM_TAXELS_AT + 4] == _NUM_TAXELS):
            self._encoded += data[:ENCODED_TACTILE.itemsize]  # what the decoder reads of it
        else:
            try:
                message = lcmt_tegrasp_tactile.decode(data)
            except (ValueError, struct.error, UnicodeDecodeError, IndexError):
                return False
            self._encoded += _OTHER_SHAPE.pack(
                _FINGERPRINT, message.utime, message.device_utime, message.stale,
                message.zeroing, message.arrival_s, message.tick_s, TAXELS_PER_PAD,
                *[np.nan] * (2 * TAXELS_PER_PAD + 6))
        self._walls.append(wall_us)
        if len(self._walls) == BLOCK_MESSAGES:
            self._decode_block()
        return True

    def _decode_block(self) -> None:
        self._blocks.append(_decoded_block(self._encoded, self._walls))
        self._encoded, self._walls = bytearray(), array.array("q")

    def columns(self) -> dict:
        """{name: array of one row a message taken, in the order taken} (COLUMNS), each
        column joined from the blocks and the blocks' parts freed one column at a time."""
        if self._walls:
            self._decode_block()
        blocks, self._blocks = self._blocks, []
        joined = {}
        for name, (kind, shape) in COLUMNS.items():
            parts = [block.pop(name) for block in blocks]
            joined[name] = np.concatenate(parts) if parts else np.empty((0, *shape), kind)
            del parts
        return joined
