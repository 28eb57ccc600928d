"""A Robotiq 2F-85 Modbus RTU client on its own thread, never blocking its caller. It
activates the gripper as the manual prescribes, then every `period` (200 Hz at most) writes
the newest command when it changed (or every `command_refresh_period`) and reads the status.
Every answer crosses a MessageBoundary; a failed transaction is counted and skipped, so a
silent gripper shows as a status whose arrival time stops advancing."""

import dataclasses
import logging
import threading
import time

import numpy as np
from pymodbus import FramerType
from pymodbus.client import ModbusSerialClient
from pymodbus.exceptions import ModbusException, ModbusIOException

from tegrasp_drake.hardware.message_boundary import (
    UNDECODABLE, MessageBoundary, RejectedMessage)
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.robotiq import units
from tegrasp_drake.robotiq import registers
from tegrasp_drake.rig.api_boundary import public_dataclass

MIN_PERIOD = 1.0 / 200.0  # [s]
# [s] the least the 2F-85's activation can take: it strokes the fingers through the whole
# stroke and back (the manual's activation), at most SPEED_MAX_MPS over STROKE_M each way. A
# wait for the gripper to be active shorter than this always fails.
ACTIVATION_MIN_S = 2.0 * units.STROKE_M / units.SPEED_MAX_MPS
# [s] a command write and its answer on the wire at the 2F-85's 115200 baud (Modbus RTU,
# registers.transaction_seconds): a request timeout shorter than this times every request out
# (a slower gripper.baudrate needs more: hardware/config.gripper_request_timeout_problem).
FASTEST_WRITE_S = registers.transaction_seconds(registers.WRITE_BYTES, registers.BAUDRATE)


@public_dataclass
@dataclasses.dataclass
class RobotiqModbusConfig:
    """Serial line, bus and timing of the client. Times in seconds."""
    port: str = "/dev/ttyUSB0"
    baudrate: int = bounded(registers.BAUDRATE, low=1200, high=115_200, unit="baud",
                            why="the 2F-85 talks at 115200 baud, Robotiq 2F-85 manual")
    device_id: int = bounded(registers.DEVICE_ID, low=1, high=247,
                             why="Modbus slave addresses, Modbus over serial line specification")
    period: float = bounded(MIN_PERIOD, low=MIN_PERIOD, high=1.0, unit="s",
                            why="the 2F-85 takes requests at up to 200 Hz")
    # a status answer is 11 bytes, about 1 ms at 115200 baud; 50 ms is ample. Low end: a
    # write and its answer at 115200 baud (FASTEST_WRITE_S); high: 10 s of silence is a
    # gripper gone, not a slow one.
    request_timeout: float = bounded(
        0.05, low=FASTEST_WRITE_S, low_open=True, high=10.0, unit="s",
        why=f"longer than a write and its answer at 115200 baud, "
            f"{number_text(FASTEST_WRITE_S)} s")
    # activation strokes the fingers (the emulator takes 1.5 s); 5 s leaves margin. Low
    # end: the fastest activation (ACTIVATION_MIN_S); high: a minute is a gripper stuck.
    activation_timeout: float = bounded(
        5.0, low=ACTIVATION_MIN_S, high=60.0, unit="s",
        why=f"at least the 2F-85's fastest activation, its {units.STROKE_M * 1e3:g} mm "
            f"stroke and back at {units.SPEED_MAX_MPS * 1e3:g} mm/s, "
            f"{number_text(ACTIVATION_MIN_S)} s")
    # a lost write is repeated within 0.1 s. Low end: one request period at the 2F-85's
    # 200 Hz (a write cannot be repeated more often than requests go out).
    command_refresh_period: float = bounded(
        0.1, low=MIN_PERIOD, high=10.0, unit="s",
        why="at least one request period at the 2F-85's 200 Hz")
    # 4, or 3 on some firmware
    read_function: int = bounded(registers.READ_FUNCTION, low=3, high=4,
                                 why="Modbus function 3 or 4")


class RobotiqActivationError(RuntimeError):
    """The gripper did not come up (port not opened or activation incomplete)."""


