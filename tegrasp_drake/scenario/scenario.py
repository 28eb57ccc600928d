"""The typed scenario: everything a simulated trial needs, loaded from YAML (the built-in
file: tegrasp_drake/scenarios/scenarios.yaml). Loading goes through Drake's `yaml_load_typed`
after a walk that names any unknown or mistyped field by its dotted path (rig/typed_yaml.py);
`--set key=value` overrides are applied to the YAML data first, so they are checked the same
way. A bad file, field or value raises ConfigError.
"""

import dataclasses
import difflib
import math
import pathlib
import re
import typing

import numpy as np
import yaml
from pydrake.common.yaml import yaml_dump_typed
from pydrake.multibody.plant import MultibodyPlantConfig
from pydrake.systems.analysis import GetIntegrationSchemes, SimulatorConfig

from tegrasp_drake.control.controller_registry import (
    CONTROLLER_CLASSES, CONTROLLER_NAMES, ControllerConfig, UnknownControllerError,
    controller_entry, controller_named, controller_tag_problem, foreign_setting,
    select_controller_tag, selected_controller)
from tegrasp_drake.control.scripted_grasp import GraspScriptConfig
from tegrasp_drake.hardware.config import HardwareStationConfig, validate_hardware_config
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.ranges import (SEED_RANGE, Choice, Range, bounded, check_ranges,
                                      check_times_resolved, declare_ranges)
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.objects import (BUILTIN_OBJECTS, DEFAULT_COLOR, FINGER_CLEARANCE_M, OBJECT_SHAPES,
                                       ObjectConfig, object_problem)
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.unset_fields import without_unset_fields
from tegrasp_drake.rig.typed_yaml import (ConfigError, apply_override, assignment_key,
                                          check_fields, keys_overlap, load_typed,
                                          loaded_with_overrides, parse_yaml,
                                          read_yaml_file_cached, refuse_a_key_set_twice,
                                          require, require_mapping, set_words)
from tegrasp_drake.simulation.capacitive_taxels import ad7147_frame_rate_hz, frame_rate_matches
from tegrasp_drake.simulation.contact_meshing import ContactGeometryConfig
from tegrasp_drake.simulation.body_force_pulse import DisturbanceConfig
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           ra_noise_std_mps2)
from tegrasp_drake.simulation.jaco_velocity_drive import drive_problem
from tegrasp_drake.simulation.sim_robotiq_driver import GripperDriverConfig
from tegrasp_drake.simulation.station import (ArmDriverConfig,
                                             SimulatedStationConfig, side_grasp_problem,
                                             start_pose_problem)
from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig
from tegrasp_drake.rig.api_boundary import (PathLike, public_api, public_dataclass,
                                            register_moved_fields, relations_checked)
from tegrasp_drake.scenario.moved_keys import (MOVED_KEYS, migrate_stored_scenario,
                                                refuse_moved_keys)
from tegrasp_drake.rig.object_file import check_model_file
from tegrasp_drake.scenario.object_placement import ObjectPlacementConfig, footprint_radius

DEFAULT_SCENARIO = "default"
__all__ = ["DEFAULT_SCENARIO", "FINGER_CLEARANCE_M", "Scenario", "LoadScenario",
           "grasp_plan", "object_pose", "resolve_object", "sample_rates_hz", "scenario_from_yaml",
           "scenario_to_yaml", "validate", "with_controller"]

# The station, selected by the YAML tag of `station` (hardware/config.py); untagged: simulated.
StationConfig = typing.Union[SimulatedStationConfig, HardwareStationConfig]


@public_dataclass
@dataclasses.dataclass
class Scenario:
    """One simulated trial: scene, sensors, drivers, the scripted grasp and the seed."""
    random_seed: int = bounded(0, **dataclasses.asdict(SEED_RANGE))
    object: ObjectConfig = dataclasses.field(default_factory=ObjectConfig)
    # Where it stands: its marker, the misplacement from it, its yaw.
    placement: ObjectPlacementConfig = dataclasses.field(default_factory=ObjectPlacementConfig)
    # stiction_tolerance 1e-6 m/s, not Drake's 1e-4: SAP's friction is viscous below it, so a
    # held object creeps; 1e-6 reaches the solver's own floor. Triangles: each contact polygon
    # cut at its centroid, more faces for the floor to spread over
    # (docs/model.md, "Friction creep").
    plant_config: MultibodyPlantConfig = dataclasses.field(
        default_factory=lambda: MultibodyPlantConfig(
            time_step=1e-3, discrete_contact_approximation="lagged", stiction_tolerance=1e-6,
            contact_model="hydroelastic_with_fallback",
            contact_surface_representation="triangle"))
    # How finely the object and the table are meshed (simulation/contact_meshing.py).
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
    controller: ControllerConfig = dataclasses.field(default_factory=CONTROLLER_CLASSES[0])
    # Simulated (default) or real devices, selected by the YAML tag (hardware/config.py).
    station: StationConfig = dataclasses.field(default_factory=SimulatedStationConfig)

    def check_relations(self, source: str) -> None:
        """ConfigError naming the field unless the fields relate as LoadScenario checks them
        (validate; a long grasp script accepted): public functions call it on a scenario."""
        validate(self, source, allow_long=True, loaded=True)


