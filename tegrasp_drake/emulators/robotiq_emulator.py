"""An emulated Robotiq 2F-85 answering Modbus RTU on a pseudo-terminal.

pymodbus's `ModbusSerialServer` serves a `SimDevice` (command registers 1000-1002,
read-only status 2000-2002) whose `action` hook runs `RobotiqGripperModel` on every access,
so a status read in the same transaction as a command already reflects it. pymodbus opens
its port by name and a pty has one named end, so server and driver sit on the two ends of a
`NullModem`; requests cross a ModbusRequestFramer on the way, as on a real receiver, which
itself answers one whose quantity is out of range (exception 03). What the model does:
docs/hardware.md, "The emulated 2F-85"."""

import asyncio
import dataclasses
import threading
import time

from pymodbus import FramerType
from pymodbus.server import ModbusSerialServer
from pymodbus.simulator import DataType, SimData, SimDevice

from tegrasp_drake.robotiq import units
from tegrasp_drake.robotiq import registers
from tegrasp_drake.emulators.modbus_request_framer import ModbusRequestFramer
from tegrasp_drake.emulators.null_modem import NullModem
from tegrasp_drake.hardware.message_boundary import MessageBoundary

ObjectStatus = units.ObjectStatus
ActivationStatus = units.ActivationStatus


@dataclasses.dataclass
class RobotiqEmulatorConfig:
    """Emulated gripper: its slave id, activation time [s], object width [m] pad to pad."""
    device_id: int = registers.DEVICE_ID
    activation_duration: float = 1.5  # a stand-in: clients wait for gSTA = 3, not a time
    object_opening: float | None = None


class RobotiqGripperModel:
    """The gripper's state and behaviour, advanced on every access (time.monotonic()) and
    thread-safe."""

    def __init__(self, config: RobotiqEmulatorConfig, now: float):
        self._config = config
        self._lock = threading.Lock()
        self._command = [0, 0, 0]
        self._status = dict(gACT=0, gGTO=0, gSTA=ActivationStatus.RESET,
                            gOBJ=ObjectStatus.MOVING, gFLT=0, gPR=0)
        self._position = units.POSITION_OPEN_BYTE
        self._target = self._position
        self._speed = 0.0
        self._activation_start = None
        self._object = (None if config.object_opening is None
                        else units.position_from_opening(config.object_opening))
        self._time = now

    def set_object_opening(self, opening_m: float | None, now: float):
        """Puts an object of this width between the pads, or removes it (None)."""
        with self._lock:
            self._advance(now)
            self._object = (None if opening_m is None
                            else units.position_from_opening(opening_m))
            if self._status["gOBJ"] == ObjectStatus.STOPPED_ON_CONTACT_CLOSING:
                self._status["gOBJ"] = ObjectStatus.MOVING

    def inject_fault(self, code: int, now: float):
        """Sets gFLT; a major fault (>= 0x0A) stops the fingers until reactivation."""
        with self._lock:
            self._advance(now)
            self._status["gFLT"] = int(code)

    def write(self, address: int, values, now: float):
        """A write of command registers (any of 1000-1002)."""
        offset = address - registers.COMMAND_ADDRESS
        if not (0 <= offset and offset + len(values) <= registers.REGISTER_COUNT):
            raise ValueError(
                f"command write of {len(values)} registers at {address} leaves registers "
                f"{registers.COMMAND_ADDRESS}-"
                f"{registers.COMMAND_ADDRESS + registers.REGISTER_COUNT - 1}: write within them")
        with self._lock:
            self._advance(now)
            self._command[offset:offset + len(values)] = [int(v) for v in values]
            self._apply(registers.decode_command_registers(self._command), now)

    def command(self) -> list[int]:
        """rPR, rSP, rFR [bytes] as last written."""
        with self._lock:
            fields = registers.decode_command_registers(self._command)
        return [fields["rPR"], fields["rSP"], fields["rFR"]]

    def status(self, now: float) -> list[float]:
        """The `gripper.status` vector now."""
        with self._lock:
            self._advance(now)
            s = self._status
            moving = s["gOBJ"] == ObjectStatus.MOVING and s["gGTO"] and self._can_move()
            # Stopped, the screw holds: no current (the manual's finished grasp reads 0x00).
            current = units.current_byte(0.0, moving=moving)
            vector = [0.0] * units.STATUS_SIZE
            vector[units.STATUS_ACT] = s["gACT"]
            vector[units.STATUS_GTO] = s["gGTO"]
            vector[units.STATUS_STA] = int(s["gSTA"])
            vector[units.STATUS_OBJ] = int(s["gOBJ"])
            vector[units.STATUS_FLT] = s["gFLT"]
            vector[units.STATUS_PR] = s["gPR"]
            vector[units.STATUS_PO] = round(self._position)
            vector[units.STATUS_CU] = round(current)
            return vector

    def _can_move(self) -> bool:
        return (self._status["gSTA"] == ActivationStatus.ACTIVE
                and self._status["gFLT"] < units.FIRST_MAJOR_FAULT)

    def _apply(self, command: dict, now: float):
        s = self._status
        if not command["rACT"]:
            s.update(gACT=0, gGTO=0, gSTA=ActivationStatus.RESET, gOBJ=ObjectStatus.MOVING,
                     gFLT=units.FAULT_NOT_ACTIVATED if command["rGTO"] else 0)
            self._activation_start = None
            return
        if not s["gACT"]:
            s.update(gACT=1, gSTA=ActivationStatus.ACTIVATING, gFLT=0)
            self._activation_start = now
        if not command["rGTO"]:
            s["gGTO"] = 0
            return
        if s["gSTA"] != ActivationStatus.ACTIVE:
            # Carried out when activation completes, as the manual's 0x05 says.
            s["gFLT"] = max(s["gFLT"], units.FAULT_ACTION_DELAYED)
            return
        self._go_to(command)

    def _go_to(self, command: dict):
        """rGTO = 1 while activated: gGTO echoes it and the fingers head for rPR."""
        s = self._status
        if not s["gGTO"] or command["rPR"] != s["gPR"]:
            s["gOBJ"] = ObjectStatus.MOVING
        s.update(gGTO=1, gPR=command["rPR"])
        self._target = min(max(float(command["rPR"]), units.POSITION_OPEN_BYTE),
                           units.POSITION_CLOSED_BYTE)
        self._speed = units.position_bytes_per_second(command["rSP"])

    def _advance(self, now: float):
        """Integrates the finger motion from the last access to `now`."""
        dt, self._time = max(now - self._time, 0.0), max(now, self._time)
        s = self._status
        if s["gSTA"] == ActivationStatus.ACTIVATING:
            completed_at = self._activation_start + self._config.activation_duration
            if now < completed_at:
                return
            s["gSTA"] = ActivationStatus.ACTIVE
            self._position = self._target = units.POSITION_OPEN_BYTE
            if s["gFLT"] == units.FAULT_ACTION_DELAYED:
                s["gFLT"] = 0
            command = registers.decode_command_registers(self._command)
            if command["rGTO"]:
                self._go_to(command)
            dt = min(dt, now - completed_at)  # the fingers move from completion on
        if not (s["gGTO"] and s["gOBJ"] == ObjectStatus.MOVING and self._can_move()):
            return
        closing = self._target > self._position
        step = min(abs(self._target - self._position), self._speed * dt)
        new_position = self._position + (step if closing else -step)
        if (closing and self._object is not None
                and self._position <= self._object <= new_position):
            self._position = self._object
            s["gOBJ"] = ObjectStatus.STOPPED_ON_CONTACT_CLOSING
        else:
            self._position = new_position
            if self._position == self._target:
                s["gOBJ"] = ObjectStatus.AT_REQUESTED_POSITION