@dataclasses.dataclass(frozen=True)
class RobotiqStatusSample:
    """One status read: the `gripper.status` vector and when it arrived."""
    status: np.ndarray
    arrival_time: float  # time.monotonic() [s]
    count: int           # 1 for the first status read, then +1 per read


@dataclasses.dataclass
class RobotiqModbusCounters:
    """Transaction counters; `errors` counts every failed transaction, `rejected` by reason."""
    writes: int = 0
    reads: int = 0
    errors: int = 0
    overruns: int = 0  # loop iterations that started late by more than one period
    last_error: str = ""
    rejected: dict = dataclasses.field(default_factory=dict)  # reason -> count


NO_ANSWER = "no answer"
EXCEPTION_RESPONSE = "exception response"
WRONG_FUNCTION = "wrong function"
WRONG_REGISTER_COUNT = "wrong register count"
WRONG_ECHO = "wrong write echo"
IMPOSSIBLE_STATUS = "impossible status"
POSITION_JUMP = "position jump"

# [counts/s] the fastest gPO can change: the 2F-85's top speed, 150 mm/s over its 85 mm
# stroke (datasheet), with the whole byte range 0..255 taken for the stroke. The encoder reads
# about 3 (open) to 230 (closed) (manual), so this bounds the counts per mm from above: a
# gripper whose encoder spans more counts than thought is not refused.
MAX_POSITION_RATE = units.SPEED_MAX_MPS / units.STROKE_M * units.BYTE_MAX
# [counts] gPO is a finger position rounded to a whole count: two readings of fingers that
# moved d counts differ by up to d + 1.
POSITION_QUANTUM = 1.0


def check_answer(response, function: int, address: int, count: int):
    """`response` (pymodbus's, to a request of `function` for `count` registers at `address`)
    when it answers that request, else RejectedMessage naming why."""
    if response.isError():
        code = getattr(response, "exception_code", None)
        raise RejectedMessage(EXCEPTION_RESPONSE, (
            f"exception code {code:02d}" if isinstance(code, int) else str(response))
            + f" to a function {function} request")
    if response.function_code != function:
        raise RejectedMessage(WRONG_FUNCTION, f"a function {response.function_code} answer "
                              f"to a function {function} request")
    if function == 16:
        if (response.address, response.count) != (address, count):
            raise RejectedMessage(WRONG_ECHO, f"the write of {count} registers at {address} "
                                  f"echoed as {response.count} at {response.address}")
    elif len(response.registers) != count:
        raise RejectedMessage(WRONG_REGISTER_COUNT, f"{len(response.registers)} registers "
                              f"answering a read of {count}")
    return response


class StatusAnswerCheck:
    """check_answer, and for a status read a status the 2F-85 can send: one its manual's
    register map allows (registers.status_contradiction) and a gPO the fingers can reach from
    the last accepted status's. The gripper samples gPO at some instant between a request's
    sending and its answer's arrival, so two samples lie at most (this answer's arrival - the
    last accepted request's sending) apart: that interval, which holds the read's timing
    jitter, times MAX_POSITION_RATE, plus POSITION_QUANTUM, is the largest step. A refused
    status leaves the last accepted one, so the interval and the allowed step grow until a
    status fits. Positions are compared only while activation is complete (gSTA = 3):
    activation strokes the fingers to calibrate them, so the first status, and the first after
    a reactivation or a restart of the gripper, have nothing to be compared with. The client
    calls `accepted` with each status its boundary lets through."""

    def __init__(self):
        self._last = None  # (gPO, its request's sending [s]) of the last accepted active status

    def __call__(self, response, function: int, address: int, count: int,
                 sent: float, arrived: float):
        response = check_answer(response, function, address, count)
        if function == 16:
            return response
        contradiction = registers.status_contradiction(response.registers)
        if contradiction is not None:
            raise RejectedMessage(IMPOSSIBLE_STATUS, contradiction)
        status = registers.status_from_registers(response.registers)
        if self._last is not None and status[units.STATUS_STA] == units.ActivationStatus.ACTIVE:
            last_position, last_sent = self._last
            interval = max(arrived - last_sent, 0.0)
            step = abs(status[units.STATUS_PO] - last_position)
            if step > MAX_POSITION_RATE * interval + POSITION_QUANTUM:
                raise RejectedMessage(
                    POSITION_JUMP, f"gPO {last_position:.0f} -> {status[units.STATUS_PO]:.0f} "
                    f"within {number_text(interval * 1e3)} ms; the 2F-85's fingers move at "
                    f"most 150 mm/s ({number_text(MAX_POSITION_RATE)} counts/s)")
        return response

    def accepted(self, status, sent: float) -> None:
        """Takes `status`, read by a request sent at `sent` [s], as the last accepted."""
        active = status[units.STATUS_STA] == units.ActivationStatus.ACTIVE
        self._last = (status[units.STATUS_PO], sent) if active else None


