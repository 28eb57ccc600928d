"""Settings whose value no physical rig has are refused at load, naming the field and its
range: values below a plausible physical minimum (an open zero decided by its physics),
timeouts of zero, time steps and durations Drake cannot run, sample rates and filters against
the rates they run at, and starts or grasps the arm cannot reach."""

import math

import pytest

import tegrasp_drake
import tegrasp_drake as T
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.simulation.station import ArmDriverConfig, initial_arm_positions
from tests.bad_input.probes import SEED, one_line_of, refusal, run_cli


def test_a_high_pass_is_checked_against_the_rate_it_runs_at():
    """The film's charge amplifier is integrated at vibration.internal_rate_hz (20 kHz): a
    600 Hz corner is a valid filter there, even with RA sampled at 1 kHz. The accelerometer's
    high-pass runs on its 1 kHz samples: above 500 Hz it is refused."""
    assert LoadScenario(overrides=["vibration.highpass_cutoff_hz=600.0"])
    with pytest.raises(ConfigError, match="field 'vibration.highpass_cutoff_hz' must lie below "
                                          "500 Hz, half the vibration.sample_rate_hz"):
        LoadScenario(overrides=["vibration.highpass_cutoff_hz=600.0",
                                "vibration.transducer=accelerometer"])


@pytest.mark.parametrize("assignment", ["controller.update_period_s=0.000000001",
                                        "arm.control_period_s=0.0001",
                                        "disturbance.hit_duration_s=0.0005"])
def test_a_time_shorter_than_the_plant_step_is_refused(assignment):
    field = assignment.split("=")[0]
    with pytest.raises(ConfigError, match=f"field '{field}' must be at least the simulation's "
                                          r"time step plant_config.time_step = 0.001 s"):
        LoadScenario(overrides=[assignment])


# --- 2. the public API: declared ranges, choices and folders, checked before any write --------

@pytest.mark.parametrize("call, argument", [
    (lambda s: tegrasp_drake.run_ideal_grasp(s, duration=-1.0), "duration"),
    (lambda s: tegrasp_drake.run_ideal_grasp(s, duration=math.nan), "duration"),
    (lambda s: tegrasp_drake.run_trial(s, max_time=-1.0), "max_time"),
    (lambda s: tegrasp_drake.run_trial(s, max_time=math.nan), "max_time"),
])
def test_a_duration_out_of_range_is_refused_by_name_never_by_drake(call, argument):
    scenario = tegrasp_drake.LoadScenario(name="box", overrides=[f"random_seed={SEED}"])
    with pytest.raises(ValueError) as refused:  # not SystemExit from Drake's AdvanceTo
        call(scenario)
    assert f"argument '{argument}'" in one_line_of(refused.value)


@pytest.mark.parametrize("config, field", [
    (dict(sa_threshold=math.nan), "sa_threshold"),
    (dict(sa_threshold=2.0), "sa_threshold"),
    (dict(sa_threshold="0.9"), "sa_threshold"),
    (dict(event_thresholds={"reach_load": (math.nan, 0.5)}), "event_thresholds"),
])
def test_a_matcher_config_out_of_range_is_refused_where_it_is_used(config, field):
    events = tegrasp_drake.load_memorized_events(paths.package_events_dir(), "box")
    with pytest.raises((ConfigError, TypeError)) as refused:
        tegrasp_drake.EventMatcher(events, tegrasp_drake.EventMatcherConfig(**config))
    assert f"field '{field}" in one_line_of(refused.value)


def _reachable_dataclasses(*roots):
    import dataclasses
    import typing
    from tegrasp_drake.rig.ranges import _config_classes
    seen, pending = [], list(roots)
    while pending:
        cls = pending.pop()
        if cls in seen or not dataclasses.is_dataclass(cls):
            continue
        seen.append(cls)
        hints = typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            pending.extend(_config_classes(hints[field.name]))
    return seen


