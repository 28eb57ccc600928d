"""The typed scenario: everything a simulated trial needs, loaded from YAML.

Scenarios live in a YAML file as a mapping from scenario name to fields of `Scenario`; the
built-in file is tegrasp_drake/scenarios/scenarios.yaml. Loading goes through Drake's
`yaml_load_typed` after a walk that names any unknown or mistyped field by its dotted path
(rig/typed_yaml.py). `--set key=value` overrides (e.g. `--set object.name=thin_cylinder`) are
applied to the YAML data before loading, so they are checked the same way. Each section's
config class lives beside the system that uses it; a bad file, field or value raises
ConfigError.
"""

import dataclasses
import math
import pathlib
import typing

from pydrake.common.yaml import yaml_dump, yaml_dump_typed, yaml_load, yaml_load_typed
from pydrake.multibody.plant import MultibodyPlantConfig
from pydrake.systems.analysis import SimulatorConfig

from tegrasp_drake.control.controller_config import (
    ControllerConfig, GraspControllerConfig, HeuristicControllerConfig,
    MemorizedControllerConfig, TaxelAwareControllerConfig, UnknownControllerError,
    controller_named, foreign_setting, select_controller_tag)
from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
from tegrasp_drake.control.scripted_grasp import GraspScriptConfig
from tegrasp_drake.hardware.config import HardwareStationConfig, validate_hardware_config
from tegrasp_drake.rig import paths
from tegrasp_drake.robotiq import drive
from tegrasp_drake.rig.objects import DESCRIPTION_FIELDS
from tegrasp_drake.rig.objects import (BUILTIN_OBJECTS, FINGER_CLEARANCE_M, OBJECT_SHAPES,
                                       ObjectConfig, object_problem)
from tegrasp_drake.rig.typed_yaml import (ConfigError, apply_override, load_typed,
                                          read_yaml_file, require)
from tegrasp_drake.simulation.capacitive_taxels import (AD7147_DECIMATIONS, CAPACITIVE_OUTPUTS,
                                                        TAXEL_TRANSDUCERS,
                                                        ad7147_frame_rate_hz,
                                                        frame_rate_matches)
from tegrasp_drake.simulation.film_readout import ADC_INPUTS
from tegrasp_drake.simulation.contact_meshing import (ContactGeometryConfig,
                                                      contact_geometry_problem)
from tegrasp_drake.simulation.body_force_pulse import DisturbanceConfig
from tegrasp_drake.simulation.linkage_pad_statics import PAD_FORCE_SOURCES
from tegrasp_drake.simulation.pad_accelerometers import VIBRATION_TRANSDUCERS
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           ra_noise_std_mps2)
from tegrasp_drake.simulation.gripper_hands import GRIPPER_MODELS
from tegrasp_drake.simulation.sim_robotiq_driver import GripperDriverConfig
from tegrasp_drake.simulation.station import (ARM_MOUNTS, ArmDriverConfig,
                                             SimulatedStationConfig)
from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig

DEFAULT_SCENARIO = "default"
__all__ = ["DEFAULT_SCENARIO", "FINGER_CLEARANCE_M", "Scenario", "LoadScenario",
           "grasp_plan", "object_pose", "resolve_object", "sample_rates_hz", "scenario_from_yaml",
           "scenario_to_yaml", "validate", "with_controller"]

# Which station a scenario runs on, selected by the YAML tag of its `station` field
# (hardware/config.py): the simulation (the default, untagged) or the real devices.
StationConfig = typing.Union[SimulatedStationConfig, HardwareStationConfig]


