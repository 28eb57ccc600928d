"""A named fault reported by a driver or by the device watchdog: which device, what (with
the device's own code where it has one) and since when, on both clocks (Context time and
wall time, to match operator logs). The state machine reports `str(fault)` on Failed."""

import dataclasses
import datetime

# Kinds of fault.
SILENT = "silent"            # the device stopped talking (watchdog)
DEVICE_FAULT = "device"      # the device reported a fault code (e.g. Robotiq gFLT)
DRIVER_ERROR = "driver"      # the driver could not bring the device up (e.g. activation)
IMPLAUSIBLE = "implausible"  # the device's data cannot be true (its clock outruns the host's)
KINDS = (SILENT, DEVICE_FAULT, DRIVER_ERROR, IMPLAUSIBLE)
# The devices a fault names: the watchdog's (watchdog.DEFAULT_TIMEOUTS) and the gripper
# driver's (RobotiqDriver's `device`).
DEVICES = ("arm", "gripper", "tactile")
NO_CODE = -1  # a fault's `code` when the device gave none (all but DEVICE_FAULT)


@dataclasses.dataclass(frozen=True)
class DeviceFault:
    """One fault of one device; `code` the device's fault code or -1; `since_*` the last good
    data (SILENT) or the first sighting, as Context time and time.time() [s]."""
    device: str
    kind: str
    description: str
    code: int = NO_CODE
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
    """Every fault on one line, "; " between them, or "no fault": the text the station's
    device-fault port carries, which the state machine writes as a Failed transition's
    reason (one timeline line)."""
    return "; ".join(str(fault) for fault in faults) if faults else "no fault"
