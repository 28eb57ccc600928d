"""Every numeric setting declares its unit and range beside its field (rig/ranges.py); one
validator enforces them where a config is loaded and again where a builder is handed one."""

import dataclasses
import typing

import pytest

from tests.bad_input.probes import assert_one_line_error, run_cli
from tegrasp_drake.control import controller_registry
from tegrasp_drake.control.controller_config import AvoidConfig
from tegrasp_drake.events import EventMatcherConfig
from tegrasp_drake.events.synthetic import SyntheticGraspConfig
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.ranges import Range, bounded, check_ranges, unranged_numeric_fields
from tegrasp_drake.rig.typed_yaml import ConfigError, read_yaml_file
from tegrasp_drake.scenario.scenario import LoadScenario, Scenario
from tegrasp_drake.sweep.spec import SweepSpec
from tegrasp_drake.transfer.matrix import TransferSpec

CONFIG_ROOTS = (Scenario, HardwareStationConfig, SweepSpec, TransferSpec,
                *(type(controller_registry.controller_named(name))
                  for name in controller_registry.CONTROLLER_NAMES))


def test_every_numeric_field_declares_its_range():
    """Fails naming each int or float field (or list of them) reachable from a scenario, a
    hardware config, a sweep or a transfer spec that has no `bounded(...)` declaration."""
    missing = unranged_numeric_fields(*CONFIG_ROOTS)
    assert not missing, ("declare a range beside each of these fields, e.g. "
                         "`x_s: float = bounded(0.5, low=0.0, high=10.0, unit=\"s\", "
                         f"why=\"...\")` (tegrasp_drake/rig/ranges.py): {missing}")


def _reachable_config_classes(*roots) -> set:
    """The dataclasses reachable from `roots` through their fields (unions, lists, maps)."""
    seen, pending = set(), list(roots)
    while pending:
        cls = pending.pop()
        if cls in seen or not dataclasses.is_dataclass(cls):
            continue
        seen.add(cls)
        for hint in typing.get_type_hints(cls).values():
            stack = [hint]
            while stack:
                member = stack.pop()
                stack.extend(typing.get_args(member))
                if dataclasses.is_dataclass(member):
                    pending.append(member)
    return seen


def test_a_ranges_own_words_for_a_low_value_agree_with_its_low_end():
    """A Range's `below` replaces the words for a value under its low end: a low end of 0
    that is open (0 refused) is never told "zero or positive", a closed one never "positive"
    (slip_window_s said "must be zero or positive" of the 0 it refused)."""
    from tegrasp_drake.rig.ranges import range_of
    classes = _reachable_config_classes(*CONFIG_ROOTS, SyntheticGraspConfig, EventMatcherConfig)
    wrong = []
    for cls in classes:
        for field in dataclasses.fields(cls):
            declared = range_of(field)
            if not isinstance(declared, Range) or not declared.below or declared.low != 0:
                continue
            says_zero_is_fine = "zero or" in declared.below or "non-negative" in declared.below
            if (declared.low_open and says_zero_is_fine) or (
                    not declared.low_open and "must be positive" in declared.below):
                wrong.append(f"{cls.__name__}.{field.name}: {declared.below!r}")
    assert not wrong, wrong


def test_no_config_class_holds_more_than_15_fields():
    """A config class nests its settings by concern rather than growing flat."""
    classes = _reachable_config_classes(*CONFIG_ROOTS, SyntheticGraspConfig, EventMatcherConfig)
    assert {Scenario, AvoidConfig, VibrationSensorConfig} <= classes
    crowded = {cls.__qualname__: len(dataclasses.fields(cls)) for cls in classes
               if len(dataclasses.fields(cls)) > 15}
    assert not crowded, crowded


@pytest.mark.parametrize("name", sorted(read_yaml_file(paths.scenarios_file(), "scenarios",
                                                    kind=None)))
def test_every_built_in_scenario_lies_in_its_ranges(name):
    check_ranges(LoadScenario(name=name), name)


def test_every_default_lies_in_its_range():
    for root in (Scenario, HardwareStationConfig, SweepSpec):
        check_ranges(root(), root.__name__)