@dataclasses.dataclass
class Scenario:
    """One simulated trial: scene, sensors, drivers, the scripted grasp and the seed."""
    random_seed: int = 0
    object: ObjectConfig = dataclasses.field(default_factory=ObjectConfig)
    # Misplacement of the object from its marker [m]: x normal to the palm, y along the stroke.
    object_offset: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0])
    object_yaw_deg: float = 0.0
    expected_object_xy: list[float] = dataclasses.field(default_factory=lambda: [0.72, 0.0])
    # stiction_tolerance 1e-6 m/s instead of Drake's 1e-4: SAP's lagged/similar friction is
    # viscous below eps = max(stiction_tolerance, mu R_t n0), so a held object under a torque
    # tau creeps at tau eps / (2 mu N r_g^2) whatever the time step (a held object slowly
    # rotating). 1e-6 brings eps down to the solver's own O(time_step) floor, about 4e-5 m/s
    # at 1 ms: creep 0.161 -> 0.048 deg/s at 17 % of the torsional friction limit, slip
    # onset moved by 2 %, no measurable cost (docs/model.md, "No creep").
    plant_config: MultibodyPlantConfig = dataclasses.field(
        default_factory=lambda: MultibodyPlantConfig(
            time_step=1e-3, discrete_contact_approximation="lagged", stiction_tolerance=1e-6,
            contact_model="hydroelastic_with_fallback"))
    # How finely the object and the table are meshed (simulation/contact_meshing.py); the
    # default is the reference geometry every committed result ran on.
    contact_geometry: ContactGeometryConfig = dataclasses.field(
        default_factory=ContactGeometryConfig)
    simulator_config: SimulatorConfig = dataclasses.field(
        default_factory=lambda: SimulatorConfig(target_realtime_rate=0.0,
                                                publish_every_time_step=False))
    tactile: TactileSensorConfig = dataclasses.field(default_factory=TactileSensorConfig)
    vibration: VibrationSensorConfig = dataclasses.field(default_factory=VibrationSensorConfig)
    gripper: GripperDriverConfig = dataclasses.field(default_factory=GripperDriverConfig)
    arm: ArmDriverConfig = dataclasses.field(default_factory=ArmDriverConfig)
    grasp: GraspScriptConfig = dataclasses.field(default_factory=GraspScriptConfig)
    disturbance: DisturbanceConfig = dataclasses.field(default_factory=DisturbanceConfig)
    # Which controller, with its settings, selected by the YAML tag (controller_config.py).
    controller: ControllerConfig = dataclasses.field(default_factory=MemorizedControllerConfig)
    # Simulated (default) or real devices, selected by the YAML tag (hardware/config.py).
    station: StationConfig = dataclasses.field(default_factory=SimulatedStationConfig)


def resolve_object(config: ObjectConfig, source: str = "scenario") -> ObjectConfig:
    """The full description of the scenario's object (a built-in one if shape is empty)."""
    if not config.shape:
        if config.name not in BUILTIN_OBJECTS:
            raise ConfigError(
                f"{source}: field 'object.name': '{config.name}' is not a built-in object "
                f"({', '.join(BUILTIN_OBJECTS)}); for your own object give object.shape "
                f"({', '.join(OBJECT_SHAPES)}), object.size, object.mass and object.friction")
        builtin = BUILTIN_OBJECTS[config.name]
        # Fields the user set on a built-in object override it (and are checked below);
        # None is "not set", so that a 0 the user gave is checked, never replaced.
        config = dataclasses.replace(
            builtin, size=list(config.size or builtin.size),
            mass=builtin.mass if config.mass is None else config.mass,
            friction=builtin.friction if config.friction is None else config.friction,
            color=list(builtin.color))
    elif config.name in BUILTIN_OBJECTS and not _is_builtin_geometry(config):
        raise ConfigError(
            f"{source}: field 'object.name': your own object (object.shape "
            f"'{config.shape}') needs its own name, not the built-in '{config.name}': its "
            f"memorized events are stored under that name (e.g. --set object.name=my_"
            f"{config.shape})")
    problem = object_problem(config)
    if problem:
        field, words = problem
        raise ConfigError(f"{source}: field 'object.{field}' {words}")
    if config.shape == "file":
        _check_model_file(config.file, source)
    return config


def _is_builtin_geometry(config: ObjectConfig) -> bool:
    """Whether `config` has the shape, size and model file of the built-in object of its
    name (a resolved built-in, perhaps with its mass or friction set): resolving is
    idempotent."""
    builtin = BUILTIN_OBJECTS[config.name]
    return (config.shape == builtin.shape and list(config.size) == list(builtin.size)
            and config.file == builtin.file)


