"""Modbus RTU requests out of a master's byte stream, resynchronising as a slave does.

A request is passed on only whole with a valid CRC; its length follows from its function code and,
for writes, its byte count (Modbus Application Protocol V1.1b3, section 6). A header that cannot
start a request (unknown function, byte count beyond the frame or unlike its register count) or a
bad CRC drops one byte and the search resumes. A header promising more bytes than have come is given
up once a whole CRC-valid request follows it (the CRC scan of Modbus over Serial Line V1.02,
2.5.1.1), so a burst of plausible headers costs one request, not the bytes they promised (pymodbus's
own framer, behind this one, would wait for them). Each run of dropped bytes counts once in a
MessageBoundary.

Addressing (Modbus over Serial Line V1.02, 2.1): a request for another slave address or the
broadcast address 0 is framed (the stream stays in step) and not passed on: on a shared RS-485 line
an answer would collide with the addressed slave's, and a broadcast is never answered."""

from pymodbus.framer.rtu import FramerRTU

from tegrasp_drake.hardware.message_boundary import MessageBoundary

MAX_FRAME_SIZE = 256   # bytes, Modbus over Serial Line V1.02, 2.5.1
CRC_SIZE = 2
# [bytes, address to CRC] of the fixed-length requests (Modbus Application Protocol, section 6)
FIXED_SIZES = {1: 8, 2: 8, 3: 8, 4: 8, 5: 8, 6: 8, 8: 8, 7: 4, 11: 4, 12: 4, 17: 4,
               22: 10, 24: 6, 43: 7}
MAX_WRITE_REGISTERS = 123   # function 16 (and 23's write part: 121)
MAX_WRITE_COILS = 1968      # function 15

BAD_CRC = "bad CRC"
FRAMING = "framing error"
BROADCAST_ADDRESS = 0


def _write_size(function: int, header: bytes) -> int | str | None:
    """The frame size of a write (15, 16, 23) from its header; a str: why it cannot start a
    request; None: more bytes needed."""
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
    """Bytes in, whole CRC-valid requests out (module docstring); one reader owns it."""

    def __init__(self, boundary: MessageBoundary, address: int | None = None):
        """address: the slave's own (1 to 247); None passes on a request for any slave but the
        broadcast address."""
        self._buffer = bytearray()
        self._dropping = False  # inside a run of dropped bytes
        self.boundary = boundary
        self.address = address
        self.skipped_bytes = 0
        self.other_addresses = 0  # whole requests for another slave or for all (broadcast)

    def feed(self, data: bytes) -> list[bytes]:
        """Adds received bytes; returns the requests for this slave they completed, in order."""
        self._buffer += data
        requests = []
        while len(self._buffer) >= 2:
            size = self._size()
            if size is None or (isinstance(size, int) and len(self._buffer) < size):
                # Waiting for bytes; unless a whole request follows: then they never come.
                start = self._whole_request_after(1)
                if start is None:
                    break
                self._drop(FRAMING, f"a function {self._buffer[1]} header whose bytes did not "
                           "come before a whole request", count=start)
                continue
            if isinstance(size, str):
                self._drop(FRAMING, size)
                continue
            frame = bytes(self._buffer[:size])
            if not _crc_valid(frame):
                self._drop(BAD_CRC, f"a {size}-byte function {frame[1]} request")
                continue
            del self._buffer[:size]
            self._dropping = False
            self.boundary.count_accepted()
            if self._for_this_slave(frame[0]):
                requests.append(frame)
            else:
                self.other_addresses += 1
        return requests

    def _for_this_slave(self, address: int) -> bool:
        if address == BROADCAST_ADDRESS:
            return False
        return self.address is None or address == self.address

    def _whole_request_after(self, first: int) -> int | None:
        """The offset (at least `first`) of the first whole CRC-valid request in the buffer, or
        None."""
        for start in range(first, len(self._buffer) - 1):
            size = self._size(start)
            if (isinstance(size, int) and start + size <= len(self._buffer)
                    and _crc_valid(bytes(self._buffer[start:start + size]))):
                return start
        return None

    def _size(self, start: int = 0) -> int | str | None:
        """The size of the request at offset `start` of the buffer; a str if none starts there;
        None if more bytes are needed."""
        function = self._buffer[start + 1]
        if function in FIXED_SIZES:
            return FIXED_SIZES[function]
        if function in (15, 16, 23):
            return _write_size(function, self._buffer[start:])
        return f"function {function} is not one whose request length is known"

    def _drop(self, reason: str, detail: str, count: int = 1):
        if not self._dropping:
            self.boundary.reject(reason, f"{detail}; dropped until a valid request")
            self._dropping = True
        self.skipped_bytes += count
        del self._buffer[:count]