def test_a_range_names_the_field_its_unit_and_why():
    @dataclasses.dataclass
    class Inner:
        hold_s: float = bounded(3.0, low=0.0, high=60.0, unit="s", why="a minute at most")
        sizes: list[float] = bounded(default_factory=lambda: [0.1], low=0.0, low_open=True,
                                     high=0.5, unit="m", below="must be positive [m]")

    @dataclasses.dataclass
    class Outer:
        inner: Inner = dataclasses.field(default_factory=Inner)
        seed: int = bounded(0, low=0, high=2**32 - 1)
    config = Outer()
    config.inner.hold_s = 1e7
    with pytest.raises(ConfigError, match=r"^here: field 'inner.hold_s' must lie in \[0, 60\] s "
                       r"\(a minute at most\), got 10000000.0$"):
        check_ranges(config, "here")
    config.inner.hold_s, config.inner.sizes = 3.0, [0.1, -0.2]
    with pytest.raises(ConfigError, match=r"field 'inner.sizes\[1\]' must be positive \[m\]"):
        check_ranges(config, "here")
    config.inner.sizes, config.seed = [0.1], 2**32
    with pytest.raises(ConfigError, match=r"must lie in \[0, 4294967295\], got 4294967296"):
        check_ranges(config, "here")
    config.seed = "7"
    with pytest.raises(ConfigError, match="field 'seed' must be a finite number, got str '7'"):
        check_ranges(config, "here")
    assert unranged_numeric_fields(Outer) == []


def test_an_undeclared_numeric_field_is_listed():
    @dataclasses.dataclass
    class NewDrive:
        gear_ratio: float = 1.0
        name: str = "drive"
        rated_n: float = bounded(10.0, low=0.0, high=100.0)
    assert unranged_numeric_fields(NewDrive) == [f"{__name__}.{NewDrive.__qualname__}.gear_ratio"]


def test_open_and_closed_ends():
    assert Range(0.0, 1.0, low_open=True).contains(0.5)
    assert not Range(0.0, 1.0, low_open=True).contains(0.0)
    assert Range(0.0, 1.0).contains(1.0) and not Range(0.0, 1.0, high_open=True).contains(1.0)
    assert Range(0.0, None).words(-1) == "must be at least 0"


# --- the probes: each a one-line error naming the field -------------------------------

@pytest.mark.parametrize("overrides, expected", [
    (["grasp.hold_s=1.0e+7"], "field 'grasp.hold_s' must lie in [0, 60] s"),
    (["grasp.hold_s=-1"], "field 'grasp.hold_s' must lie in [0, 60] s"),
    (["placement.offset=[2,2]"], "field 'placement.offset[0]' must lie in [-0.2, 0.2] m"),
    (["placement.expected_xy=[0.9,0.49]"], "field 'placement.offset' puts the object at "
     "(0.900, 0.490) m"),
    (["object.size=[0.045,0.045,50]"], "field 'object.size[2]' must lie in [0.005, 0.5] m"),
    (["object.mass=1.0e+9"], "field 'object.mass' must lie in [0.01, 5] kg"),
    (["object.friction=1.0e+9"], "field 'object.friction' must lie in [0.005, 2]"),
    (["grasp.grip_force=1.0e+9"], "field 'grasp.grip_force' must lie in [20, 235] N"),
    (["grasp.close_speed=0"], "field 'grasp.close_speed' must lie in [0.02, 0.15] m/s"),
    (["grasp.hold_s=50", "grasp.lift_s=20"], "field 'grasp': the grasp script lasts"),
    (["object.mass=1e9"], "field 'object.mass' must lie in [0.01, 5] kg"),  # a number
    (["object.mass='1e9'"], "got str '1e9' (YAML reads it as text: write 1000000000.0)"),
    (["controller.update_period_s=0"], "field 'controller.update_period_s' must be positive"),
    (["controller.lift_load.slip_s=-1"], "field 'controller.lift_load.slip_s' must be zero or positive [s]"),
    (["arm.initial_gripper_xyz=[0.69,0.0,7]"],
     "field 'arm.initial_gripper_xyz[2]' must lie in [-0.9, 0.9] m"),
])
def test_an_out_of_range_scenario_value_is_one_line(overrides, expected, capfd):
    argv = ["trial"]
    for assignment in overrides:
        argv += ["--set", assignment]
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, expected)


def test_a_long_script_is_accepted_when_confirmed():
    overrides = ["grasp.hold_s=50", "grasp.lift_s=20"]
    with pytest.raises(ConfigError, match="--allow-long"):
        LoadScenario(name="box", overrides=overrides)
    assert LoadScenario(name="box", overrides=overrides, allow_long=True).grasp.hold_s == 50


