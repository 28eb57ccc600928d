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

from pydrake.common.yaml import yaml_dump_typed
from pydrake.multibody.plant import MultibodyPlantConfig
from pydrake.systems.analysis import SimulatorConfig

from tegrasp_drake.control.controller_config import CONTROLLERS, GraspControllerConfig
from tegrasp_drake.control.scripted_grasp import GraspScriptConfig
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS, OBJECT_SHAPES, ObjectConfig, object_problem
from tegrasp_drake.rig.robotiq_units import STROKE_M
from tegrasp_drake.rig.typed_yaml import ConfigError, apply_override, load_typed, read_yaml_file
from tegrasp_drake.simulation.object_force_pulse import DisturbanceConfig
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.simulation.sim_robotiq_driver import GripperDriverConfig
from tegrasp_drake.simulation.station import ArmDriverConfig, SimulatedStationConfig
from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig

DEFAULT_SCENARIO = "default"
FINGER_CLEARANCE_M = 0.0025  # smallest gap between an open pad and the object

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
    # tau creeps at tau eps / (2 mu N r_g^2) whatever the time step (the rotating object of
    # issue #11). 1e-6 brings eps down to the solver's own O(time_step) floor, about 4e-5 m/s
    # at 1 ms: creep 0.161 -> 0.048 deg/s at 17 % of the torsional friction limit, slip
    # onset moved by 2 %, no measurable cost (README, "No creep").
    plant_config: MultibodyPlantConfig = dataclasses.field(
        default_factory=lambda: MultibodyPlantConfig(
            time_step=1e-3, discrete_contact_approximation="lagged", stiction_tolerance=1e-6,
            contact_model="hydroelastic_with_fallback"))
    simulator_config: SimulatorConfig = dataclasses.field(
        default_factory=lambda: SimulatorConfig(target_realtime_rate=0.0,
                                                publish_every_time_step=False))
    tactile: TactileSensorConfig = dataclasses.field(default_factory=TactileSensorConfig)
    vibration: VibrationSensorConfig = dataclasses.field(default_factory=VibrationSensorConfig)
    gripper: GripperDriverConfig = dataclasses.field(default_factory=GripperDriverConfig)
    arm: ArmDriverConfig = dataclasses.field(default_factory=ArmDriverConfig)
    grasp: GraspScriptConfig = dataclasses.field(default_factory=GraspScriptConfig)
    disturbance: DisturbanceConfig = dataclasses.field(default_factory=DisturbanceConfig)
    controller: GraspControllerConfig = dataclasses.field(default_factory=GraspControllerConfig)
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
        # Fields the user set on a built-in object override it (and are checked below).
        config = dataclasses.replace(
            builtin, size=list(config.size or builtin.size),
            mass=config.mass or builtin.mass, friction=config.friction or builtin.friction,
            color=list(builtin.color))
    problem = object_problem(config)
    if problem:
        field, words = problem
        raise ConfigError(f"{source}: field 'object.{field}' {words}")
    if config.shape == "file":
        _check_model_file(config.file, source)
    return config


def _check_model_file(file: str, source: str) -> None:
    if not file:
        raise ConfigError(f"{source}: field 'object.file' is required for shape 'file'")
    if file.startswith("package://"):
        return  # resolved (and checked) by the parser's package map
    if not pathlib.Path(file).is_file():
        raise ConfigError(f"{source}: field 'object.file': model file '{file}' does not exist")


def validate(scenario: Scenario, source: str = "scenario") -> Scenario:
    """Checks values that the schema cannot; returns the scenario with its object resolved."""
    scenario = dataclasses.replace(scenario, object=resolve_object(scenario.object, source))
    if len(scenario.object_offset) != 2:
        raise ConfigError(f"{source}: field 'object_offset' must be [x, y] in metres, got "
                            f"{scenario.object_offset}")
    # The object must fit between the open fingers. Offset along the stroke beyond that is
    # allowed: an open finger then meets the object on the way in, as it would on a robot
    # (the paper's thick cylinder failed most when misplaced outward).
    width = scenario.object.width_along_stroke()
    room = STROKE_M - 2 * FINGER_CLEARANCE_M
    if width > room:
        raise ConfigError(
            f"{source}: field 'object.size': the object is {width * 1000:.1f} mm wide along the "
            f"finger stroke, more than the {room * 1000:.1f} mm the 85 mm stroke leaves with "
            f"{FINGER_CLEARANCE_M * 1000:.1f} mm clearance per finger")
    for name in ("sample_rate_hz",):
        for section in (scenario.tactile, scenario.vibration):
            if getattr(section, name) <= 0 or not math.isfinite(getattr(section, name)):
                raise ConfigError(f"{source}: sample rates must be positive")
    if scenario.controller.name not in CONTROLLERS:
        raise ConfigError(f"{source}: field 'controller.name': '{scenario.controller.name}' "
                            f"is not one of {', '.join(CONTROLLERS)}")
    if len(scenario.disturbance.hit_force_n) != 3 or scenario.disturbance.hit_duration_s <= 0:
        raise ConfigError(f"{source}: field 'disturbance': hit_force_n must be [x, y, z] in "
                            "newtons and hit_duration_s positive")
    if scenario.plant_config.time_step <= 0:
        raise ConfigError(f"{source}: field 'plant_config.time_step' must be positive "
                            "(the station is a discrete-time plant)")
    return scenario


def LoadScenario(filename: str | pathlib.Path | None = None, name: str = DEFAULT_SCENARIO,
                  overrides: typing.Sequence[str] = ()) -> Scenario:
    """Loads scenario `name` from `filename` (default: the built-in file) with overrides."""
    path = pathlib.Path(filename) if filename else paths.scenarios_file()
    document = read_yaml_file(path, "the scenario file")
    if not isinstance(document, dict) or name not in document:
        names = ", ".join(document) if isinstance(document, dict) else "none"
        raise ConfigError(f"{path}: no scenario named '{name}' (scenarios: {names})")
    data = document[name] or {}
    for assignment in overrides:
        apply_override(data, assignment)
    source = f"{path} [{name}]"
    return validate(load_typed(data, Scenario, source), source)


def scenario_to_yaml(scenario: Scenario) -> str:
    """The scenario as YAML text (for logs and provenance)."""
    return yaml_dump_typed(scenario)
