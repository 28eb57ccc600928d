"""Modbus RTU requests out of a master's byte stream, resynchronising as a slave does.

A request is passed on only whole with a valid CRC; its length follows from its function code and,
for writes, its byte count (Modbus Application Protocol V1.1b3, section 6). A header that cannot
start a request (unknown function, byte count beyond the largest frame) or a bad CRC drops one byte
and the search resumes. A header promising more bytes than have come is given up once a whole
CRC-valid request follows it (the CRC scan of Modbus over Serial Line V1.02, 2.5.1.1), so a burst of
plausible headers costs one request, not the bytes they promised (pymodbus's own framer, behind
this one, would wait for them). Each run of dropped bytes counts once in a MessageBoundary.

A whole request whose quantity is outside its function's range, or whose byte count is not the
one its quantity takes, is answered, as a slave must (Modbus Application Protocol V1.1b3, 6.1-6.4,
6.11, 6.12, 6.17), with the exception response: its function with 0x80 set and exception code 03
(illegal data value), through `answer`; it is not passed on.

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
# The quantity a request may name, per function: (offset of the quantity field, most allowed);
# at least 1 each (Modbus Application Protocol V1.1b3, 6.1-6.4, 6.11, 6.12, 6.17).
QUANTITY_LIMITS = {1: ((4, 0x7D0),), 2: ((4, 0x7D0),), 3: ((4, 0x7D),), 4: ((4, 0x7D),),
                   15: ((4, 0x7B0),), 16: ((4, 0x7B),), 23: ((4, 0x7D), (8, 0x79))}
ILLEGAL_DATA_VALUE = 0x03   # the exception code for a quantity or byte count out of range
EXCEPTION_FLAG = 0x80       # set in the function byte of an exception response

BAD_CRC = "bad CRC"
FRAMING = "framing error"
BROADCAST_ADDRESS = 0


def _write_size(function: int, header: bytes) -> int | str | None:
    """The frame size of a write (15, 16, 23) from its byte count; a str: why it cannot start a
    request; None: more bytes needed. Whether the byte count fits the quantity is asked of the
    whole request (data_value_problem), which is answered when it does not."""
    count_at = 6 if function in (15, 16) else 10  # 23: read address, count, write address, count
    if len(header) <= count_at:
        return None
    size = count_at + 1 + header[count_at] + CRC_SIZE
    if size > MAX_FRAME_SIZE:
        return (f"function {function} declares {header[count_at]} bytes to write, a "
                f"{size}-byte frame (at most {MAX_FRAME_SIZE})")
    return size


def data_value_problem(frame: bytes) -> str | None:
    """Why a whole request's quantity or byte count is out of its function's range, or None."""
    function = frame[1]
    for offset, limit in QUANTITY_LIMITS.get(function, ()):
        quantity = int.from_bytes(frame[offset:offset + 2], "big")
        if not 1 <= quantity <= limit:
            return f"function {function} asks for {quantity} values (1 to {limit})"
    if function in (15, 16, 23):
        quantity = int.from_bytes(frame[8:10] if function == 23 else frame[4:6], "big")
        byte_count = frame[10] if function == 23 else frame[6]
        expected = (quantity + 7) // 8 if function == 15 else 2 * quantity
        if byte_count != expected:
            return (f"function {function} declares {byte_count} bytes for {quantity} values "
                    f"({expected} bytes)")
    return None


def exception_response(request: bytes, code: int) -> bytes:
    """The RTU exception response to `request`: its address, its function | 0x80, `code`, CRC."""
    body = bytes([request[0], request[1] | EXCEPTION_FLAG, code])
    return body + FramerRTU.compute_CRC(body).to_bytes(2, "big")


def _crc_valid(frame: bytes) -> bool:
    return FramerRTU.check_CRC(frame[:-CRC_SIZE], int.from_bytes(frame[-CRC_SIZE:], "big"))


class ModbusRequestFramer:
    """Bytes in, whole CRC-valid requests out (module docstring); one reader owns it."""

    def __init__(self, boundary: MessageBoundary, address: int | None = None, answer=None):
        """address: the slave's own (1 to 247); None passes on a request for any slave but the
        broadcast address. answer(reply_bytes): sends an exception response to the master;
        None: a request that would get one is counted as rejected in `boundary` instead."""
        self._buffer = bytearray()
        self._dropping = False  # inside a run of dropped bytes
        self.boundary = boundary
        self.address = address
        self.answer = answer
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
            if not self._for_this_slave(frame[0]):
                self.other_addresses += 1
                continue
            problem = data_value_problem(frame)
            if problem is None:
                requests.append(frame)
            elif self.answer is not None:
                self.answer(exception_response(frame, ILLEGAL_DATA_VALUE))
            else:
                self.boundary.reject(FRAMING, f"{problem}; not answered")
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