register_moved_fields(Scenario, {old: new for old, new in MOVED_KEYS.items()
                                 if "." not in old})


# Drake's own config sections cannot carry `bounded` declarations: their allowed values are
# declared here (Drake's documented names, pydrake 1.51; numbers Drake accepts, narrowed to a
# hand-sized grasp) and checked by the same validator (rig/ranges.py).
MIN_TIME_STEP_S, MAX_TIME_STEP_S = 1e-4, 1e-3
declare_ranges(MultibodyPlantConfig, {
    "time_step": Range(MIN_TIME_STEP_S, MAX_TIME_STEP_S, unit="s",
                       why="a discrete step the pads' contact and the 1 kHz sensors can use; "
                           "the wall time grows as 1/step"),
    "penetration_allowance": Range(0.0, 0.01, low_open=True, unit="m",
                                   why="Drake's point-contact stiffness from it must be "
                                       "positive; a centimetre is a third of a pad"),
    "stiction_tolerance": Range(0.0, 0.01, low_open=True, unit="m/s",
                                why="Drake's regularized friction needs a positive slip speed; "
                                    "above 1 cm/s a held object slides visibly"),
    # Of Drake's three contact models, the one this station simulates: the taxels integrate
    # the pads' hydroelastic pressure field (tactile_pads.py), which point contact never makes
    # (a trial ran to "no Reach-Load event" with every taxel at 0 N), and strict hydroelastic
    # stops at t = 0 on the links and shapes that have no hydroelastic representation.
    "contact_model": Choice(("hydroelastic_with_fallback",),
                            "the taxels read the pads' hydroelastic pressure field, which "
                            "'point' never makes; strict 'hydroelastic' stops at the shapes "
                            "with no hydroelastic representation"),
    # Of Drake's four, the SAP family: the 2F-85's closed five-bar is a ball constraint and
    # its drive a coupler, which Drake's TAMSI solver does not support (it stops at build).
    "discrete_contact_approximation": Choice(("sap", "similar", "lagged"),
                                             "the SAP solver's: the 2F-85 linkage's ball "
                                             "constraints are not supported by 'tamsi'"),
    "sap_near_rigid_threshold": Range(0.0, 10.0, why="Drake's SAP near-rigid regime, "
                                      "non-negative, typically in [0, 1]"),
    "contact_surface_representation": Choice(("triangle", "polygon"),
                                             "Drake's hydroelastic surface representations"),
})
declare_ranges(SimulatorConfig, {
    "integration_scheme": Choice(tuple(GetIntegrationSchemes()), "Drake's integrators"),
    "max_step_size": Range(0.0, 1.0, low_open=True, unit="s",
                           why="the error-controlled integrator's largest step"),
    "accuracy": Range(0.0, 1.0, low_open=True,
                      why="the integrator's relative error tolerance, a fraction"),
    "start_time": Range(0.0, 0.0, unit="s",
                        why="the grasp script's times count from the trial's start at 0 s"),
    "target_realtime_rate": Range(0.0, 100.0, unit="x real time",
                                  why="0 runs as fast as it can; 1 paces it to real time"),
})


def resolve_object(config: ObjectConfig, source: str = "scenario", *,
                   loaded: bool = False) -> ObjectConfig:
    """The full description of the scenario's object (a built-in one if shape is empty).
    loaded: `config` came resolved from a loaded scenario, where a built-in's name with other
    sizes is that built-in with the sizes the user set (LoadScenario already asked)."""
    if not config.shape:
        if config.name not in BUILTIN_OBJECTS:
            raise ConfigError(
                f"{source}: field 'object.name': '{config.name}' is not a built-in object "
                f"({', '.join(BUILTIN_OBJECTS)}); for your own object give object.shape "
                f"({', '.join(OBJECT_SHAPES)}), object.size, object.mass and object.friction")
        builtin = BUILTIN_OBJECTS[config.name]
        if config.file:
            raise ConfigError(
                f"{source}: field 'object.file' is for your own object (object.shape: file); "
                f"the built-in '{config.name}' has its own model: leave object.file out, or "
                f"give your object its own name and object.shape: file")
        # Fields the user set on a built-in object override it (and are checked below);
        # None is "not set", so that a 0 the user gave is checked, never replaced.
        config = dataclasses.replace(
            builtin, size=list(config.size or builtin.size),
            mass=builtin.mass if config.mass is None else config.mass,
            friction=builtin.friction if config.friction is None else config.friction,
            color=list(config.color or builtin.color))
    elif (config.name in BUILTIN_OBJECTS and not loaded
          and not _is_builtin_geometry(config)):
        raise ConfigError(
            f"{source}: field 'object.name': your own object (object.shape "
            f"'{config.shape}') needs its own name, not the built-in '{config.name}': its "
            f"memorized events are stored under that name (e.g. --set object.name=my_"
            f"{config.shape})")
    if not config.color:
        config = dataclasses.replace(config, color=list(DEFAULT_COLOR))
    require(len(config.color) == 4, source, "object.color",
            "must be [r, g, b, a], each in [0, 1]", config.color)
    problem = object_problem(config)
    if problem:
        field, words = problem
        raise ConfigError(f"{source}: field 'object.{field}' {words}")
    if config.shape == "file":
        check_model_file(config.file, source, config.size)
    return config