class RobotiqEmulator:
    """Serves `RobotiqGripperModel` over Modbus RTU on `port`; start and stop with a `with` block;
    `disconnect()` silences the gripper, `reconnect()` brings it back."""

    def __init__(self, config: RobotiqEmulatorConfig | None = None):
        self._config = dataclasses.replace(config or RobotiqEmulatorConfig())
        self.model = RobotiqGripperModel(self._config, time.monotonic())
        self._cable = None
        self._loop = None
        self._thread = None
        self._stop_serving = None
        self._ready = threading.Event()
        self._error = None
        self.request_boundary = MessageBoundary("robotiq: Modbus requests")
        self._framer = ModbusRequestFramer(self.request_boundary, address=self._config.device_id,
                                           answer=lambda reply: self._cable.answer_host(reply))

    @property
    def port(self) -> str:
        """The tty name the driver opens."""
        return self._cable.host_port

    def set_object_opening(self, opening_m: float | None):
        self.model.set_object_opening(opening_m, time.monotonic())

    def inject_fault(self, code: int):
        self.model.inject_fault(code, time.monotonic())

    def disconnect(self):
        self._cable.connected = False

    def reconnect(self):
        self._cable.connected = True

    def start(self, timeout: float = 5.0) -> "RobotiqEmulator":
        self._cable = NullModem(to_device=lambda data: b"".join(self._framer.feed(data)))
        self._thread = threading.Thread(target=self._serve, name="robotiq emulator",
                                        daemon=True)
        self._thread.start()
        if not self._ready.wait(timeout) or self._error:
            self.stop()
            raise RuntimeError(f"Robotiq emulator did not start: {self._error}")
        return self

    def stop(self, timeout: float = 5.0):
        if self._loop is not None and self._stop_serving is not None:
            self._loop.call_soon_threadsafe(self._stop_serving.set)
        if self._thread is not None:
            self._thread.join(timeout)
        if self._cable is not None:
            self._cable.close()

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()

    def _serve(self):
        self._loop = asyncio.new_event_loop()
        try:
            self._loop.run_until_complete(self._serve_async())
        except Exception as exc:  # reported by start()
            self._error = repr(exc)
            self._ready.set()
        finally:
            self._loop.close()

    async def _serve_async(self):
        self._stop_serving = asyncio.Event()
        device = SimDevice(self._config.device_id, simdata=[
            SimData(registers.COMMAND_ADDRESS, count=registers.REGISTER_COUNT, values=0,
                    datatype=DataType.REGISTERS),
            SimData(registers.STATUS_ADDRESS, count=registers.REGISTER_COUNT, values=0,
                    datatype=DataType.REGISTERS, readonly=True),
        ], action=self._on_access)
        server = ModbusSerialServer(device, framer=FramerType.RTU, port=self._cable.device_port,
                                    baudrate=registers.BAUDRATE)
        await server.serve_forever(background=True)
        self._ready.set()
        await self._stop_serving.wait()
        await server.shutdown()

    async def _on_access(self, function_code, start_address, address, count, current,
                         set_values):
        """pymodbus `SimDevice.action`: runs the model on every request."""
        now = time.monotonic()
        if set_values is not None:
            self.model.write(address, set_values, now)
        elif address + count > registers.STATUS_ADDRESS:
            first = registers.STATUS_ADDRESS - start_address
            current[first:first + registers.REGISTER_COUNT] = registers.status_registers(
                self.model.status(now))
        return None