def _check_model_file(file: str, source: str) -> None:
    """The object's model file parses and holds one model with one body."""
    from pydrake.multibody.plant import MultibodyPlant
    if not file:
        raise ConfigError(f"{source}: field 'object.file' is required for shape 'file'")
    if not file.startswith("package://") and not pathlib.Path(file).is_file():
        raise ConfigError(f"{source}: field 'object.file': model file '{file}' does not exist")
    plant = MultibodyPlant(time_step=0.0)
    parser = paths.make_parser(plant)
    try:
        if file.startswith("package://"):
            instances = parser.AddModels(url=file)
        else:
            instances = parser.AddModels(file_name=file)
    except (RuntimeError, ValueError) as e:
        first_line = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        raise ConfigError(f"{source}: field 'object.file': '{file}' is not a model Drake "
                          f"can load: {first_line}") from None
    bodies = [plant.get_body(b).name() for i in instances for b in plant.GetBodyIndices(i)]
    if len(instances) != 1 or len(bodies) != 1:
        raise ConfigError(
            f"{source}: field 'object.file': '{file}' must hold one model with one body "
            f"(the object), it holds {len(instances)} model(s) with bodies {bodies}")


# Controller settings by unit (the suffix of their names): what each must be.
_CONTROLLER_RULES = (("_s", lambda v: v >= 0, "must be zero or positive [s]"),
                     ("_n", lambda v: v >= 0, "must be zero or positive [N]"),
                     ("_mps2", lambda v: v >= 0, "must be zero or positive [m/s^2]"),
                     ("_m", lambda v: v >= 0, "must be zero or positive [m]"),
                     ("_sigmas", lambda v: v >= 0,
                      "must be zero (the number alone) or positive [noise sigmas]"),
                     ("_threshold", lambda v: -1.0 <= v <= 1.0,
                      "must lie in [-1, 1] (Eq. 3 scores are correlations)"))


def _check_controller(controller, source: str) -> None:
    if isinstance(controller, GraspControllerConfig):
        _check_state_machine(controller, source)
    if isinstance(controller, HeuristicControllerConfig):
        _check_units(controller.heuristic, source, "controller.heuristic")
        require(0 < controller.heuristic.grip_fraction <= 1, source,
                "controller.heuristic.grip_fraction", "must lie in (0, 1]",
                controller.heuristic.grip_fraction)
    if isinstance(controller, TaxelAwareControllerConfig):
        strike = controller.taxel_aware.finger_strike
        prefix = "controller.taxel_aware.finger_strike"
        for name, ok, words in (("force_n", lambda v: v > 0, "must be positive [N]"),
                                ("sustain_s", lambda v: v >= 0,
                                 "must be zero or positive [s]"),
                                ("min_moment_nm", lambda v: v >= 0,
                                 "must be zero or positive [N m]")):
            require(ok(getattr(strike, name)), source, f"{prefix}.{name}", words,
                    getattr(strike, name))


def _check_units(section, source: str, prefix: str) -> None:
    """Each float setting of `section` by the unit its name ends in (_CONTROLLER_RULES)."""
    for field in dataclasses.fields(section):
        value = getattr(section, field.name)
        for suffix, ok, words in _CONTROLLER_RULES:
            if field.name.endswith(suffix) and isinstance(value, float):
                require(ok(value), source, f"{prefix}.{field.name}", words, value)


