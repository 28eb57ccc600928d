"""A watchdog that names the device that stopped talking, and since when, and stops the arm.
A device is silent when its `time_measured` has not changed for longer than its timeout
(Context time), with `startup_grace` more before it is first heard. A trip latches."""

import dataclasses
import time

from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.hardware.device_fault import SILENT, DeviceFault

# [s] several missed samples, short against the matcher's 0.5 s windows: arm five 100 Hz
# statuses; gripper 10-20 reads (its own comm-loss fault is 1 s); tactile 50 frames at 1 kHz.
DEFAULT_TIMEOUTS = {"arm": 0.050, "gripper": 0.100, "tactile": 0.050}


@dataclasses.dataclass(frozen=True)
class DeviceActivity:
    """When one device's time_measured last changed (None: never heard from)."""
    last_value: float | None = None
    since_sim_time: float = 0.0
    since_wall_time: float = 0.0
    fault: DeviceFault | None = None

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's copies of the Context's state can share it


class DeviceActivities(tuple):
    """The watchdog's state, ((device, DeviceActivity), ...); immutable, so Drake's 1 kHz
    Context copies share it."""

    def __deepcopy__(self, memo):
        return self


def next_activity(activity: DeviceActivity, value: float, *, device: str, timeout: float,
                  startup_grace: float, sim_time: float, wall_time: float) -> DeviceActivity:
    """The activity after seeing `value` at `sim_time`; trips (latched) once silent. A value
    of 0 before any other means "not heard from yet" (the receivers' initial output)."""
    if activity.fault is not None:
        return activity
    never_heard = activity.last_value is None
    if value != activity.last_value and not (never_heard and value == 0.0):
        return DeviceActivity(value, sim_time, wall_time)
    allowed = timeout + (startup_grace if never_heard else 0.0)
    if sim_time - activity.since_sim_time <= allowed:
        return activity
    description = ("never heard from" if never_heard else "no new data") + (
        f" for more than {allowed * 1e3:.0f} ms")
    return dataclasses.replace(activity, fault=DeviceFault(
        device, SILENT, description, since_sim_time=activity.since_sim_time,
        since_wall_time=activity.since_wall_time))


class DeviceWatchdog(LeafSystem):
    """Watches devices' `time_measured` [s, device clock]: one input per device of
    `timeouts`. fault: the silent devices (DeviceFault) in trip order; stop: 1 once any tripped.

    .. pydrake_system::

        name: DeviceWatchdog
        input_ports:
        - arm_time_measured
        - gripper_time_measured
        - tactile_time_measured
        output_ports:
        - fault
        - stop
    """

    def __init__(self, timeouts: dict[str, float] | None = None, *, period: float = 1e-3,
                 startup_grace: float = 1.0):
        super().__init__()
        self._timeouts = dict(timeouts or DEFAULT_TIMEOUTS)
        self._startup_grace = startup_grace
        self._ports = {device: self.DeclareVectorInputPort(f"{device}_time_measured", 1)
                       for device in self._timeouts}
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(
            DeviceActivities((device, DeviceActivity()) for device in self._timeouts)))
        self.DeclareInitializationUnrestrictedUpdateEvent(self._initialize)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        ticket = {self.abstract_state_ticket(self._state_index)}
        self.DeclareAbstractOutputPort("fault", lambda: AbstractValue.Make(()),
                                       self._calc_fault, prerequisites_of_calc=ticket)
        self.DeclareVectorOutputPort(
            "stop", 1, lambda context, out: out.SetAtIndex(0, bool(self._faults(context))),
            prerequisites_of_calc=ticket)

    def _activities(self, context) -> dict:
        return dict(context.get_abstract_state(self._state_index).get_value())

    def _faults(self, context) -> tuple:
        faults = [a.fault for a in self._activities(context).values() if a.fault]
        return tuple(sorted(faults, key=lambda fault: fault.since_sim_time))

    def _initialize(self, context, state):
        now = context.get_time()
        state.get_mutable_abstract_state(self._state_index).set_value(DeviceActivities(
            (device, DeviceActivity(None, now, time.time())) for device in self._timeouts))

    def _update(self, context, state):
        now, wall = context.get_time(), time.time()
        activities = DeviceActivities(
            (device, next_activity(activity, self._ports[device].Eval(context)[0],
                                   device=device, timeout=self._timeouts[device],
                                   startup_grace=self._startup_grace, sim_time=now,
                                   wall_time=wall))
            for device, activity in self._activities(context).items())
        state.get_mutable_abstract_state(self._state_index).set_value(activities)

    def _calc_fault(self, context, output):
        output.set_value(self._faults(context))
