"""Modbus RTU requests out of a master's byte stream, resynchronising as a slave does.

A Modbus RTU slave takes a request when a whole frame with a valid CRC has arrived, and
drops anything else: noise, a frame with a bad CRC, a frame whose declared byte count
contradicts its own register count. The length of a request follows from its function
code and, for the writes, its byte count (Modbus Application Protocol Specification
V1.1b3, section 6; Modbus over Serial Line V1.02, 2.5.1: at most 256 bytes a frame). The
framer here applies those rules to the bytes the emulated 2F-85 receives:

- a request is passed on only whole, its CRC valid;
- a header that cannot start a request (a function whose length the specification does
  not fix, a byte count beyond the frame maximum or other than its register count says)
  is a framing error: the first byte is dropped and the search resumes at the next (never
  a wait for bytes the header promised: the next valid request is answered). Without the
  line's silent intervals, a frame of another function has no length to check its CRC
  at: searching every length up to 256 bytes would take one in about 260 positions of
  noise for a request, which pymodbus's framer behind would then misread;
- a frame of the right length whose CRC fails is dropped the same way.

Each run of dropped bytes between two requests is counted once in a MessageBoundary
(hardware/message_boundary.py), under the reason that started it, and its bytes in
`skipped_bytes`. pymodbus's own framer (the emulator's server) waits for the bytes a declared
byte count promises, so one malformed write would swallow the valid requests behind it;
this framer stands in front of it.
"""

from pymodbus.framer.rtu import FramerRTU

from tegrasp_drake.hardware.message_boundary import MessageBoundary

MAX_FRAME_SIZE = 256   # bytes, Modbus over Serial Line V1.02, 2.5.1
CRC_SIZE = 2
# Requests of a fixed length [bytes, address to CRC]: read coils, discrete inputs, holding
# and input registers (1-4), write single coil / register (5, 6), diagnostics (8), read
# exception status (7), comm event counter/log (11, 12), report server id (17), mask
# write (22), read FIFO (24), read device identification (43 / MEI 14).
FIXED_SIZES = {1: 8, 2: 8, 3: 8, 4: 8, 5: 8, 6: 8, 8: 8, 7: 4, 11: 4, 12: 4, 17: 4,
               22: 10, 24: 6, 43: 7}
MAX_WRITE_REGISTERS = 123   # function 16 (and 23's write part: 121)
MAX_WRITE_COILS = 1968      # function 15

BAD_CRC = "bad CRC"
FRAMING = "framing error"


def _write_size(function: int, header: bytes) -> int | str | None:
    """The frame size of a write (15, 16, 23) from its header; a str says why the header
    cannot start a request; None: more bytes needed to tell."""
    if function in (15, 16):
        if len(header) < 7:
            return None
        quantity, byte_count = int.from_bytes(header[4:6], "big"), header[6]
        expected = 2 * quantity if function == 16 else (quantity + 7) // 8
        limit = MAX_WRITE_REGISTERS if function == 16 else MAX_WRITE_COILS
        if not 1 <= quantity <= limit or byte_count != expected:
            return (f"function {function} declares {quantity} values in {byte_count} bytes "
                    f"(1 to {limit} values, {expected} bytes for {quantity})")
        return 9 + byte_count
    if len(header) < 11:  # function 23: read address, count, write address, count, bytes
        return None
    quantity, byte_count = int.from_bytes(header[8:10], "big"), header[10]
    if not 1 <= quantity <= 121 or byte_count != 2 * quantity:
        return (f"function 23 declares {quantity} registers to write in {byte_count} bytes "
                "(1 to 121 registers, 2 bytes each)")
    return 13 + byte_count


def _crc_valid(frame: bytes) -> bool:
    return FramerRTU.check_CRC(frame[:-CRC_SIZE], int.from_bytes(frame[-CRC_SIZE:], "big"))


class ModbusRequestFramer:
    """Feeds bytes in, takes whole CRC-valid requests out (module docstring). Not
    thread-safe: one reader owns it."""

    def __init__(self, boundary: MessageBoundary):
        self._buffer = bytearray()
        self._dropping = False  # inside a run of dropped bytes
        self.boundary = boundary
        self.skipped_bytes = 0

    def feed(self, data: bytes) -> list[bytes]:
        """Adds received bytes; returns the requests they completed, in order."""
        self._buffer += data
        requests = []
        while len(self._buffer) >= 2:
            size = self._size()
            if size is None:
                break
            if isinstance(size, str):
                self._drop(FRAMING, size)
                continue
            if len(self._buffer) < size:
                break
            frame = bytes(self._buffer[:size])
            if not _crc_valid(frame):
                self._drop(BAD_CRC, f"a {size}-byte function {frame[1]} request")
                continue
            del self._buffer[:size]
            self._dropping = False
            self.boundary.count_accepted()
            requests.append(frame)
        return requests

    def _size(self) -> int | str | None:
        """The size of the request at the buffer's start, a str if none starts there, None
        if more bytes are needed."""
        function = self._buffer[1]
        if function in FIXED_SIZES:
            return FIXED_SIZES[function]
        if function in (15, 16, 23):
            return _write_size(function, self._buffer)
        return f"function {function} is not one whose request length is known"

    def _drop(self, reason: str, detail: str):
        if not self._dropping:
            self.boundary.reject(reason, f"{detail}; dropped until a valid request")
            self._dropping = True
        self.skipped_bytes += 1
        del self._buffer[:1]
