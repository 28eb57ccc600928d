"""A named fault reported by a driver or by the device watchdog.

The controller's state machine goes to Failed on any fault and reports `str(fault)`, so a
fault carries which device, what went wrong (with the device's own code where it has one)
and since when, on both clocks: simulation time [s] (the diagram's Context time) and wall
time [s since the epoch] (for matching against operator logs).
"""

import dataclasses
import datetime

# Kinds of fault.
SILENT = "silent"            # the device stopped talking (watchdog)
DEVICE_FAULT = "device"      # the device reported a fault code (e.g. Robotiq gFLT)
DRIVER_ERROR = "driver"      # the driver could not bring the device up (e.g. activation)


@dataclasses.dataclass(frozen=True)
class DeviceFault:
    """One fault of one device.

    Attributes:
        device: the device name ("arm", "gripper", "tactile").
        kind: SILENT, DEVICE_FAULT or DRIVER_ERROR.
        description: human-readable cause, e.g. the Robotiq manual's name of a gFLT code.
        code: the device's fault code, or -1 when it has none.
        since_sim_time: Context time [s] of the last good data (SILENT) or of the first
            sighting of the fault.
        since_wall_time: the same instant as `time.time()` [s since the epoch].
    """
    device: str
    kind: str
    description: str
    code: int = -1
    since_sim_time: float = 0.0
    since_wall_time: float = 0.0

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's copies of the Context's state can share it

    def __str__(self) -> str:
        wall = datetime.datetime.fromtimestamp(self.since_wall_time).isoformat(
            timespec="milliseconds")
        code = f" (code 0x{self.code:02X})" if self.code >= 0 else ""
        return (f"{self.device}: {self.kind}{code}: {self.description}; since t = "
                f"{self.since_sim_time:.3f} s (wall {wall})")


def describe_faults(faults) -> str:
    """One line per fault, or "no fault"."""
    return "\n".join(str(fault) for fault in faults) if faults else "no fault"