def _check_state_machine(controller: GraspControllerConfig, source: str) -> None:
    require(controller.update_period_s > 0, source, "controller.update_period_s",
            "must be positive [s]", controller.update_period_s)
    require(controller.sensor_block_s >= 0, source, "controller.sensor_block_s",
            "must be zero (one update per sample) or positive [s]", controller.sensor_block_s)
    for k, name in enumerate(controller.memorized_corrective_events):
        require(name in CORRECTIVE_TRANSITIONS, source,
                f"controller.memorized_corrective_events[{k}]",
                f"must name a corrective event ({', '.join(CORRECTIVE_TRANSITIONS)})", name)
    for name in ("lift_load_event_thresholds", "hold_avoid_event_thresholds"):
        pair = getattr(controller, name)
        require(len(pair) == 2 and all(-1.0 <= v <= 1.0 for v in pair), source,
                f"controller.{name}", "must be [SA, RA], each in [-1, 1] (Eq. 3 scores)",
                pair)
    _check_units(controller, source, "controller")
    for name in ("max_re_reaches", "max_lift_loads"):
        require(getattr(controller, name) >= 0, source, f"controller.{name}",
                "must be zero or positive", getattr(controller, name))
    require(controller.lift_load_force_factor >= 1, source,
            "controller.lift_load_force_factor", "must be at least 1",
            controller.lift_load_force_factor)
    for name in ("grip_fraction",):
        require(0 < getattr(controller, name) <= 1, source, f"controller.{name}",
                "must lie in (0, 1]", getattr(controller, name))
    for k, name in enumerate(controller.event_object_may_differ):
        require(name in DESCRIPTION_FIELDS, source, f"controller.event_object_may_differ[{k}]",
                f"must name a field of the object ({', '.join(DESCRIPTION_FIELDS)})", name)


# Ranges a simulation can use; each message says why (README, "Bad input").
MIN_TIME_STEP_S, MAX_TIME_STEP_S = 1e-4, 1e-3
MIN_SAMPLE_RATE_HZ, MAX_SAMPLE_RATE_HZ = 16.0, 20_000.0
MAX_HIT_FORCE_N = 100.0  # five times the paper's 20 N hit
MAX_HIT_DURATION_S = 1.0
SEED_LIMIT = 2**32  # Drake's RandomGenerator takes a 32-bit seed


def _check_sensors_and_scene(scenario: Scenario, source: str) -> None:
    """Values that would switch a sensor off, or put the hit outside the trial."""
    require(0 <= scenario.random_seed < SEED_LIMIT, source, "random_seed",
            f"must lie in [0, {SEED_LIMIT - 1}] (Drake's random generator takes a 32-bit "
            "seed; a larger one would repeat a smaller one's noise)", scenario.random_seed)
    tactile, vibration = scenario.tactile, scenario.vibration
    for path, value, unit in (("tactile.noise_std_n", tactile.noise_std_n, "N"),
                              ("tactile.quantization_n", tactile.quantization_n, "N"),
                              ("vibration.noise_std_mps2", vibration.noise_std_mps2, "m/s^2")):
        require(value >= 0, source, path, f"must be zero (no noise) or positive [{unit}]",
                value)
    require(vibration.internal_rate_hz > 0, source, "vibration.internal_rate_hz",
            "must be positive [Hz]", vibration.internal_rate_hz)
    nyquist = vibration.internal_rate_hz / 2
    require(0 < vibration.mode_frequency_hz < nyquist, source, "vibration.mode_frequency_hz",
            f"must lie in (0, {nyquist:g}) Hz (the fingertip's mode, integrated at "
            "vibration.internal_rate_hz; at 0 the film feels no ring)",
            vibration.mode_frequency_hz)
    require(vibration.mode_mass_kg > 0, source, "vibration.mode_mass_kg",
            "must be positive [kg] (the fingertip's moving mass)", vibration.mode_mass_kg)
    require(vibration.mode_damping_ratio >= 0, source, "vibration.mode_damping_ratio",
            "must be zero or positive", vibration.mode_damping_ratio)
    block_s = getattr(scenario.controller, "sensor_block_s", 0.0)
    if block_s > 0 and vibration.sample_rate_hz > 0:
        from tegrasp_drake.tactile.sample_block import block_samples, block_update_period
        samples = block_samples(vibration.sample_rate_hz, block_s)
        try:
            if samples > 1:
                block_update_period(1.0 / vibration.sample_rate_hz, samples)
        except ValueError:
            require(False, source, "controller.sensor_block_s",
                    f"gives blocks of {samples} samples at vibration.sample_rate_hz "
                    f"{vibration.sample_rate_hz:g}, which do not fall on the sample times in "
                    "floating point; choose a block such as 0.01 or 0.016 s", block_s)
    disturbance = scenario.disturbance
    force = math.hypot(*disturbance.hit_force_n) if len(disturbance.hit_force_n) == 3 else 0
    require(force <= MAX_HIT_FORCE_N, source, "disturbance.hit_force_n",
            f"must be at most {MAX_HIT_FORCE_N:g} N in size (five times the paper's 20 N "
            "hit; the simulated grasp is not made for more)", disturbance.hit_force_n)
    require(disturbance.hit_duration_s <= MAX_HIT_DURATION_S, source,
            "disturbance.hit_duration_s", f"must be at most {MAX_HIT_DURATION_S:g} s (a hit, "
            "not a push)", disturbance.hit_duration_s)
    if disturbance.hit_time_s >= 0:
        from tegrasp_drake.control.scripted_grasp import plan_duration, plan_scripted_grasp
        end = plan_duration(plan_scripted_grasp(grasp_plan(scenario)))
        require(disturbance.hit_time_s < end, source, "disturbance.hit_time_s",
                f"must come before the grasp's script ends at {end:.1f} s (or be negative: "
                "no hit)", disturbance.hit_time_s)