def test_every_timeout_refuses_zero_as_the_user_guide_says():
    import dataclasses
    from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_named
    from tegrasp_drake.hardware.config import HardwareStationConfig
    from tegrasp_drake.rig.ranges import range_of
    from tegrasp_drake.scenario.scenario import Scenario
    roots = [Scenario, HardwareStationConfig,
             *(type(controller_named(name)) for name in CONTROLLER_NAMES)]
    timeouts, zero_allowed = [], []
    for cls in _reachable_dataclasses(*roots):
        for field in dataclasses.fields(cls):
            declared = range_of(field)
            if "timeout" in field.name and declared is not None:
                timeouts.append(f"{cls.__name__}.{field.name}")
                if declared.low is not None and declared.low <= 0 and not declared.low_open:
                    zero_allowed.append(f"{cls.__name__}.{field.name}")
    assert len(timeouts) >= 4 and zero_allowed == []


@pytest.mark.parametrize("key", ["controller.load_event_timeout_s",
                                 "controller.re_reach.reach_event_timeout_s",
                                 "controller.place.event_timeout_s"])
def test_a_zero_controller_timeout_is_refused(key):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    with pytest.raises(ConfigError, match=f"field '{key}' must be positive"):
        LoadScenario(name="box", overrides=[f"{key}=0.0"])


def _numeric_fields(scenario) -> list[str]:
    """The dotted name of every number a scenario holds (lists left out)."""
    import yaml
    from tegrasp_drake.scenario.scenario import scenario_to_yaml

    class Loader(yaml.SafeLoader):
        pass
    Loader.add_multi_constructor("!", lambda loader, _, node: loader.construct_mapping(node))
    found = []

    def walk(value, path):
        if isinstance(value, dict):
            for key, item in value.items():
                walk(item, f"{path}.{key}" if path else str(key))
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            found.append(path)
    walk(yaml.load(scenario_to_yaml(scenario), Loader=Loader), "")
    return found


@pytest.mark.parametrize("controller", ["open_loop", "memorized", "heuristic", "taxel_aware",
                                        "fixed_load_time"])
def test_every_number_set_to_zero_loads_or_is_refused_in_one_line(controller):
    """0 and -0.0 in each numeric field, with each controller: the scenario loads or is
    refused in one ConfigError line naming the field; no check divides by a zero it let
    through (a move duration of 0 once reached the hand-speed check's division)."""
    from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES
    assert controller in CONTROLLER_NAMES and len(CONTROLLER_NAMES) == 5
    base = [f"controller.name={controller}"]
    fields = _numeric_fields(LoadScenario(overrides=base))
    assert "controller.avoid.move_s" in fields or controller == "open_loop"
    for field in fields:
        for zero in ("0", "-0.0"):
            try:
                LoadScenario(overrides=[*base, f"{field}={zero}"])
            except ConfigError as refused:
                assert f"'{field}" in one_line_of(refused), (field, str(refused))


@pytest.mark.parametrize("field", ["controller.avoid.move_s", "controller.re_reach.move_s"])
@pytest.mark.parametrize("zero", ["0", "-0.0"])
def test_a_move_in_no_time_is_refused_naming_its_duration(field, zero):
    refusal(lambda: LoadScenario(overrides=[f"{field}={zero}"]),
            f"field '{field}' must be positive [s]", "the arm cannot move the hand")