@pytest.mark.parametrize("text, expected", [
    ("ready_timeout: 1.0e+9\n", "field 'ready_timeout' must lie in [1.13333, 600] s"),
    ("gripper: {device_id: 0}\n", "field 'gripper.device_id' must lie in [1, 247]"),
    ("realtime_priority: 100\n", "field 'realtime_priority' must lie in [1, 99]"),
    ("arm: {tracker: {max_joint_speed: [1, 1, 1, 1, 1, 1]}}\n",
     "field 'arm.tracker.max_joint_speed[0]' must lie in (0, 0.837758] rad/s"),
])
def test_an_out_of_range_hardware_value_is_one_line(text, expected, tmp_path, capfd):
    config = tmp_path / "hw.yaml"
    config.write_text(text)
    code, output = run_cli(["hardware", "--config", str(config)], capfd)
    assert_one_line_error(code, output, str(config), expected)


@pytest.mark.parametrize("text, expected", [
    ("randomisation: {placement_xy_bound_m: 5}\n",
     "field 'randomisation.placement_xy_bound_m' must lie in [0, 0.05] m"),
    ("grid: [[0.0, 3.0]]\n", "field 'grid[0][1]' must lie in [-0.2, 0.2] m"),
    ("base_seed: 4294967296\n", "field 'base_seed' must lie in [0, 4294967295]"),
])
def test_an_out_of_range_sweep_value_is_one_line(text, expected, tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text(text)
    code, output = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, output, str(spec), expected)
    assert not (tmp_path / "o").exists()


# --- a config changed after loading is caught where a builder is handed it ---------------------

def test_a_config_changed_after_loading_is_refused_by_the_builders():
    from tegrasp_drake import MakeGraspDiagram, MakeStation, run_trial
    scenario = LoadScenario(name="box")
    scenario.object.mass = -1.0
    for build, name in ((MakeStation, "MakeStation"), (MakeGraspDiagram, "MakeGraspDiagram"),
                        (run_trial, "run_trial")):
        with pytest.raises(ConfigError, match=rf"^{name}: scenario: field 'object.mass' must be "
                           r"positive \(the object's mass \[kg\]\), got -1.0$"):
            build(scenario)
    scenario.object.mass = 0.15
    scenario.grasp.hold_s = 1e7
    with pytest.raises(ConfigError, match="field 'grasp.hold_s' must lie in"):
        MakeStation(scenario)


def test_a_hardware_config_changed_after_loading_is_refused():
    from tegrasp_drake import MakeHardwareStation
    config = HardwareStationConfig()
    config.watchdog.arm_timeout = -5.0
    with pytest.raises(ConfigError, match=r"^MakeHardwareStation: config: field "
                       r"'watchdog.arm_timeout' must lie in \(0.02, 10\] s"):
        MakeHardwareStation(config)


# A gain or rate next to zero (1e-300, 1e-9 Hz) is no setting a device runs at: each declares
# a low its range's words give the reason for.
@pytest.mark.parametrize("override, words", [
    ("arm.position_gain=1e-300", "field 'arm.position_gain' must lie in [40, 100000] N m/rad"),
    ("arm.tracker.kp=1e-300", "field 'arm.tracker.kp' must lie in [0.1, 100] 1/s"),
    ("arm.command_rate_hz=1", "field 'arm.command_rate_hz' must lie in [16, 1000] Hz"),
    ("gripper.position_gain=1e-300", "field 'gripper.position_gain' must lie in [300,"),
    ("gripper.update_rate_hz=1e-9", "field 'gripper.update_rate_hz' must lie in [80, 1000] Hz"),
    ("vibration.film.film_charge_gain_c_per_m=1e-300",
     "field 'vibration.film.film_charge_gain_c_per_m' must lie in [5e-07, 0.01] C/m"),
])
def test_a_gain_or_rate_near_zero_is_refused_naming_its_low(override, words):
    with pytest.raises(ConfigError) as refused:
        LoadScenario(name="box", overrides=[override])
    assert words in str(refused.value) and "\n" not in str(refused.value), str(refused.value)