def _is_builtin_geometry(config: ObjectConfig) -> bool:
    """Whether `config` has the shape, size and model file of the built-in object of its
    name (a resolved built-in, its mass or friction perhaps set): resolving is idempotent."""
    builtin = BUILTIN_OBJECTS[config.name]
    return (config.shape == builtin.shape and list(config.size) == list(builtin.size)
            and config.file == builtin.file)


def _check_controller(scenario: Scenario, source: str) -> None:
    """What the controller's config class checks of its settings (`problem`), against the
    scenario's RA rate and approach; its numbers' ranges are declared on its fields."""
    controller = scenario.controller
    if not controller_entry(controller).closed_loop:
        return
    problem = controller.problem(ra_rate_hz=scenario.vibration.sample_rate_hz,
                                 approach_s=scenario.grasp.settle_s + scenario.grasp.reach_s)
    if problem is not None:
        field, words, value = problem
        require(False, source, f"controller.{field}", words, value)
    lift_load = getattr(controller, "lift_load", None)
    if lift_load is not None:  # Lift-Load grips at min(grip x force_factor, this cap)
        require(lift_load.max_grip_force_n >= scenario.grasp.grip_force, source,
                "controller.lift_load.max_grip_force_n",
                f"must be at least grasp.grip_force ({scenario.grasp.grip_force:g} N): below "
                "it a slip's Lift-Load would loosen the grip; raise it or lower "
                "grasp.grip_force", lift_load.max_grip_force_n)


# What relates fields, or belongs to Drake's own config classes; each message says why.
MAX_HIT_FORCE_N = 100.0  # five times the paper's 20 N hit, in size
# The longest grasp script without `allow_long`: the paper's lasts about 12 s; a trial takes
# about WALL_S_PER_SIM_S of one core per simulated second (12.25 s in 9.97 s, rounded up).
MAX_SCRIPT_S = 60.0
WALL_S_PER_SIM_S = 1.0


def _check_sensors_and_scene(scenario: Scenario, source: str) -> None:
    """Values that relate a sensor's settings (its config class's `problem`), or put the
    hit outside the trial (each number's own range is declared on its field)."""
    problem = scenario.vibration.problem()
    if problem is not None:
        require(False, source, f"vibration.{problem[0]}", problem[1], problem[2])
    disturbance = scenario.disturbance
    if disturbance.hit_time_s >= 0:
        end = script_duration(scenario)
        require(disturbance.hit_time_s < end, source, "disturbance.hit_time_s",
                f"must come before the grasp's script ends at {end:.1f} s (or be negative: "
                "no hit)", disturbance.hit_time_s)


# Avoid moves along the stroke (y, either way) or up, or along a hit's horizontal push (any
# horizontal way, known only once the hit comes). Checked along the first three; along the
# push the defaults' Avoid is faster than the arm, and the state machine stretches that move
# to what the arm follows (cartesian_arm_controller.followable_move_s;
# docs/model.md, "What each setting may be").
AVOID_DIRECTIONS = ((0.0, 1.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0))


def _hand_moves(scenario: Scenario):
    """(duration field, distance [m], duration [s], what moves, paths) of each arm move the
    trial may ask: each phase of the grasp script, and the closed-loop controller's own moves
    (Avoid's from the lifted pose, a Re-Reach's shift along the stroke of at most half of it
    as the paper's at the grasp pose, the retract after Unload from the placed pose). paths:
    the straight moves ((start, end) [m, world]) it may take; the arm must follow each."""
    from tegrasp_drake.control.scripted_grasp import plan_scripted_grasp
    from tegrasp_drake.robotiq.units import STROKE_M
    at = {}
    for segment in plan_scripted_grasp(grasp_plan(scenario)):
        start, end = segment.X_start.translation(), segment.X_end.translation()
        at[segment.phase] = end
        yield (f"grasp.{segment.phase}_s", float(np.linalg.norm(end - start)),
               getattr(scenario.grasp, f"{segment.phase}_s"),
               f"the {segment.phase.capitalize()} phase", [(start, end)])
    controller = scenario.controller
    if not controller_entry(controller).closed_loop:
        return
    avoid = controller.avoid.distance_m
    yield ("controller.avoid.move_s", avoid, controller.avoid.move_s,
           "Avoid, controller.avoid.distance_m",
           [(at["lift"], at["lift"] + np.multiply(avoid, d)) for d in AVOID_DIRECTIONS])
    shift = np.array([0.0, STROKE_M / 2, 0.0])
    yield ("controller.re_reach.move_s", STROKE_M / 2, controller.re_reach.move_s,
           "a Re-Reach's shift, up to half the 85 mm stroke",
           [(at["reach"], at["reach"] + shift), (at["reach"], at["reach"] - shift)])
    placed, start_xyz = at["place"], scenario.arm.initial_gripper_xyz
    retracted = np.array([max(placed[0] - scenario.grasp.retract_distance, start_xyz[0]),
                          placed[1], start_xyz[2]])  # as the state machine's retract
    yield ("grasp.retract_s", float(np.linalg.norm(retracted - placed)),
           scenario.grasp.retract_s, "the retract after Unload, grasp.retract_distance",
           [(placed, retracted)])