def test_a_move_in_no_time_is_refused_by_the_api_and_the_command_line(tmp_path, capfd,
                                                                      no_simulation):
    """A scenario changed after loading is checked where it is run; `tegrasp trial` and a
    sweep spec's scenario_overrides refuse it as bad input (exits 1 and 2), never exit 70."""
    import dataclasses
    from tegrasp_drake.scenario.scenario import _check_hand_speeds
    scenario = LoadScenario(name="box", overrides=[f"random_seed={SEED}"])
    scenario.controller.re_reach = dataclasses.replace(scenario.controller.re_reach, move_s=0.0)
    with pytest.raises(ConfigError) as refused:
        T.run_trial(scenario)
    assert "'controller.re_reach.move_s' must be positive" in one_line_of(refused.value)
    with pytest.raises(ConfigError) as refused:  # the cross-field check alone never divides
        _check_hand_speeds(scenario, "scenario")
    assert "'controller.re_reach.move_s' must be positive" in one_line_of(refused.value)
    code, text = run_cli(["trial", "--out", str(tmp_path / "t"), "--set",
                          "controller.avoid.move_s=0"], capfd)
    assert code == 1 and "'controller.avoid.move_s' must be positive" in text, text
    assert len(text.strip().splitlines()) == 1, text
    spec = tmp_path / "spec.yaml"
    spec.write_text("scenario_overrides: [controller.avoid.move_s=0]\n")
    code, text = run_cli(["sweep", "--dry-run", "--spec", str(spec), "--out",
                          str(tmp_path / "s")], capfd)
    assert code == 2 and "'controller.avoid.move_s' must be positive" in text, text