def _check_transducers(scenario: Scenario, source: str) -> None:
    """The SA and RA transducers by name, and the capacitive taxel's numbers."""
    require(scenario.tactile.transducer in TAXEL_TRANSDUCERS, source, "tactile.transducer",
            f"must be one of {', '.join(TAXEL_TRANSDUCERS)} (ideal force taxels, or the "
            "AD7147's parallel-plate taxels)", scenario.tactile.transducer)
    require(scenario.vibration.transducer in VIBRATION_TRANSDUCERS, source,
            "vibration.transducer", f"must be one of {', '.join(VIBRATION_TRANSDUCERS)} "
            "(the PVDF film, or a high-passed accelerometer on the pad)",
            scenario.vibration.transducer)
    require(scenario.vibration.pad_force_source in PAD_FORCE_SOURCES, source,
            "vibration.pad_force_source", f"must be one of {', '.join(PAD_FORCE_SOURCES)}",
            scenario.vibration.pad_force_source)
    capacitive = scenario.tactile.capacitive
    require(capacitive.output in CAPACITIVE_OUTPUTS, source, "tactile.capacitive.output",
            f"must be one of {', '.join(CAPACITIVE_OUTPUTS)}", capacitive.output)
    for name, ok, words in (
            ("relative_permittivity", lambda v: v >= 1.0, "must be at least 1 (vacuum)"),
            ("noise_std_counts", lambda v: v >= 0.0, "must be zero (no noise) or positive"),
            ("minimum_gap_fraction", lambda v: 0.0 < v < 1.0, "must lie in (0, 1)"),
            ("calibration_force_n", lambda v: v > 0.0, "must be positive [N]")):
        require(ok(getattr(capacitive, name)), source, f"tactile.capacitive.{name}", words,
                getattr(capacitive, name))
    require(capacitive.decimation in AD7147_DECIMATIONS, source, "tactile.capacitive.decimation",
            f"must be one of {', '.join(map(str, AD7147_DECIMATIONS))} (the AD7147's)",
            capacitive.decimation)
    if scenario.tactile.transducer == "capacitive":
        frame = ad7147_frame_rate_hz(capacitive.decimation)
        require(frame_rate_matches(scenario.tactile.sample_rate_hz, capacitive.decimation),
                source, "tactile.sample_rate_hz", f"must be the AD7147's frame rate at "
                f"tactile.capacitive.decimation {capacitive.decimation}, {frame:.1f} Hz (12 "
                f"stages of {1e3 / (12 * frame):.3f} ms): set both together",
                scenario.tactile.sample_rate_hz)
    _check_film_electronics(scenario.vibration, source)