def _check_hand_speeds(scenario: Scenario, source: str) -> None:
    """Each arm move against the fastest the arm can move the hand along it where it is
    (cartesian_arm_controller.shortest_move_s over move_top_speeds_mps: its joints at their
    speed limits, the hand's orientation held), pose by pose along its path: a move asking
    more somewhere leaves the differential IK behind, the arm lags its command and the trial
    would not do what its script says. The moves the state machine decides at run time
    (Avoid along a hit's push, a Re-Reach's shift) it stretches by the same rule
    (followable_move_s)."""
    # every arm move, scripted or corrective, follows the minimum-jerk profile
    from tegrasp_drake.control.cartesian_arm_controller import shortest_move_s
    from tegrasp_drake.control.motion_profiles import MINIMUM_JERK_PEAK_SPEED
    for field, distance, duration, what, move_paths in _hand_moves(scenario):
        if distance <= 0:  # no move (the Settle and Hold phases): it may take no time
            continue
        # a move's duration must not be 0 below (a controller move's declared range excludes
        # it; a config that skipped check_ranges must not divide by it)
        require(duration > 0, source, field, "must be positive [s]: the arm cannot move the "
                f"hand in no time ({what})", duration)
        shortest, binding = 0.0, math.inf  # [s], the top speed [m/s] where it binds
        for start, end in move_paths:
            found = shortest_move_s(start, end)
            if found is None:  # the arm cannot put the hand at a pose of this move
                _refuse_unreachable_move(field, what, start, end, source)
            if found[0] > shortest:
                shortest, binding = found
        if duration < shortest:
            require(False, source, field,
                    f"is too short to move the hand {distance * 1000:.0f} mm ({what}): its "
                    f"minimum-jerk move peaks at "
                    f"{MINIMUM_JERK_PEAK_SPEED * distance / duration:.3g} m/s, more than the "
                    f"JACO2 can move it along its path, its orientation held ({binding:.3g} "
                    f"m/s where it binds); give it at least "
                    f"{math.ceil(shortest * 1000) / 1000:g} s", duration)


# The settings that place each arm move's poses (by its duration field), which a move out of
# the arm's reach names: the start pose, the marker and grasp height, and what each phase adds.
_GRASP_POSE_FIELDS = ("placement.expected_xy", "grasp.grasp_height")
_MOVE_PLACED_BY = {
    "grasp.reach_s": ("arm.initial_gripper_xyz",) + _GRASP_POSE_FIELDS,
    "grasp.lift_s": _GRASP_POSE_FIELDS + ("grasp.lift_height",),
    "grasp.place_s": _GRASP_POSE_FIELDS + ("grasp.lift_height", "grasp.place_offset",
                                           "grasp.place_press"),
    "grasp.retract_s": _GRASP_POSE_FIELDS + ("grasp.place_offset", "grasp.retract_distance",
                                             "arm.initial_gripper_xyz"),
    "controller.avoid.move_s": _GRASP_POSE_FIELDS + ("grasp.lift_height",
                                                     "controller.avoid.distance_m"),
    "controller.re_reach.move_s": _GRASP_POSE_FIELDS,
}


def _refuse_unreachable_move(field: str, what: str, start, end, source: str) -> None:
    """ConfigError naming the fields that place a move (field: its duration) the JACO2 cannot
    follow: no joint angles put the hand at a pose along it in the side grasp's orientation,
    or following it from its start leaves the arm's reach (move_top_speeds_mps is None)."""
    placed_by = _MOVE_PLACED_BY.get(field, (field,))
    fields = ", ".join(f"'{name}'" for name in placed_by)
    raise ConfigError(
        f"{source}: fields {fields} put {what} (from {_mm_text(start)} to {_mm_text(end)} "
        "m) out of the JACO2's reach in the side grasp; place them in front of the arm "
        "(defaults [0.72, 0.0] and [0.69, 0.0, 0.145] m)")


def _mm_text(xyz) -> str:
    return number_text([round(float(v), 3) for v in xyz])


