"""The Robotiq 2F-85 over Modbus RTU as a Drake system with the simulated gripper's ports:
periodic events hand `command` to the RobotiqModbusClient's thread and copy its newest
status into the Context, never waiting on the serial line. `fault` names a nonzero gFLT (the
manual's name) or the client's error."""

import dataclasses
import time

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.robotiq import units
from tegrasp_drake.hardware.device_fault import DEVICE_FAULT, DRIVER_ERROR, DeviceFault
from tegrasp_drake.hardware.state_outputs import declare_scalar_state_outputs


@dataclasses.dataclass(frozen=True)
class RobotiqDriverState:
    """The newest status and what it means, kept in the Context."""
    status: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(units.STATUS_SIZE))
    arrival_time: float = 0.0   # time.monotonic() [s]; 0 before the first status
    count: int = 0              # the client's status count of `status`
    stale: bool = True
    faults: tuple = ()

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's copies of the Context's state can share it


def gripper_faults(status, count: int, driver_error: str | None, previous: tuple, *,
                   device: str, sim_time: float, wall_time: float) -> tuple:
    """The faults now (a fault already present keeps its `since`)."""
    found = []
    if driver_error:
        found.append(DeviceFault(device, DRIVER_ERROR, driver_error))
    code = int(status[units.STATUS_FLT]) if count > 0 else 0
    if code:
        found.append(DeviceFault(device, DEVICE_FAULT, units.fault_name(code), code))
    since = {(f.kind, f.code): f for f in previous}
    return tuple(
        since.get((f.kind, f.code)) or dataclasses.replace(
            f, since_sim_time=sim_time, since_wall_time=wall_time)
        for f in found)


class RobotiqDriver(LeafSystem):
    """Wraps a started `RobotiqModbusClient` (module docstring). command: (3) [rPR, rSP, rFR]
    bytes, nothing sent while unconnected; status: (8) [gACT, gGTO, gSTA, gOBJ, gFLT, gPR, gPO,
    gCU]; time_measured: host time.monotonic() [s] of its arrival (0 before); stale: 1 when
    older than `stale_timeout` [s]; fault: tuple of DeviceFault, empty when all is well.

    .. pydrake_system::

        name: RobotiqDriver
        input_ports:
        - command (optional)
        output_ports:
        - status
        - time_measured
        - stale
        - fault
    """

    def __init__(self, client, *, period: float = 0.005, stale_timeout: float = 0.1,
                 device: str = "gripper"):
        super().__init__()
        self._client = client
        self._stale_timeout = stale_timeout
        self._device = device
        self._command_port = self.DeclareVectorInputPort("command", units.COMMAND_SIZE)
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(RobotiqDriverState()))
        self.DeclarePeriodicPublishEvent(period, 0.0, self._send_command)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        ticket = {self.abstract_state_ticket(self._state_index)}
        self.DeclareVectorOutputPort(
            "status", units.STATUS_SIZE,
            lambda context, out: out.SetFromVector(self._state(context).status),
            prerequisites_of_calc=ticket)
        declare_scalar_state_outputs(self, self._state_index, {
            "time_measured": lambda state: state.arrival_time,
            "stale": lambda state: state.stale})
        self.DeclareAbstractOutputPort(
            "fault", lambda: AbstractValue.Make(()),
            lambda context, out: out.set_value(self._state(context).faults),
            prerequisites_of_calc=ticket)

    @property
    def client(self):
        return self._client

    def _state(self, context) -> RobotiqDriverState:
        return context.get_abstract_state(self._state_index).get_value()

    def _send_command(self, context):
        if self._command_port.HasValue(context):
            self._client.set_command(self._command_port.Eval(context))

    def _update(self, context, state):
        old = self._state(context)
        sample = self._client.latest_status()
        status, arrival, count = old.status, old.arrival_time, old.count
        if sample is not None and sample.count != old.count:
            status, arrival, count = sample.status.copy(), sample.arrival_time, sample.count
        new = RobotiqDriverState(
            status=status, arrival_time=arrival, count=count,
            stale=count == 0 or time.monotonic() - arrival > self._stale_timeout,
            faults=gripper_faults(status, count, self._client.error, old.faults,
                                  device=self._device, sim_time=context.get_time(),
                                  wall_time=time.time()))
        state.get_mutable_abstract_state(self._state_index).set_value(new)