def _check_film_electronics(vibration: VibrationSensorConfig, source: str) -> None:
    """The film's readout and the drives' vibration (film_readout.py, drive_vibration.py)."""
    require(vibration.adc_input in ADC_INPUTS, source, "vibration.adc_input",
            f"must be one of {', '.join(ADC_INPUTS)} (the myRIO's +-10 V MSP input, its "
            "0-5 V MXP input, or no converter)", vibration.adc_input)
    require(vibration.adc_noise_lsb >= 0, source, "vibration.adc_noise_lsb",
            "must be zero (no noise) or positive [codes rms]", vibration.adc_noise_lsb)
    require(vibration.amplifier_swing_v > 0, source, "vibration.amplifier_swing_v",
            "must be positive [V]", vibration.amplifier_swing_v)
    for name in ("film_charge_gain_c_per_m", "feedback_capacitance_f"):
        require(getattr(vibration, name) > 0, source, f"vibration.{name}",
                "must be positive (it sets the film's volts per m/s^2)",
                getattr(vibration, name))
    for name in ("gripper_drive", "arm_drive"):
        drive = getattr(vibration, name)
        require(not drive.amplitudes_mps2 or len(drive.amplitudes_mps2) == len(drive.orders),
                source,
                f"vibration.{name}.orders", "must give one order per amplitude "
                f"({len(drive.amplitudes_mps2)} amplitudes; amplitudes_mps2=[] switches the "
                "drive off)", drive.orders)
        require(all(a >= 0 for a in drive.amplitudes_mps2), source,
                f"vibration.{name}.amplitudes_mps2",
                "must be zero (off) or positive [m/s^2]", drive.amplitudes_mps2)
        if drive.enabled():
            require(drive.full_speed > 0, source, f"vibration.{name}.full_speed",
                    "must be positive (the joint rate of the amplitudes)", drive.full_speed)
            require(drive.motor_revolutions_per_unit >= 0 and all(
                o >= 0 for o in drive.orders), source, f"vibration.{name}",
                "needs motor_revolutions_per_unit and orders of zero or more",
                [drive.motor_revolutions_per_unit, drive.orders])


def _check_drive(gripper: GripperDriverConfig, source: str) -> None:
    """The 2F-85 drive's settings within their plausible ranges (robotiq/drive.py)."""
    low, high = drive.POSITION_LOOP_HZ_RANGE
    require(low <= gripper.position_loop_hz <= high, source, "gripper.position_loop_hz",
            f"must lie in [{low:g}, {high:g}] Hz (the 2F-85 firmware's position loop: slower "
            "and the locked drive yields, faster and a 1 ms plant step cannot follow it)",
            gripper.position_loop_hz)
    low, high = drive.SCREW_EFFICIENCY_RANGE
    require(low <= gripper.screw_efficiency <= high, source, "gripper.screw_efficiency",
            f"must lie in [{low:g}, {high:g}] (a self-locking screw's forward efficiency is "
            "below 0.5)", gripper.screw_efficiency)