def quiet_modbus_library() -> None:
    """Keeps pymodbus's log to what is critical: the client counts timed-out and undecodable
    replies itself (its MessageBoundary), in one line each, where pymodbus would print
    multi-line hex dumps of garbage replies on stderr."""
    logging.getLogger("pymodbus").setLevel(logging.CRITICAL)


def status_words(status) -> str:
    """Every field of a status vector, e.g. "gACT 1, gGTO 0, gSTA 1, gOBJ 0, gFLT 0x00, gPR 0,
    gPO 3, gCU 0": what the gripper said, for a message that says what arrived."""
    return ", ".join(f"{name} 0x{int(value):02X}" if index == units.STATUS_FLT
                     else f"{name} {int(value)}"
                     for index, (name, value) in enumerate(zip(units.STATUS_NAMES, status)))


def device_fault_words(status) -> str:
    """gFLT of a status vector with its name, e.g. "gFLT = 0x0F (automatic release completed)"."""
    code = int(status[units.STATUS_FLT])
    return f"gFLT = 0x{code:02X} ({units.fault_name(code)})"


class RobotiqModbusClient:
    """See the module docstring. Use as a context manager, or call start() and close()."""

    def __init__(self, config: RobotiqModbusConfig):
        if config.period < MIN_PERIOD:
            raise ValueError(f"period {number_text(config.period)} s is faster than the "
                             "gripper's 200 Hz")
        self._config = dataclasses.replace(config)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._active = threading.Event()
        self._finished = threading.Event()
        self._thread = None
        self._command = None
        self._sample = None
        self._error = None
        self._counters = RobotiqModbusCounters()
        self._status_check = StatusAnswerCheck()
        self.boundary = MessageBoundary(f"gripper: {config.port}", self._status_check)

    @property
    def port(self) -> str:
        return self._config.port

    def start(self) -> "RobotiqModbusClient":
        """Starts the thread (opening the port happens there); returns at once."""
        if self._thread is not None:
            raise RuntimeError("RobotiqModbusClient already started")
        quiet_modbus_library()
        self._thread = threading.Thread(target=self._run, name=f"robotiq {self.port}",
                                        daemon=True)
        self._thread.start()
        return self

    def close(self, timeout: float = 2.0):
        """Stops the thread (within a transaction timeout) and closes the port."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.close()

    def set_command(self, command):
        """Requests [rPR, rSP, rFR] (bytes); sent with rACT = rGTO = 1 once active."""
        words = registers.command_registers_from_vector(command)
        with self._lock:
            self._command = words

    def latest_status(self) -> RobotiqStatusSample | None:
        """The newest status read, or None before the first."""
        with self._lock:
            return self._sample

    def counters(self) -> RobotiqModbusCounters:
        answers = self.boundary.counters()
        with self._lock:
            return dataclasses.replace(self._counters, errors=answers.rejected_total,
                                       last_error=answers.last_rejection,
                                       rejected=answers.rejected)

    @property
    def error(self) -> str | None:
        """Why the thread stopped (e.g. activation failed), or None."""
        with self._lock:
            return self._error

    @property
    def is_active(self) -> bool:
        """True once activation completed (gSTA = 3)."""
        return self._active.is_set()

    def wait_until_active(self, timeout: float, *,
                          configured_s: float | None = None) -> RobotiqStatusSample:
        """Blocks (start-up code, never in a diagram) until activation is complete; raises
        RobotiqActivationError with the thread's error, or on timeout. configured_s: the
        timeout the user set, said in the error, when `timeout` is what is left of it (the
        station's ready_timeout after the arm's wait)."""
        deadline = time.monotonic() + timeout
        while not self._active.wait(0.01):
            if self._finished.is_set() or time.monotonic() > deadline:
                raise RobotiqActivationError(self.error or self._not_active_words(
                    timeout if configured_s is None else configured_s))
        return self.latest_status()

    def _not_active_words(self, timeout: float) -> str:
        """Why the gripper is not active after `timeout` [s]: what was awaited, what came,
        and what to check."""
        sample, counters = self.latest_status(), self.counters()
        if sample is not None:
            seen = (f"gSTA = {int(sample.status[units.STATUS_STA])} in its last status, "
                    f"{device_fault_words(sample.status)}")
        elif counters.writes or counters.errors:
            seen = (f"no status read was accepted ({counters.writes} write(s) accepted, "
                    f"{counters.errors} transaction(s) failed; {self._last_refusal()})")
        else:
            seen = "it has not answered a request yet"
        return (f"Robotiq 2F-85 on {self.port} (slave {self._config.device_id}) not active "
                f"within {number_text(timeout)} s: waited for its status to report activation "
                f"complete (gSTA = {int(units.ActivationStatus.ACTIVE)}, no fault); {seen}. "
                f"Check the gripper's power, its RS-485 adapter on {self.port}, the Modbus "
                f"slave id ({self._config.device_id}) and the baud rate "
                f"({self._config.baudrate}); `tegrasp emulate all` runs the station without "
                "hardware")

    # --- the thread -------------------------------------------------------------------

    def _run(self):
        client = ModbusSerialClient(
            self._config.port, framer=FramerType.RTU, baudrate=self._config.baudrate,
            bytesize=8, parity="N", stopbits=1, timeout=self._config.request_timeout,
            retries=0)
        try:
            if not client.connect():
                raise RobotiqActivationError(f"cannot open serial port {self.port}")
            self._activate(client)
            self._loop(client)
        except Exception as exc:  # the thread must end quietly and say why
            with self._lock:
                self._error = str(exc)
        finally:
            client.close()
            self._finished.set()

    def _transaction(self, request, function: int, address: int, register_count: int,
                     **kwargs):
        """One request's checked answer and when the request was sent (time.monotonic() [s]),
        or None (counted by the boundary)."""
        sent = time.monotonic()
        try:
            response = request(address, device_id=self._config.device_id, **kwargs)
        except ModbusIOException:  # pymodbus's words for it hold a line break and advice of its own
            self.boundary.reject(NO_ANSWER, f"nothing came back to a function {function} "
                                 f"request within {number_text(self._config.request_timeout)} "
                                 "s (gripper.request_timeout)")
            return None
        except ModbusException as exc:
            self.boundary.reject(NO_ANSWER, str(exc))
            return None
        except Exception as exc:  # noqa: BLE001: bytes pymodbus could not make sense of
            self.boundary.reject(UNDECODABLE, f"{type(exc).__name__}: {exc}")
            return None
        checked = self.boundary.accept(response, function, address, register_count, sent,
                                       time.monotonic())
        return None if checked is None else (checked, sent)

    def _write(self, client, words) -> bool:
        ok = self._transaction(client.write_registers, 16, registers.COMMAND_ADDRESS,
                               len(words), values=words)
        if ok is not None:
            with self._lock:
                self._counters.writes += 1
        return ok is not None

    def _read(self, client) -> RobotiqStatusSample | None:
        read = (client.read_input_registers if self._config.read_function == 4
                else client.read_holding_registers)
        answer = self._transaction(read, self._config.read_function,
                                   registers.STATUS_ADDRESS, registers.REGISTER_COUNT,
                                   count=registers.REGISTER_COUNT)
        if answer is None:
            return None
        response, sent = answer
        status = registers.status_from_registers(response.registers)
        self._status_check.accepted(status, sent)
        with self._lock:
            self._counters.reads += 1
            self._sample = RobotiqStatusSample(status, time.monotonic(), self._counters.reads)
            return self._sample

    def _activate(self, client):
        reset = registers.command_registers(0, 0, 0, activate=False, go_to=False)
        activate = registers.command_registers(0, 0, 0, activate=True, go_to=False)
        deadline = time.monotonic() + self._config.activation_timeout
        for words in (reset, activate):
            while not self._write(client, words):
                if self._stop.wait(self._config.period) or time.monotonic() > deadline:
                    raise self._activation_error(f"the write of {words} was not accepted "
                                                 f"({self._last_refusal()})")
        last = None  # the last accepted status
        states = []  # each gSTA the accepted statuses gave, in order of first sight
        while not self._stop.wait(self._config.period):
            sample = self._read(client)
            last = sample.status if sample is not None else last
            if sample is not None and int(sample.status[units.STATUS_STA]) not in states:
                states.append(int(sample.status[units.STATUS_STA]))
            # A major fault stops the fingers until the next activation (manual, gFLT): the
            # gripper is at fault, not active, whatever gSTA says.
            if sample is not None and sample.status[units.STATUS_FLT] >= units.FIRST_MAJOR_FAULT:
                raise self._activation_error(f"the gripper reports a fault: "
                                             f"{device_fault_words(sample.status)}")
            if sample is not None and sample.status[units.STATUS_STA] == (
                    units.ActivationStatus.ACTIVE) and sample.status[units.STATUS_FLT] == 0:
                self._active.set()
                return
            if time.monotonic() > deadline:
                if last is None:
                    raise self._activation_error("no status read was accepted "
                                                 f"({self._last_refusal()})")
                refused = "" if sample is not None else (
                    f"; the last status read was refused, {self._last_refusal()}")
                seen = " then ".join(f"{state} ({units.ActivationStatus(state).name.lower()})"
                                     for state in states)
                raise self._activation_error(
                    f"its status never reported activation complete (gSTA = "
                    f"{int(units.ActivationStatus.ACTIVE)}, no fault) in "
                    f"{self.counters().reads} status read(s) answered, gSTA = {seen}; the "
                    f"last status {status_words(last)}{refused}", answered=True)

    def _last_refusal(self) -> str:
        """The last refused answer in words, under its reason (docs/hardware.md's)."""
        last = self.boundary.counters().last_rejection
        return f"the last refused: {last}" if last else "no answer was refused"

    def _activation_error(self, why, *, answered: bool = False) -> RobotiqActivationError:
        """`why`: what arrived; `answered`: whether the gripper answered status reads, which
        tells what to check."""
        config = self._config
        if answered:
            check = (f"the gripper's power (24 V), that the activation request reaches it "
                     f"(rACT = 1 written to register {registers.COMMAND_ADDRESS}: gACT 1 says it did, "
                     f"gACT 0 that it did not or was reset), that nothing blocks the fingers' "
                     f"stroke, and that the unit id gripper.device_id ({config.device_id}) is "
                     f"the 2F-85's, not another device's on the bus")
        else:
            check = (f"the gripper's power, its RS-485 adapter on {self.port}, the unit id "
                     f"gripper.device_id ({config.device_id}: a 2F-85 of another id does not "
                     f"answer) and gripper.baudrate ({config.baudrate})")
        return RobotiqActivationError(
            f"Robotiq 2F-85 on {self.port} (slave {config.device_id}) did not "
            f"activate within {number_text(config.activation_timeout)} s: {why}. Check {check}")

    def _loop(self, client):
        period = self._config.period
        next_time = time.monotonic()
        written, written_time = None, -np.inf
        while not self._stop.wait(max(0.0, next_time - time.monotonic())):
            now = time.monotonic()
            next_time += period
            if next_time < now:
                next_time = now + period
                with self._lock:
                    self._counters.overruns += 1
            with self._lock:
                command = self._command
            if command is not None and (
                    command != written
                    or now - written_time >= self._config.command_refresh_period):
                if self._write(client, command):
                    written, written_time = command, now
            self._read(client)