# Every range that stops at an open 0, decided by its physics: a tiny positive value of these
# is harmless. Times [s]: a simulated one shorter than the plant step is refused
# (check_times_resolved); the devices' timeouts have their devices' periods as their lows
# (hardware/config.py). Speeds, forces and fractions: a tiny one makes a slow or failed grasp the trial reports (tried at
# 1e-9: grip_force, gripper acceleration). Filter corners (slip band, load low-pass): a tiny
# one makes a vanishing signal (a test turns the load channel off with a 1e-3 Hz corner).
# Contact: Drake's point contact and regularized friction ran at 1e-9 m and 1e-12 m/s. The
# integrator's accuracy and largest step: the diagram is discrete (ran at 1e-12 and 1e-9 s).
# The others have a plausible physical minimum instead (object mass, size and friction; the
# fingertip's mode, mass and stiffness; the amplifier's capacitor, swing, corner and rate; the
# pad texture, pad friction, the 2F-85's 20 N grip; the taxels' calibration weight and gap;
# the gains and rates: the servos' and the tracker's gains, the film's charge gain, the arm's
# command and the gripper's update rates). An arm move's duration: one too short for the arm
# to follow is refused at load with the shortest it may take (scenario._check_hand_speeds).
TINY_IS_HARMLESS = {
    "AvoidConfig": {"move_s"},
    "ArmDriverConfig": {"command_latency_s", "control_period_s"},
    "DisturbanceConfig": {"hit_duration_s"},
    "DriveVibrationConfig": {"full_speed"},
    "FilmConfig": {"load_lowpass_hz"},
    "FingerStrikeConfig": {"force_n"},
    "FixedLoadTimeControllerConfig": {"load_event_timeout_s", "load_time_s", "update_period_s"},
    "GraspScriptConfig": {"lift_s", "load_s", "place_s", "reach_s", "retract_s",
                          "unload_s"},
    "GripperDriverConfig": {"acceleration", "stall_speed"},
    "HeuristicControllerConfig": {"load_event_timeout_s", "update_period_s"},
    "HeuristicTriggerConfig": {"grip_fraction"},
    "JacoVelocityTrackerConfig": {"max_joint_speed"},
    "LiftLoadConfig": {"grip_fraction", "slip_band_hz", "slip_window_s"},
    "MemorizedControllerConfig": {"load_event_timeout_s", "update_period_s"},
    "MultibodyPlantConfig": {"penetration_allowance", "stiction_tolerance"},
    "PlaceConfig": {"event_timeout_s"},
    "ReReachConfig": {"move_s", "reach_event_timeout_s"},
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


def test_a_huge_sample_rate_is_refused_before_anything_is_built():
    from pydrake.systems.framework import DiagramBuilder
    from pydrake.systems.primitives import ConstantVectorSource
    from tegrasp_drake import AddGraspController, LoadScenario, grasp_plan
    scenario = LoadScenario(name="box")
    with pytest.raises(ValueError, match=r"sample_rates_hz.*must lie in \[16, 20000\] Hz"):
        AddGraspController(DiagramBuilder(), controller=scenario.controller,
                           plan=grasp_plan(scenario), station=ConstantVectorSource([0.0]),
                           arm=scenario.arm, sample_rates_hz=(1e12, 1e12))


# Rule: a public function's number takes the range its command-line or scenario twin takes,
# from one declaration.
def _declared(function, argument: str):
    """The Range annotated on `function`'s `argument`."""
    import typing
    from tegrasp_drake.rig.ranges import Range
    hint = typing.get_type_hints(function.__wrapped__, include_extras=True)[argument]
    (declared,) = [m for m in hint.__metadata__ if isinstance(m, Range)]
    return declared


def test_seeds_workers_and_simulated_durations_are_declared_once():
    import tegrasp_drake
    from tegrasp_drake.rig.ranges import SEED_RANGE, SIMULATED_DURATION, field_range
    from tegrasp_drake.sweep.runner import WORKER_COUNT
    assert _declared(tegrasp_drake.MakeGraspStation, "random_seed") == SEED_RANGE
    assert field_range(tegrasp_drake.Scenario, "random_seed") == SEED_RANGE
    assert field_range(tegrasp_drake.SweepSpec, "base_seed") == SEED_RANGE
    assert _declared(tegrasp_drake.run_sweep, "workers") == WORKER_COUNT
    assert _declared(tegrasp_drake.run_trial, "max_time") == SIMULATED_DURATION
    assert _declared(tegrasp_drake.run_ideal_grasp, "duration") == SIMULATED_DURATION


@pytest.mark.parametrize("controller", ["memorized", "taxel_aware"])
def test_a_trial_longer_than_the_scenarios_time_limit_is_refused_before_it_is_built(
        controller, monkeypatch):
    import tegrasp_drake
    from tegrasp_drake.runs import ideal_grasp, trial
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    scenario = tegrasp_drake.LoadScenario(name="box", controller=controller)
    limit = MakeGraspDiagram(scenario, log=False).time_limit  # where `tegrasp trial` stops

    def not_built(*args, **kwargs):
        raise AssertionError("built before the argument was checked")
    monkeypatch.setattr(trial, "MakeGraspDiagram", not_built)
    monkeypatch.setattr(ideal_grasp, "MakeGraspDiagram", not_built)
    words = f"must lie in (0, {limit:g}] s (the scenario's time limit"
    with pytest.raises(ValueError, match="run_trial: argument 'max_time'") as refused:
        tegrasp_drake.run_trial(scenario, max_time=1.0e7)
    assert words in str(refused.value)
    with pytest.raises(ValueError, match="argument 'max_time' must be above 0 s"):
        tegrasp_drake.run_trial(scenario, max_time=0.0)
    with pytest.raises(ValueError, match="run_ideal_grasp: argument 'duration' must lie in"):
        tegrasp_drake.run_ideal_grasp(scenario, duration=1.0e7)
    with pytest.raises(AssertionError, match="built before"):  # the limit itself is accepted
        tegrasp_drake.run_trial(scenario, max_time=limit)


# Rule: a setting a solver decides (the arm's start, reached by inverse kinematics) is
# checked with the others when the scenario is loaded: out of reach, it is refused naming
# the field, before anything is built; a builder given one says the same.
def test_a_start_the_arm_cannot_reach_is_refused_naming_the_field():
    unreachable = "arm.initial_gripper_xyz=[0.69, 0.0, -0.5]"  # 0.5 m under the table
    refusal(lambda: LoadScenario(overrides=[unreachable]), "field 'arm.initial_gripper_xyz'",
             "must be a point the JACO2 reaches")
    arm = ArmDriverConfig(initial_gripper_xyz=[0.69, 0.0, -0.5])
    refusal(lambda: initial_arm_positions(arm), "field 'arm.initial_gripper_xyz'")
    assert initial_arm_positions(ArmDriverConfig()).shape == (6,)


# Rule: a range's low end is a physical low, not just "positive": a value a real fingertip,
# pad, object or amplifier cannot have is refused naming the field, while the committed
# values (and the slip recordings' slippery objects) still load.
@pytest.mark.parametrize("setting, field", [
    ("vibration.film.mode_frequency_hz=1e-9", "vibration.film.mode_frequency_hz"),
    ("vibration.film.mode_frequency_hz=1.0", "vibration.film.mode_frequency_hz"),
    ("vibration.film.mode_mass_kg=1e-9", "vibration.film.mode_mass_kg"),
    ("vibration.film.pad_contact_stiffness_n_per_m=1e-6",
     "vibration.film.pad_contact_stiffness_n_per_m"),
    ("vibration.film.feedback_capacitance_f=1e-20", "vibration.film.feedback_capacitance_f"),
    ("vibration.highpass_cutoff_hz=1e-9", "vibration.highpass_cutoff_hz"),
    ("vibration.slip_texture_period_m=1e-12", "vibration.slip_texture_period_m"),
    ("vibration.amplifier_swing_v=1e-6", "vibration.amplifier_swing_v"),
    ("vibration.internal_rate_hz=1.0", "vibration.internal_rate_hz"),
    ("object.friction=1e-12", "object.friction"),
    ("gripper.pad_friction=1e-9", "gripper.pad_friction"),
    ("tactile.capacitive.calibration_force_n=1e-9", "tactile.capacitive.calibration_force_n"),
    ("tactile.capacitive.minimum_gap_fraction=1e-9",
     "tactile.capacitive.minimum_gap_fraction"),
    ("grasp.grip_force=1.0", "grasp.grip_force"),
])
def test_a_physically_meaningless_small_value_is_refused(setting, field):
    refusal(lambda: T.LoadScenario(name="box", overrides=[setting]), f"'{field}'")


def test_the_slip_recordings_slippery_object_still_loads():
    assert T.LoadScenario(name="box", overrides=["object.friction=0.008"]).object.friction \
        == pytest.approx(0.008)


# Rule: what a scenario's fields must be to build is checked where it is loaded (validate),
# not found while building: a side grasp the JACO2 cannot reach, at which the carriage's
# impedance is taken (`station.arm: carriage`), is bad input naming the fields (exit 1).
CARRIAGE_OUT_OF_REACH = ["station.arm=carriage", "placement.expected_xy=[0.2,0.0]"]


def test_a_carriage_side_grasp_out_of_reach_is_refused_at_load():
    refusal(lambda: T.LoadScenario(name="box", overrides=CARRIAGE_OUT_OF_REACH),
             "'placement.expected_xy'", "reach")


def test_tegrasp_trial_says_a_carriage_side_grasp_out_of_reach_as_bad_input(tmp_path, capfd):
    argv = ["trial", "--set", "random_seed=640", "--out", str(tmp_path / "o")]
    for setting in CARRIAGE_OUT_OF_REACH:
        argv += ["--set", setting]
    code, text = run_cli(argv, capfd)
    assert code == 1 and "placement.expected_xy" in text and "internal error" not in text, text


@pytest.mark.parametrize("number", ["1e-400", "-1e-400", "1e400", "-1.5e400"])
def test_a_set_number_no_float_holds_is_refused_naming_the_field(number, capfd):
    """`1e-400` is not read as 0, nor `1e400` as inf: refused as the number options refuse
    them."""
    code, text = run_cli(["trial", "--set", f"object.mass={number}"], capfd)
    assert code == 1
    assert "field 'object.mass'" in text and "beyond the range of any setting" in text, text


def test_a_scenario_file_number_no_float_holds_is_refused_naming_the_file_and_field(tmp_path):
    scenario = tmp_path / "scenarios.yaml"
    scenario.write_text("x:\n  object: {name: box, mass: 1e-400}\n")
    refusal(lambda: LoadScenario(scenario, "x"), str(scenario), "mass",
            "beyond the range of any setting")