def validate(scenario: Scenario, source: str = "scenario") -> Scenario:
    """Checks values that the schema cannot; returns the scenario with its object resolved."""
    scenario = dataclasses.replace(scenario, object=resolve_object(scenario.object, source))
    if len(scenario.object_offset) != 2:
        raise ConfigError(f"{source}: field 'object_offset' must be [x, y] in metres, got "
                            f"{scenario.object_offset}")
    # The object must fit between the open fingers (object_problem). Offset along the
    # stroke beyond that is allowed: an open finger then meets the object on the way in, as
    # it would on a robot (the paper's thick cylinder failed most when misplaced outward).
    for section in ("tactile", "vibration"):
        rate = getattr(scenario, section).sample_rate_hz
        require(MIN_SAMPLE_RATE_HZ <= rate <= MAX_SAMPLE_RATE_HZ, source,
                f"{section}.sample_rate_hz", f"must lie in [{MIN_SAMPLE_RATE_HZ:g}, "
                f"{MAX_SAMPLE_RATE_HZ:g}] Hz (the 0.5 s event window needs 8 samples; the "
                "film is integrated at 20 kHz)", rate)
    envelope_hz = getattr(scenario.controller, "ra_envelope_hz", 0.0)
    require(envelope_hz == 0 or 0 < envelope_hz < scenario.vibration.sample_rate_hz / 2,
            source, "controller.ra_envelope_hz", "must be 0 (no RA envelope) or lie between "
            f"0 and half the RA rate ({scenario.vibration.sample_rate_hz / 2:g} Hz)",
            envelope_hz)
    require(getattr(scenario.controller, "ra_noise_floor_sigmas", 0.0) >= 0, source,
            "controller.ra_noise_floor_sigmas", "must be 0 (no RA noise floor) or positive "
            "(standard deviations of the RA noise)",
            getattr(scenario.controller, "ra_noise_floor_sigmas", 0.0))
    quiet_s = getattr(scenario.controller, "ra_noise_quiet_s", 2.0)
    require(quiet_s * scenario.vibration.sample_rate_hz >= 2, source,
            "controller.ra_noise_quiet_s", "must hold at least 2 RA samples [s] (the start of "
            "the run, pads untouched, where the RA noise is measured)", quiet_s)
    approach_s = scenario.grasp.settle_s + scenario.grasp.reach_s
    require(getattr(scenario.controller, "ra_noise_floor_sigmas", 0.0) == 0
            or quiet_s <= approach_s, source, "controller.ra_noise_quiet_s",
            "must end with the approach, by grasp.settle_s + grasp.reach_s = "
            f"{approach_s:g} s, when the RA noise floor is on (the noise is measured with the "
            "pads untouched; shorten it or lengthen the approach)", quiet_s)
    _check_sensors_and_scene(scenario, source)
    _check_controller(scenario.controller, source)
    if len(scenario.disturbance.hit_force_n) != 3 or scenario.disturbance.hit_duration_s <= 0:
        raise ConfigError(f"{source}: field 'disturbance': hit_force_n must be [x, y, z] in "
                            "newtons and hit_duration_s positive")
    require(MIN_TIME_STEP_S <= scenario.plant_config.time_step <= MAX_TIME_STEP_S, source,
            "plant_config.time_step", f"must lie in [{MIN_TIME_STEP_S:g}, "
            f"{MAX_TIME_STEP_S:g}] s (a discrete step the pads' contact and the 1 kHz "
            "sensors can use; the wall time grows as 1/step)",
            scenario.plant_config.time_step)
    require(scenario.grasp.grip_force > 0, source, "grasp.grip_force", "must be positive [N]",
            scenario.grasp.grip_force)
    problem = contact_geometry_problem(scenario.contact_geometry)
    if problem:
        raise ConfigError(f"{source}: field 'contact_geometry.{problem[0]}' {problem[1]}")
    _check_transducers(scenario, source)
    require(scenario.gripper.model in GRIPPER_MODELS, source, "gripper.model",
            f"must be one of {', '.join(GRIPPER_MODELS)} (the 2F-85's finger linkage, or "
            "prismatic fingers)", scenario.gripper.model)
    _check_drive(scenario.gripper, source)
    if isinstance(scenario.station, HardwareStationConfig):
        validate_hardware_config(scenario.station, source, "station")
    else:
        require(scenario.station.arm in ARM_MOUNTS, source, "station.arm",
                f"must be one of {', '.join(ARM_MOUNTS)} (the JACO2 arm, or the Cartesian "
                "carriage with the arm's end-point impedance, for sweeps)", scenario.station.arm)
    return scenario


