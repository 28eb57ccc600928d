"""Bad inputs found by the seventh hostile pass: a closed output pipe ends any command quietly,
and ranges start at a plausible physical minimum instead of an open zero."""

import io
import os

import pytest

from tegrasp_drake import cli


def _closed_pipe_stream() -> io.TextIOWrapper:
    """A buffered text stream on a pipe whose reader has gone (`tegrasp ... | head`)."""
    read, write = os.pipe()
    os.close(read)
    return io.TextIOWrapper(io.BufferedWriter(io.FileIO(write, "w"), buffer_size=1 << 16),
                            encoding="utf-8")


@pytest.mark.parametrize("argv, closed", [
    (["--help"], "stdout"),
    (["sweep", "--help"], "stdout"),
    (["trial", "--no-such-option"], "stderr"),  # argparse's usage error
])
def test_a_closed_output_pipe_ends_the_command_quietly(monkeypatch, argv, closed):
    stream = _closed_pipe_stream()
    monkeypatch.setattr(cli.sys, closed, stream)
    other = "stderr" if closed == "stdout" else "stdout"
    monkeypatch.setattr(cli.sys, other, io.StringIO())
    try:
        assert cli.main(argv) == cli.EXIT_CLOSED_PIPE
        stream.flush()  # what Python does at exit: nothing left to report
    finally:
        stream.close()
    assert "Traceback" not in getattr(cli.sys, other).getvalue()


@pytest.mark.parametrize("override, words", [
    ("object.mass=1.0e-9", "field 'object.mass' must lie in [0.01, 5] kg"),
    ("object.mass=1e-30", "field 'object.mass' must lie in [0.01, 5] kg"),  # read as a number
    ("object.size=[1.0e-4,1.0e-4,0.11]", "field 'object.size[0]' must lie in [0.005, 0.5] m"),
])
def test_a_tiny_object_is_refused_before_drake_sees_it(override, words):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    with pytest.raises(ConfigError) as error:
        LoadScenario(name="box", overrides=[override])
    assert words in str(error.value)


def test_the_smallest_object_is_one_the_contact_geometry_resolves():
    from tegrasp_drake.rig.objects import MIN_SIZE_M
    from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y
    from tegrasp_drake.simulation.object_model import MESH_RESOLUTION_M
    assert MESH_RESOLUTION_M <= MIN_SIZE_M <= min(CELL_X, CELL_Y)


# Every range that stops at an open 0, decided by its physics: a tiny positive value of these
# is harmless. Times [s]: a simulated one shorter than the plant step is refused
# (check_times_resolved), a device timeout that short fails at once naming the device. Speeds,
# forces and fractions: a tiny one makes a slow or failed grasp the trial reports (tried at
# 1e-9: grip_force, gripper acceleration). Filter corners (slip band, load low-pass): a tiny
# one makes a vanishing signal (a test turns the load channel off with a 1e-3 Hz corner).
# Contact: Drake's point contact and regularized friction ran at 1e-9 m and 1e-12 m/s. The
# integrator's accuracy and largest step: the diagram is discrete (ran at 1e-12 and 1e-9 s).
# The others have a plausible physical minimum instead (object mass, size and friction; the
# fingertip's mode, mass and stiffness; the amplifier's capacitor, swing, corner and rate; the
# pad texture, pad friction, the 2F-85's 20 N grip; the taxels' calibration weight and gap;
# the gains and rates: the servos' and the tracker's gains, the film's charge gain, the arm's
# command and the gripper's update rates).
TINY_IS_HARMLESS = {
    "ArmDriverConfig": {"command_latency_s", "control_period_s"},
    "DeviceWatchdogConfig": {"arm_timeout", "gripper_timeout", "tactile_timeout"},
    "DisturbanceConfig": {"hit_duration_s"},
    "DriveVibrationConfig": {"full_speed"},
    "FilmConfig": {"load_lowpass_hz"},
    "FingerStrikeConfig": {"force_n"},
    "FixedLoadTimeControllerConfig": {"load_event_timeout_s", "load_time_s", "update_period_s"},
    "GraspScriptConfig": {"lift_s", "load_s", "place_s", "reach_s", "retract_s",
                          "unload_s"},
    "GripperDriverConfig": {"acceleration", "stall_speed"},
    "HardwareStationConfig": {"ready_timeout"},
    "HeuristicControllerConfig": {"load_event_timeout_s", "update_period_s"},
    "HeuristicTriggerConfig": {"grip_fraction"},
    "JacoVelocityTrackerConfig": {"max_joint_speed"},
    "LiftLoadConfig": {"grip_fraction", "slip_band_hz", "slip_window_s"},
    "MemorizedControllerConfig": {"load_event_timeout_s", "update_period_s"},
    "MultibodyPlantConfig": {"penetration_allowance", "stiction_tolerance"},
    "PlaceConfig": {"event_timeout_s"},
    "ReReachConfig": {"reach_event_timeout_s"},
    "RobotiqModbusConfig": {"activation_timeout", "command_refresh_period", "request_timeout"},
    "SerialTactileDriver": {"stale_timeout"},
    "SimulatorConfig": {"accuracy", "max_step_size"},
    "TaxelAwareControllerConfig": {"load_event_timeout_s", "update_period_s"},
}


def _open_zero_ranges(*roots) -> dict[str, set[str]]:
    """{class name: its fields whose Range is (0, ...]}, of every config reachable from `roots`."""
    import dataclasses
    import typing

    from tegrasp_drake.rig.ranges import Range, _config_classes, declared_ranges, range_of
    found, seen, pending = {}, set(), list(roots)
    while pending:
        cls = pending.pop()
        if cls in seen:
            continue
        seen.add(cls)
        if dataclasses.is_dataclass(cls):
            hints = typing.get_type_hints(cls)
            ranges = {f.name: range_of(f) for f in dataclasses.fields(cls)}
            for field in dataclasses.fields(cls):
                pending.extend(_config_classes(hints[field.name]))
        else:
            ranges = declared_ranges(cls)
        for name, declared in ranges.items():
            if isinstance(declared, Range) and declared.low == 0 and declared.low_open:
                found.setdefault(cls.__name__, set()).add(name)
    return found


def test_every_range_open_at_zero_was_decided_by_its_physics():
    from tegrasp_drake.hardware.config import HardwareStationConfig
    from tegrasp_drake.scenario.scenario import Scenario
    assert _open_zero_ranges(Scenario, HardwareStationConfig) == TINY_IS_HARMLESS, (
        "a setting whose range stops at an open 0: give it a plausible minimum (bounded(low=..., "
        "why=...)) or, if a tiny value is harmless, say why here")