def _open_hand_parts() -> tuple[tuple[float, float, float, float, float], ...]:
    """The open 2F-85's solid parts as boxes about the grasp frame G in the side grasp [m]:
    each (back, front) along the approach (world x, from G), (right, left) across the stroke
    (world y, from G) and half its extent up and down (world z). Both hand models, from the
    dimensions their models are built from: the body, a cylinder of BASE_RADIUS (the
    datasheet's ~75 mm body) from the mounting face (PAD_CENTER_Z behind G) to the palm
    (PALM_Z from it); and each finger, from the palm to its pad's far end (PAD_LENGTH / 2
    beyond G), from its open pad's face (HALF_STROKE from G) out to the wider hand's outer
    face (the prismatic finger's back, or the linkage's widest pin plus half its bar), as
    thick as a pad or a linkage bar, whichever is thicker. The space between the open pads
    is free: a hand may start with an object there (the station's squeeze tests do)."""
    from tegrasp_drake.modelgen.robotiq_linkage_sdf import LINK_BAR_SIZE
    from tegrasp_drake.modelgen.robotiq_sdf import BASE_RADIUS, FINGER_LINK_THICKNESS
    from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH
    from tegrasp_drake.robotiq import linkage
    from tegrasp_drake.robotiq.dimensions import HALF_STROKE, PAD_CENTER_Z, PALM_Z
    outer = max(HALF_STROKE + PAD_THICKNESS + FINGER_LINK_THICKNESS,
                max(float(point[0]) for point in (
                    linkage.A, linkage.B, linkage.C, linkage.D, linkage.E)) + LINK_BAR_SIZE / 2)
    palm, tip, finger_half_z = PALM_Z - PAD_CENTER_Z, PAD_LENGTH / 2, max(PAD_WIDTH,
                                                                          LINK_BAR_SIZE) / 2
    return ((-PAD_CENTER_Z, palm, -BASE_RADIUS, BASE_RADIUS, BASE_RADIUS),
            (palm, tip, HALF_STROKE, outer, finger_half_z),
            (palm, tip, -outer, -HALF_STROKE, finger_half_z))


def check_start_clearance(scenario: Scenario, source: str, spread_m: float = 0.0) -> None:
    """The open hand at its start pose (arm.initial_gripper_xyz, up to
    arm.start_position_bound_m off it each way) clear of the table and of the object where it
    stands (placement.expected_xy + placement.offset, and up to spread_m [m] off it along
    each axis: a sweep's placement jitter). A start on or in the table top (world
    z = 0) is a pose the simulated table does not let the hand take; a start with the body or
    a finger inside the object is one no real trial begins from (the contact solver would
    push them apart at the first step). The object is taken as the upright cylinder about
    its footprint (a box's diagonal: any yaw), from the table top to its height."""
    x, y, z = scenario.arm.initial_gripper_xyz
    margin = scenario.arm.start_position_bound_m
    parts = _open_hand_parts()
    lowest = z - max(part[4] for part in parts) - margin
    if lowest <= 0.0:
        require(False, source, "arm.initial_gripper_xyz",
                f"puts the open hand {-lowest * 1000:.0f} mm into the table top (z = 0; it "
                f"reaches {(z - lowest) * 1000:.1f} mm below the grasp frame, "
                "arm.start_position_bound_m included): start it higher, e.g. "
                "[0.69, 0.0, 0.145] m", list(scenario.arm.initial_gripper_xyz))
    obj = scenario.object
    size = obj.size
    radius = footprint_radius(obj.shape, size)
    cx, cy = scenario.placement.xy()
    reach = margin + spread_m  # the hand's start bound and the object's jitter, each way
    for back, front, right, left, half_z in parts:
        near_x = min(max(cx, x + back - reach), x + front + reach)
        near_y = min(max(cy, y + right - reach), y + left + reach)
        overlaps_xy = math.hypot(cx - near_x, cy - near_y) < radius
        if overlaps_xy and z - half_z - margin < obj.height():
            require(False, source, "arm.initial_gripper_xyz",
                    f"starts the open hand's body or a finger inside the object "
                    f"'{obj.name}' at ({cx:.3f}, {cy:.3f}) m (placement.expected_xy + "
                    "placement.offset"
                    + (f", +-{spread_m * 1000:g} mm of placement jitter" if spread_m else "")
                    + "): start the hand behind or above it, or move it",
                    list(scenario.arm.initial_gripper_xyz))


def script_duration(scenario: Scenario) -> float:
    """When the scenario's scripted grasp ends [s of simulated time]."""
    from tegrasp_drake.control.scripted_grasp import plan_duration, plan_scripted_grasp
    return plan_duration(plan_scripted_grasp(grasp_plan(scenario)))


def _check_capacitive_timing(scenario: Scenario, source: str) -> None:
    """The capacitive taxels' sample rate against their decimation (each field's choices
    are declared on it)."""
    capacitive = scenario.tactile.capacitive
    if scenario.tactile.transducer == "capacitive" and capacitive.ad7147_timing:
        frame = ad7147_frame_rate_hz(capacitive.decimation)
        require(frame_rate_matches(scenario.tactile.sample_rate_hz, capacitive.decimation),
                source, "tactile.sample_rate_hz", f"must be the AD7147's frame rate at "
                f"tactile.capacitive.decimation {capacitive.decimation}, {frame:.1f} Hz (12 "
                f"stages of {1e3 / (12 * frame):.3f} ms): set both together (or "
                f"tactile.capacitive.ad7147_timing=false for an idealised readout)",
                scenario.tactile.sample_rate_hz)


