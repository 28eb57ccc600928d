"""Emulated devices on this shared, loaded, not real-time host (no tests here): the
hardware-in-the-loop tests and the tests of `tegrasp hardware`'s own output share this.

pty data from the emulators can arrive 50-100 ms late when the host is loaded, past the
real devices' 50-100 ms watchdog timeouts, so a run against the emulators would fault on a
busy machine for reasons that are the host's, not the code's. Tests that are not about the
watchdog give it LOADED_HOST_WATCHDOG_S instead (the fault tests measure the reaction after
the timeout, whatever it is)."""

from tegrasp_drake.emulators.launcher import EMULATED_WATCHDOG_TIMEOUT_S

# What `tegrasp emulate --write-config` gives each emulated device, for the same reason.
LOADED_HOST_WATCHDOG_S = EMULATED_WATCHDOG_TIMEOUT_S


def tolerate_a_loaded_host(config):
    """Sets the arm, gripper and tactile watchdog timeouts of a HardwareStationConfig to
    LOADED_HOST_WATCHDOG_S [s]; returns the config."""
    watchdog = config.watchdog
    watchdog.arm_timeout = watchdog.gripper_timeout = LOADED_HOST_WATCHDOG_S
    watchdog.tactile_timeout = LOADED_HOST_WATCHDOG_S
    return config
