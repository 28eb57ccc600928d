"""The typed scenario: everything a simulated trial needs, loaded from YAML.

Scenarios live in a YAML file as a mapping from scenario name to fields of `Scenario`; the
built-in file is tegrasp_drake/scenarios/scenarios.yaml. Loading goes through Drake's
`yaml_load_typed` after a walk that names any unknown or mistyped field by its dotted path.
`--set key=value` overrides (e.g. `--set object.name=thin_cylinder`) are applied to the YAML
data before loading, so they are checked the same way. Each section's config class lives
beside the system that uses it.
"""

import dataclasses
import math
import pathlib
import typing

from pydrake.common.yaml import yaml_dump, yaml_load, yaml_load_typed
from pydrake.multibody.plant import MultibodyPlantConfig
from pydrake.systems.analysis import SimulatorConfig

from tegrasp_drake.control.controller_config import CONTROLLERS, GraspControllerConfig
from tegrasp_drake.control.scripted_grasp import GraspScriptConfig
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS, OBJECT_SHAPES, ObjectConfig
from tegrasp_drake.rig.robotiq_units import STROKE_M
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


class ScenarioError(ValueError):
    """A scenario file, field or value is wrong; the message names it."""


@dataclasses.dataclass
class Scenario:
    """One simulated trial: scene, sensors, drivers, the scripted grasp and the seed."""
    random_seed: int = 0
    object: ObjectConfig = dataclasses.field(default_factory=ObjectConfig)
    # Misplacement of the object from its marker [m]: x normal to the palm, y along the stroke.
    object_offset: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0])
    object_yaw_deg: float = 0.0
    expected_object_xy: list[float] = dataclasses.field(default_factory=lambda: [0.72, 0.0])
    plant_config: MultibodyPlantConfig = dataclasses.field(
        default_factory=lambda: MultibodyPlantConfig(
            time_step=1e-3, discrete_contact_approximation="lagged",
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


def _describe(value) -> str:
    return f"{type(value).__name__} {value!r}"


def _check_against_schema(data, schema, where: str, source: str) -> None:
    """Walks YAML data against a dataclass schema; names the first bad field."""
    if not dataclasses.is_dataclass(schema):
        # A Drake config class: let Drake check it, but name the section.
        try:
            yaml_load_typed(schema=schema, data=yaml_dump(data))
        except (RuntimeError, ValueError) as e:
            raise ScenarioError(f"{source}: field '{where}': {e}") from None
        return
    if not isinstance(data, dict):
        raise ScenarioError(f"{source}: field '{where}' must be a mapping, got {_describe(data)}")
    hints = typing.get_type_hints(schema)
    for key, value in data.items():
        path = f"{where}.{key}" if where else key
        if key not in hints:
            known = ", ".join(sorted(hints))
            raise ScenarioError(f"{source}: unknown field '{path}' (known: {known})")
        _check_value(value, hints[key], path, source)


def _union_member(value, hint, path: str, source: str):
    """The member of a Union that a YAML tag (or its absence: the first) selects."""
    members = typing.get_args(hint)
    tag = value.get("_tag") if isinstance(value, dict) else None
    if tag is None:
        return members[0], value
    for member in members:
        if tag == f"!{member.__name__}":
            return member, {k: v for k, v in value.items() if k != "_tag"}
    known = ", ".join(f"!{m.__name__}" for m in members)
    raise ScenarioError(f"{source}: field '{path}': unknown tag {tag} (known: {known})")


def _check_value(value, hint, path: str, source: str) -> None:
    origin = typing.get_origin(hint)
    if origin is typing.Union:
        member, value = _union_member(value, hint, path, source)
        _check_value(value, member, path, source)
    elif origin is list:
        if not isinstance(value, list):
            raise ScenarioError(f"{source}: field '{path}' must be a list, got {_describe(value)}")
        for k, item in enumerate(value):
            _check_value(item, typing.get_args(hint)[0], f"{path}[{k}]", source)
    elif hint is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ScenarioError(f"{source}: field '{path}' must be a number, got "
                                f"{_describe(value)}")
    elif hint is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ScenarioError(f"{source}: field '{path}' must be an integer, got "
                                f"{_describe(value)}")
    elif hint is str:
        if not isinstance(value, str):
            raise ScenarioError(f"{source}: field '{path}' must be a string, got "
                                f"{_describe(value)}")
    elif hint is bool:
        if not isinstance(value, bool):
            raise ScenarioError(f"{source}: field '{path}' must be true or false, got "
                                f"{_describe(value)}")
    else:
        _check_against_schema(value, hint, path, source)


def apply_override(data: dict, assignment: str) -> None:
    """Sets `key.sub=value` (YAML value) in nested YAML data."""
    if "=" not in assignment:
        raise ScenarioError(f"--set '{assignment}': expected key=value, e.g. object.name=box")
    key, text = assignment.split("=", 1)
    value = yaml_load(data=f"value: {text}")["value"] if text.strip() else ""
    node = data
    parts = key.strip().split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise ScenarioError(f"--set '{assignment}': '{part}' is not a mapping")
    node[parts[-1]] = value


def resolve_object(config: ObjectConfig, source: str = "scenario") -> ObjectConfig:
    """The full description of the scenario's object (a built-in one if shape is empty)."""
    if not config.shape:
        if config.name not in BUILTIN_OBJECTS:
            raise ScenarioError(
                f"{source}: field 'object.name': '{config.name}' is not a built-in object "
                f"({', '.join(BUILTIN_OBJECTS)}); for your own object give object.shape "
                f"({', '.join(OBJECT_SHAPES)}), object.size, object.mass and object.friction")
        builtin = BUILTIN_OBJECTS[config.name]
        # Fields the user set on a built-in object override it (and are checked below).
        config = dataclasses.replace(
            builtin, size=list(config.size or builtin.size),
            mass=config.mass or builtin.mass, friction=config.friction or builtin.friction,
            color=list(builtin.color))
    elif config.shape not in OBJECT_SHAPES:
        raise ScenarioError(f"{source}: field 'object.shape': '{config.shape}' is not one of "
                            f"{', '.join(OBJECT_SHAPES)}")
    expected_sizes = {"box": 3, "cylinder": 2, "file": 3}[config.shape]
    if len(config.size) != expected_sizes or min(config.size) <= 0:
        raise ScenarioError(f"{source}: field 'object.size' must hold {expected_sizes} positive "
                            f"lengths in metres for shape '{config.shape}', got {config.size}")
    if config.mass <= 0:
        raise ScenarioError(f"{source}: field 'object.mass' must be positive [kg], got "
                            f"{config.mass}")
    if config.friction <= 0:
        raise ScenarioError(f"{source}: field 'object.friction' must be positive, got "
                            f"{config.friction}")
    if config.shape == "file":
        _check_model_file(config.file, source)
    return config


def _check_model_file(file: str, source: str) -> None:
    if not file:
        raise ScenarioError(f"{source}: field 'object.file' is required for shape 'file'")
    if file.startswith("package://"):
        return  # resolved (and checked) by the parser's package map
    if not pathlib.Path(file).is_file():
        raise ScenarioError(f"{source}: field 'object.file': model file '{file}' does not exist")


def validate(scenario: Scenario, source: str = "scenario") -> Scenario:
    """Checks values that the schema cannot; returns the scenario with its object resolved."""
    scenario = dataclasses.replace(scenario, object=resolve_object(scenario.object, source))
    if len(scenario.object_offset) != 2:
        raise ScenarioError(f"{source}: field 'object_offset' must be [x, y] in metres, got "
                            f"{scenario.object_offset}")
    # The object must fit between the open fingers. Offset along the stroke beyond that is
    # allowed: an open finger then meets the object on the way in, as it would on a robot
    # (the paper's thick cylinder failed most when misplaced outward).
    width = scenario.object.width_along_stroke()
    room = STROKE_M - 2 * FINGER_CLEARANCE_M
    if width > room:
        raise ScenarioError(
            f"{source}: field 'object.size': the object is {width * 1000:.1f} mm wide along the "
            f"finger stroke, more than the {room * 1000:.1f} mm the 85 mm stroke leaves with "
            f"{FINGER_CLEARANCE_M * 1000:.1f} mm clearance per finger")
    for name in ("sample_rate_hz",):
        for section in (scenario.tactile, scenario.vibration):
            if getattr(section, name) <= 0 or not math.isfinite(getattr(section, name)):
                raise ScenarioError(f"{source}: sample rates must be positive")
    if scenario.controller.name not in CONTROLLERS:
        raise ScenarioError(f"{source}: field 'controller.name': '{scenario.controller.name}' "
                            f"is not one of {', '.join(CONTROLLERS)}")
    if len(scenario.disturbance.hit_force_n) != 3 or scenario.disturbance.hit_duration_s <= 0:
        raise ScenarioError(f"{source}: field 'disturbance': hit_force_n must be [x, y, z] in "
                            "newtons and hit_duration_s positive")
    if scenario.plant_config.time_step <= 0:
        raise ScenarioError(f"{source}: field 'plant_config.time_step' must be positive "
                            "(the station is a discrete-time plant)")
    return scenario


def load_scenario(filename: str | pathlib.Path | None = None, name: str = DEFAULT_SCENARIO,
                  overrides: typing.Sequence[str] = ()) -> Scenario:
    """Loads scenario `name` from `filename` (default: the built-in file) with overrides."""
    path = pathlib.Path(filename) if filename else paths.scenarios_file()
    if not path.is_file():
        raise ScenarioError(f"scenario file '{path}' does not exist")
    try:
        document = yaml_load(filename=str(path))
    except RuntimeError as e:
        raise ScenarioError(f"{path}: not valid YAML: {e}") from None
    if not isinstance(document, dict) or name not in document:
        names = ", ".join(document) if isinstance(document, dict) else "none"
        raise ScenarioError(f"{path}: no scenario named '{name}' (scenarios: {names})")
    data = document[name] or {}
    for assignment in overrides:
        apply_override(data, assignment)
    source = f"{path} [{name}]"
    return validate(load_typed(data, Scenario, source), source)


def load_typed(data: dict, schema, source: str):
    """An instance of the dataclass `schema` from YAML data (defaults for what is not
    set), after a walk that names any unknown or mistyped field."""
    _check_against_schema(data, schema, "", source)
    try:
        return yaml_load_typed(schema=schema, data=yaml_dump(data), defaults=schema())
    except (RuntimeError, ValueError) as e:
        raise ScenarioError(f"{source}: {e}") from None


def scenario_to_yaml(scenario: Scenario) -> str:
    """The scenario as YAML text (for logs and provenance)."""
    from pydrake.common.yaml import yaml_dump_typed
    return yaml_dump_typed(scenario)