def validate(scenario: Scenario, source: str = "scenario", *,
             allow_long: bool = False, loaded: bool = False) -> Scenario:
    """Checks what the schema cannot (each number's declared range, then what relates
    fields); returns the scenario with its object resolved (loaded: see resolve_object)."""
    with relations_checked():  # the public functions it calls take the scenario as it is
        return _validated(scenario, source, allow_long=allow_long, loaded=loaded)


def _validated(scenario: Scenario, source: str, *, allow_long: bool,
               loaded: bool) -> Scenario:
    try:  # every check below reads the controller's kind
        entry = controller_entry(scenario.controller, f"{source}: field 'controller'")
    except UnknownControllerError as e:
        raise ConfigError(str(e)) from None
    require(isinstance(scenario.controller, entry.config), source, "controller",
            f"must be a controller's config, e.g. {entry.config.__name__}(), not its name "
            "or class", scenario.controller)
    # Each number finite first, then what relates them: a NaN mass is said to be not finite,
    # not "not positive"; a NaN force not "too large".
    check_ranges(scenario, source, numbers_only=True)
    scenario = dataclasses.replace(scenario, object=resolve_object(scenario.object, source,
                                                                   loaded=loaded))
    disturbance = scenario.disturbance
    require(len(disturbance.hit_force_n) == 3, source, "disturbance.hit_force_n",
            "must hold 3 numbers [N] ([x, y, z])", disturbance.hit_force_n)
    force = math.hypot(*disturbance.hit_force_n)
    require(force <= MAX_HIT_FORCE_N, source, "disturbance.hit_force_n",
            f"must be at most {MAX_HIT_FORCE_N:g} N in size (five times the paper's 20 N "
            "hit; the simulated grasp is not made for more)", disturbance.hit_force_n)
    check_ranges(scenario, source)
    check_times_resolved(  # a hardware station's timeouts are the devices', not the plant's
        dataclasses.replace(scenario, station=SimulatedStationConfig())
        if isinstance(scenario.station, HardwareStationConfig) else scenario,
        scenario.plant_config.time_step, source)
    problem = scenario.placement.problem(scenario.object.shape, scenario.object.size)
    if problem is not None:
        require(False, source, f"placement.{problem[0]}", problem[1], problem[2])
    height = scenario.object.height()
    require(scenario.grasp.grasp_height <= height, source, "grasp.grasp_height",
            f"must lie within the object's height, {height:g} m (the pad centre above the "
            "table, on the object's side: higher, the pads close over it)",
            scenario.grasp.grasp_height)
    # The object must fit between the open fingers; an offset beyond that is allowed (a finger
    # then meets it on the way in, as on a robot).
    duration = script_duration(scenario)
    if duration > MAX_SCRIPT_S and not allow_long:
        raise ConfigError(
            f"{source}: field 'grasp': the grasp script lasts {duration:.1f} s, about "
            f"{duration * WALL_S_PER_SIM_S / 60:.0f} min of one core; a trial is at most "
            f"{MAX_SCRIPT_S:g} s (the paper's lasts about 12 s): shorten its phases, or "
            "confirm with --allow-long (LoadScenario(..., allow_long=True))")
    _check_sensors_and_scene(scenario, source)
    _check_controller(scenario, source)
    problem = drive_problem(scenario.arm, scenario.plant_config.time_step)
    if problem:
        field, words, value = problem
        require(False, source, f"arm.{field}", words, value)
    problem = start_pose_problem(scenario.arm)
    if problem:
        field, words, value = problem
        require(False, source, f"arm.{field}", words, value)
    check_start_clearance(scenario, source)
    require(not scenario.contact_geometry.pad_refinement or scenario.gripper.model == "linkage",
            source, "contact_geometry.pad_refinement", "must be 0 with gripper.model prismatic "
            "(the refined pad meshes are the linkage hand's: set gripper.model=linkage, or "
            "leave pad_refinement unset)",
            scenario.contact_geometry.pad_refinement)
    _check_capacitive_timing(scenario, source)
    if isinstance(scenario.station, HardwareStationConfig):
        validate_hardware_config(scenario.station, source, "station")
    else:
        problem = scenario.station.uses_carriage() and side_grasp_problem(
            scenario.placement.expected_xy, scenario.grasp.grasp_height)
        if problem:
            raise ConfigError(f"{source}: fields 'placement.expected_xy' and "
                              f"'grasp.grasp_height' put the side grasp out of the JACO2's "
                              f"reach ({problem}), which the carriage's impedance (station.arm "
                              "carriage) is taken at: choose a marker in front of the arm")
    _check_hand_speeds(scenario, source)  # at poses the checks above found in reach
    return scenario