@pytest.mark.parametrize("field", ["sa_rate_hz", "ra_rate_hz"])
def test_a_matcher_or_event_rate_too_slow_for_the_window_is_refused(field):
    import numpy as np

    from tegrasp_drake.events.event_matcher import check_matcher_config
    from tegrasp_drake.events.memorized_event import MemorizedEvent
    with pytest.raises(ConfigError, match=rf"field '{field}' must lie in \[16, 20000\] Hz"):
        check_matcher_config(EventMatcherConfig(**{field: 1e-9}))
    with pytest.raises(ConfigError, match=rf"field '{field}' must lie in \[16, 20000\] Hz"):
        MemorizedEvent(object_name="box", transition="reach_load", sa=np.ones((2, 8)),
                       ra=np.ones((2, 8)), **({"sa_rate_hz": 16.0, "ra_rate_hz": 16.0}
                                              | {field: 1e-9}))


# Rule: every public rate, window, block and read period that sizes an allocation (a window's
# samples, a block's input port) has an upper bound declared once (rig/ranges.py: the
# scenario's sensors' 20 kHz is the matcher's and the normalizer's), refused at construction
# in one line naming the field and its range, before anything is allocated.
@pytest.mark.parametrize("build, words", [
    (lambda: EventMatcherConfig(sa_rate_hz=1e9),
     "EventMatcherConfig: field 'sa_rate_hz' must lie in [16, 20000] Hz"),
    (lambda: EventMatcherConfig(ra_rate_hz=1e9),
     "EventMatcherConfig: field 'ra_rate_hz' must lie in [16, 20000] Hz"),
    (lambda: EventMatcherConfig(block_s=1e6),
     "EventMatcherConfig: field 'block_s' must lie in [0, 0.1] s"),
    (lambda: EventMatcherConfig(read_period_s=1e6),
     "EventMatcherConfig: field 'read_period_s' must lie in [0, 0.1] s"),
    (lambda: _window_normalizer_config(sa_rate_hz=1e9),
     "WindowNormalizerConfig: field 'sa_rate_hz' must lie in [16, 20000] Hz"),
    (lambda: _window_normalizer_config(window_s=1e6),
     "WindowNormalizerConfig: field 'window_s' must lie in (0, 10] s"),
    (lambda: _memorized_event(ra_rate_hz=1e9),
     "MemorizedEvent: field 'ra_rate_hz' must lie in [16, 20000] Hz"),
])
def test_a_rate_or_window_too_large_to_allocate_is_refused_at_construction(build, words):
    with pytest.raises(ConfigError) as refused:
        build()
    assert str(refused.value).startswith(words), str(refused.value)
    assert "\n" not in str(refused.value)


def _window_normalizer_config(**fields):
    from tegrasp_drake.tactile.window_normalizer import WindowNormalizerConfig
    return WindowNormalizerConfig(**fields)


def _memorized_event(**rates):
    import numpy as np

    from tegrasp_drake.events.memorized_event import MemorizedEvent
    return MemorizedEvent(object_name="box", transition="reach_load", sa=np.ones((2, 8)),
                          ra=np.ones((2, 8)), **({"sa_rate_hz": 16.0, "ra_rate_hz": 16.0} | rates))


def test_a_rate_changed_after_construction_is_refused_before_the_matcher_allocates():
    from tegrasp_drake.events.event_matcher import EventMatcher
    from tegrasp_drake.events.events_folder import load_memorized_events
    config = EventMatcherConfig()
    config.sa_rate_hz = 40_000.0  # cheap to allocate, were it not refused
    with pytest.raises(ConfigError, match=r"field 'sa_rate_hz' must lie in \[16, 20000\] Hz"):
        EventMatcher(load_memorized_events(paths.package_events_dir(), "box"), config)


def test_the_matchers_rates_share_the_sensors_declared_range():
    from tegrasp_drake.rig.ranges import SAMPLE_RATE, field_range
    from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig
    from tegrasp_drake.tactile.window_normalizer import WindowNormalizerConfig
    for cls, name in ((EventMatcherConfig, "sa_rate_hz"), (EventMatcherConfig, "ra_rate_hz"),
                      (WindowNormalizerConfig, "sa_rate_hz"),
                      (TactileSensorConfig, "sample_rate_hz"),
                      (VibrationSensorConfig, "sample_rate_hz")):
        assert field_range(cls, name) is SAMPLE_RATE, (cls, name)