def LoadScenario(filename: str | pathlib.Path | None = None, name: str = DEFAULT_SCENARIO,
                  overrides: typing.Sequence[str] = (), *,
                  controller: str | None = None) -> Scenario:
    """Loads scenario `name` from `filename` (default: the built-in file) with overrides.

    controller: run it with the controller of this name (a sweep's trial), keeping the
    overrides' settings that controller has and dropping those of the others."""
    path = pathlib.Path(filename) if filename else paths.scenarios_file()
    document = read_yaml_file(path, "the scenario file")
    if not isinstance(document, dict) or name not in document:
        names = ", ".join(document) if isinstance(document, dict) else "none"
        raise ConfigError(f"{path}: no scenario named '{name}' (scenarios: {names})")
    data = document[name] or {}
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: scenario '{name}' must be a mapping of fields, got "
                          f"{type(data).__name__} {data!r}")
    for assignment in overrides:
        apply_override(data, assignment)
    # A bad value given with --set is named as such, not as the file's.
    source = f"{path} [{name}]" + "".join(f" --set {a}" for a in overrides)
    if controller is not None:
        data.setdefault("controller", {})["name"] = controller
    try:
        select_controller_tag(data, drop_others=controller is not None)
    except UnknownControllerError as e:
        raise ConfigError(f"{source}: field 'controller.name': {e} (or select it by its "
                          "tag, e.g. controller: !TaxelAwareControllerConfig {})") from None
    foreign = foreign_setting(data.get("controller"))
    if foreign is not None:
        key, owners = foreign
        raise ConfigError(f"{source}: field 'controller.{key}' is a setting of the "
                          f"{' and '.join(owners)} controller{'s' * (len(owners) > 1)}: "
                          "select one with --set "
                          f"controller.name={owners[0]} (or its YAML tag "
                          f"controller: !{type(controller_named(owners[0])).__name__} {{...}})")
    return validate(load_typed(data, Scenario, source), source)


def grasp_plan(scenario: Scenario):
    """The GraspPlan of the scenario: its grasp script placed for its expected object, by
    its hand, from its arm's start pose."""
    from tegrasp_drake.control.machine_state import GraspPlan
    return GraspPlan.make(scenario.grasp, start_xyz=scenario.arm.initial_gripper_xyz,
                          expected_object_xy=scenario.expected_object_xy,
                          object=scenario.object, gripper_model=scenario.gripper.model)


def object_pose(scenario: Scenario):
    """X_WO of the scenario's object: on its marker, moved by its offset, yawed."""
    from tegrasp_drake.simulation.station import object_pose_on_table
    return object_pose_on_table(scenario.expected_object_xy, scenario.object_offset,
                                scenario.object_yaw_deg)


def controller_in_force(scenario: Scenario):
    """The scenario's controller config with the RA thresholds it runs with: raised to their
    sigmas of the RA noise of the scenario's film electronics (control/noise_thresholds.py);
    the open-loop script's as it is."""
    controller = scenario.controller
    if not isinstance(controller, GraspControllerConfig):
        return controller
    from tegrasp_drake.control.noise_thresholds import resolve_noise_thresholds
    return resolve_noise_thresholds(
        controller, ra_noise_std_mps2=ra_noise_std_mps2(scenario.vibration),
        ra_rate_hz=scenario.vibration.sample_rate_hz)


def sample_rates_hz(scenario: Scenario) -> tuple[float, float]:
    """The live SA (taxel) and RA (film) sample rates [Hz] the controller's matchers read."""
    return scenario.tactile.sample_rate_hz, scenario.vibration.sample_rate_hz


def with_controller(scenario: Scenario, name: str) -> Scenario:
    """`scenario` run by the controller called `name` (controller_config.CONTROLLER_NAMES),
    keeping the settings its config class shares with the scenario's controller."""
    return dataclasses.replace(scenario, controller=controller_named(
        name, like=scenario.controller))


def scenario_from_yaml(text: str) -> Scenario:
    """The Scenario of YAML text that scenario_to_yaml wrote (a log's), also when written
    with a flat controller section naming its controller (the settings its class lacks are
    dropped)."""
    data = yaml_load(data=text) or {}
    select_controller_tag(data, drop_others=True)
    return yaml_load_typed(schema=Scenario, data=yaml_dump(data), defaults=Scenario())


def scenario_to_yaml(scenario: Scenario) -> str:
    """The scenario as YAML text (for logs and provenance)."""
    return yaml_dump_typed(scenario)