@public_api
def LoadScenario(filename: PathLike | None = None, name: str = DEFAULT_SCENARIO,
                  overrides: typing.Sequence[str] = (), *,
                  controller: str | None = None, allow_long: bool = False,
                  on_ignored: typing.Callable[[list[str]], None] | None = None) -> Scenario:
    """Loads scenario `name` from `filename` (default: the built-in file) with overrides.
    controller: run it with this controller, keeping the controller settings it has and
    dropping the others' (on_ignored, if given, is called with their names); allow_long:
    accept a grasp script longer than MAX_SCRIPT_S. `overrides` may not set one key twice to
    two values (refuse_a_key_set_twice), as --set may not."""
    refuse_a_key_set_twice(overrides, "LoadScenario", "overrides", kind="argument")
    path = pathlib.Path(filename) if filename else paths.scenarios_file()
    document = read_yaml_file_cached(path, "the scenario file", kind=None)
    if document is not None:  # an empty file: no scenario named `name`, below
        require_mapping(document, path, "the scenario file",
                        "scenario names to scenarios (default: {object: {name: box}})")
    if not document or name not in document:
        raise ConfigError(f"{path}: {_no_scenario_named(name, document)}")
    data = document[name]
    if data is None:  # `x:` alone: an entry left empty, not the default scenario
        raise ConfigError(f"{path}: scenario '{name}' is empty (null): give its fields, or "
                          f"`{name}: {{}}` for the default scenario")
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: scenario '{name}' must be a mapping of fields, got "
                          f"{type(data).__name__} {data!r}")
    for assignment in overrides:
        apply_override(data, assignment)
    _refuse_other_controller_name(data, overrides, controller)
    return loaded_with_overrides(
        lambda source: _checked_scenario(data, source, controller=controller,
                                         allow_long=allow_long, on_ignored=on_ignored),
        f"{path} [{name}]", overrides)


def refuse_listed_override(overrides: typing.Sequence[str], place, *,
                           base: typing.Sequence[str] = (), controller: str | None = None) -> None:
    """For `overrides` a file lists (a sweep's scenario_overrides, a transfer world's
    overrides) that the default scenario, after the `base` assignments, refused: ConfigError
    naming place(k) (the file and the list's entry k) of the first one refused with those
    before it, its assignment, why and what to do. Returns when none is refused so (the base
    is at fault)."""
    for k, assignment in enumerate(overrides):
        document = read_yaml_file_cached(paths.scenarios_file(), "the scenario file", kind=None)
        data = document[DEFAULT_SCENARIO]
        taken = (*base, *overrides[:k + 1])
        try:
            for given in taken:
                apply_override(data, given, option=place(k))
            _refuse_other_controller_name(data, taken, controller)
            _checked_scenario(data, set_words(assignment, place(k)), controller=controller,
                              allow_long=False, on_ignored=None)
        except ConfigError as error:
            raise ConfigError(f"{error}; correct the entry, or drop it") from None


def _refuse_other_controller_name(data: dict, overrides, controller: str | None) -> None:
    """ConfigError when `controller` is given and the overrides select another controller,
    by controller.name or by a section's tag (`controller=!HeuristicControllerConfig {}`):
    neither may silently win."""
    named = [a for a in overrides if keys_overlap(assignment_key(a), "controller.name")]
    name = selected_controller(data.get("controller"))
    if controller is not None and named and name is not None and name != controller:
        raise ConfigError(f"--controller {controller} and --set {named[-1]} select different "
                          "controllers; give one of them")


_SCENARIO_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_.-]*")
# The most scenario names a refusal lists in full (the built-in file holds 11); a longer
# file's others are counted.
_LISTED_SCENARIOS = 30


def _no_scenario_named(name: str, document: dict | None) -> str:
    """Why a scenario file's `document` has no scenario `name`: the names of its scenarios
    (keys that look like a name and map to fields), cut as an echoed value is; keys that are
    no scenario only counted, so that a file of another kind is never shown."""
    names = [str(key) for key, value in (document or {}).items()
             if isinstance(value, dict) and _SCENARIO_NAME.fullmatch(str(key))]
    if names:
        listed = ", ".join(shorten(n) for n in names[:_LISTED_SCENARIOS])
        if len(names) > _LISTED_SCENARIOS:
            listed += f", and {len(names) - _LISTED_SCENARIOS} more"
        close = difflib.get_close_matches(str(name), names, n=1)
        hint = f"; did you mean '{shorten(close[0])}'?" if close else ""
        return f"no scenario named '{shorten(str(name))}' (scenarios: {listed}){hint}"
    keys = len(document or {})
    return (f"no scenario named '{name}', and no scenario at all ({keys} top-level key(s), "
            "none a name mapped to scenario fields): give a scenario file")


def _checked_scenario(data: dict, source: str, *, controller, allow_long, on_ignored):
    """The Scenario of a loaded entry's `data` (its overrides applied), checked; errors name
    `source`."""
    refuse_moved_keys(data, source)
    problem = controller_tag_problem(data.get("controller"))  # as written, before a choice
    if problem:
        raise ConfigError(f"{source}: field 'controller': {problem}")
    if controller is not None:
        check_controller_section_as_written(data, source)
        section = data.setdefault("controller", {})
        section["name"] = controller
        if isinstance(section, dict):
            section.pop("_tag", None)  # the choice replaces the written controller
    try:
        ignored = select_controller_tag(data, drop_others=controller is not None)
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
    scenario = validate(load_typed(data, Scenario, source), source, allow_long=allow_long)
    if ignored and on_ignored is not None:
        on_ignored(ignored)
    return scenario


def check_controller_section_as_written(data: dict, source: str) -> None:
    """ConfigError naming the field unless the YAML data's `controller` section is one a
    load without a choice of controller accepts in its form (a mapping, a known tag) and each
    of its settings is one its controller accepts (type and range): a choice of controller
    replaces the tag and drops the others' settings, which must not hide a mistake."""
    section = data.get("controller", {})
    if not isinstance(section, dict) or "_tag" in section:
        check_fields({"controller": section if not isinstance(section, dict)
                      else {"_tag": section["_tag"]}}, Scenario, source)
    by_owner: dict[type, dict] = {}
    for key, value in section.items():
        owner = next((cls for cls in CONTROLLER_CLASSES if key in _field_names(cls)), None)
        if owner is not None:
            by_owner.setdefault(owner, {})[key] = value
    for owner, settings in by_owner.items():
        checked = load_typed({"controller": {"_tag": f"!{owner.__name__}", **settings}},
                             Scenario, source)
        check_ranges(checked.controller, source, "controller")


def _field_names(cls) -> set[str]:
    return {field.name for field in dataclasses.fields(cls)}


def rechecked(scenario: Scenario, source: str) -> Scenario:
    """`scenario` checked again as LoadScenario checks it, for a builder given one a script
    may have changed after loading (ranges, list lengths, the object's sizes for its shape);
    returned with its object resolved (a bare Scenario() is the built-in box). A long grasp
    script is accepted: that limit is LoadScenario's allow_long."""
    return validate(scenario, source, allow_long=True, loaded=True)


@public_api
def grasp_plan(scenario: Scenario):
    """The GraspPlan of the scenario: its grasp script placed for its expected object, by
    its hand, from its arm's start pose."""
    from tegrasp_drake.control.machine_state import GraspPlan
    return GraspPlan.make(scenario.grasp, start_xyz=scenario.arm.initial_gripper_xyz,
                          expected_object_xy=scenario.placement.expected_xy,
                          object=scenario.object, gripper_model=scenario.gripper.model)


def object_pose(scenario: Scenario):
    """X_WO of the scenario's object: on its marker, moved by its offset, yawed."""
    from tegrasp_drake.simulation.station import object_pose_on_table
    placement = scenario.placement
    return object_pose_on_table(placement.expected_xy, placement.offset, placement.yaw_deg)


def controller_in_force(scenario: Scenario):
    """The scenario's controller config with the RA and SA thresholds it runs with: raised
    to the noise of the scenario's film and taxel electronics (control/noise_thresholds.py);
    the open-loop script's as it is."""
    controller = scenario.controller
    if not controller_entry(controller).closed_loop:
        return controller
    from tegrasp_drake.control.noise_thresholds import resolve_noise_thresholds
    return resolve_noise_thresholds(
        controller, ra_noise_std_mps2=ra_noise_std_mps2(scenario.vibration),
        ra_rate_hz=scenario.vibration.sample_rate_hz, tactile=scenario.tactile,
        sa_rate_hz=scenario.tactile.sample_rate_hz)


@public_api
def sample_rates_hz(scenario: Scenario) -> tuple[float, float]:
    """The live SA (taxel) and RA (film) sample rates [Hz] the controller's matchers read."""
    return scenario.tactile.sample_rate_hz, scenario.vibration.sample_rate_hz


@public_api
def with_controller(scenario: Scenario,
                    name: typing.Annotated[str, Choice(CONTROLLER_NAMES)]) -> Scenario:
    """`scenario` run by the controller called `name` (controller_config.CONTROLLER_NAMES),
    keeping the settings its config class shares with the scenario's controller."""
    return dataclasses.replace(scenario, controller=controller_named(
        name, like=scenario.controller))


def scenario_from_yaml(text: str, source: str = "the logged scenario") -> Scenario:
    """The Scenario of YAML text that scenario_to_yaml wrote (a log's, stored), also in the
    flat layout of older records (moved_keys.migrate_stored_scenario). Its values are checked
    as a loaded scenario's are; ConfigError names `source` and the field."""
    try:
        data = migrate_stored_scenario(parse_yaml(text, source) or {})
        select_controller_tag(data, drop_others=True)
        # load_typed walks the fields first (check_fields), as LoadScenario's loading does: a
        # key or section that corrupt bytes changed is named, never handed to Drake's loader
        scenario = load_typed(data, Scenario, source, stored=True)
    except (RuntimeError, ValueError, TypeError, AttributeError, yaml.YAMLError) as e:
        if isinstance(e, ConfigError):
            raise
        raise ConfigError(f"{source}: is not a scenario: {e}") from None
    check_ranges(scenario, source)
    check_times_resolved(
        dataclasses.replace(scenario, station=SimulatedStationConfig())
        if isinstance(scenario.station, HardwareStationConfig) else scenario,
        scenario.plant_config.time_step, source)
    return scenario


@public_api
def scenario_to_yaml(scenario: Scenario) -> str:
    """The scenario as YAML text (for logs and provenance), without its empty "not set"
    fields (rig/unset_fields.py), so that it reads back as a scenario file."""
    return without_unset_fields(yaml_dump_typed(scenario), scenario)
