"""Every system's docstring has a `.. pydrake_system::` block naming its real ports, in
order; so has every function that builds a Diagram of compiled systems in place of a
system (`Make<Name>`, its block named <Name>).

The block is Drake's (YAML: name, input_ports, output_ports); a port name may carry an
" (optional)" note, as in GraspStateMachine. Systems whose ports depend on constructor
arguments (DeviceWatchdog, FaultLatch) document, and are built here with, the arguments
MakeHardwareStation uses.
"""

import contextlib
import functools
import importlib
import inspect
import pkgutil
import re

import numpy as np
import pytest
import yaml
from pydrake.geometry import Meshcat
from pydrake.lcm import DrakeLcm
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import Diagram, DiagramBuilder, LeafSystem

import tegrasp_drake
from tegrasp_drake.control.controller_config import (
    GraspControllerConfig, HeuristicTriggerConfig)
from tegrasp_drake.control.grasp_modes import Trigger
from tegrasp_drake.control.grasp_state_machine import GraspStateMachine
from tegrasp_drake.control.grasp_wrench_estimator import GraspWrenchEstimator
from tegrasp_drake.control.heuristic_event_detector import HeuristicEventDetector
from tegrasp_drake.control.scripted_grasp import ScriptedGraspSource, plan_scripted_grasp
from tegrasp_drake.emulators.myrio_emulator import MyRioEmulator, TactileRecording
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator
from tegrasp_drake.events.event_matcher import EventMatcher, EventMatcherConfig
from tegrasp_drake.events.ra_envelope import RaEnvelope
from tegrasp_drake.events.ra_noise_floor import RaNoiseFloor
from tegrasp_drake.events.event_sequencer import EventSequencer
from tegrasp_drake.events.events_folder import load_memorized_events
from benchmarks.drivers import LoopTick
from benchmarks.matcher import _InputReader
from benchmarks.per_step_python import BarePythonOutput, PythonPadStatics, linkage_pad_statics
from tegrasp_drake.scenario.scenario import LoadScenario, grasp_plan
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.hardware.device_log_messages import GripperStatusSender, TactileStatusSender
from tegrasp_drake.hardware.fault_latch import FaultLatch
from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JacoCommandReceiver, JacoCommandSender, JacoStatusReceiver, JacoStatusSender)
from tegrasp_drake.rig.jaco_velocity_tracker import JacoVelocityTracker
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver
from tegrasp_drake.hardware.robotiq.modbus_client import RobotiqModbusClient
from tegrasp_drake.hardware.robotiq.robotiq_driver import RobotiqDriver
from tegrasp_drake.hardware.station import HardwareStation, MakeHardwareStation
from tegrasp_drake.hardware.watchdog import DeviceWatchdog
from tegrasp_drake.rig import paths
from tegrasp_drake.tactile.mechanoreceptor_channels import (MakeMechanoreceptorChannels,
                                                           SlowlyAdapting)
from tegrasp_drake.tactile.slip_band_diagram import MakeSlipVibrationBand
from tegrasp_drake.tactile.slip_vibration_band import SlipVibrationBand
from tegrasp_drake.tactile.window_normalizer import WindowNormalizer
from tegrasp_drake.simulation.taxel_force_display import (TaxelForceDisplay,
                                                          TaxelForceDisplayConfig)
from tegrasp_drake.simulation.validation_scenes import FingerDrive, GripProgram
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.simulation.linkage_pad_statics import LinkagePadStatics
from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
from tegrasp_drake.simulation.film_chain import MakePadFilms
from tegrasp_drake.simulation.film_dynamics import film_step_matrices
from tegrasp_drake.simulation.film_loads import FilmLoads
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig, film_parameters
from tegrasp_drake.simulation.station import pad_geometries
from tegrasp_drake.simulation.body_force_pulse import BodyForcePulse
from tegrasp_drake.simulation.pad_slip_vibration import PadSlipVibration
from tegrasp_drake.simulation.tactile_pads import TactilePads, TactileSensorConfig
from tegrasp_drake.simulation.capacitive_taxels import CapacitiveTaxelConfig, CapacitiveTaxels
from tegrasp_drake.simulation.pad_accelerometers import PadAccelerometers
from tegrasp_drake.simulation.carriage import AddCarriage
from tegrasp_drake.simulation.carriage_systems import CarriageCommand, CarriageWristWrench
from tegrasp_drake.simulation.pad_normal_forces import PadNormalForces
from tegrasp_drake.scenario.grasp_diagram import station_carriage
from tegrasp_drake.simulation.station import initial_arm_positions
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig,
                                                         MakeSimRobotiqDriver, SimRobotiqPlanner)

EVENT_INDICES = {"reach_load": 0, "load_lift": 1, "place_unload": 2}


@functools.cache
def box_scenario():
    return LoadScenario(name="box")


@functools.cache
def gripper_plant():
    """A finalized plant holding only the (linkage) gripper, and its pads."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    (gripper,) = paths.make_parser(plant).AddModels(
        url="package://tegrasp/robotiq_2f85/robotiq_2f85_linkage.sdf")
    plant.Finalize()
    return plant, pad_geometries(plant, scene_graph, gripper)


@functools.cache
def welded_linkage_gripper():
    """A finalized plant that holds only the linkage gripper, welded to the world, its
    gripper instance and its pads."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    (gripper,) = paths.make_parser(plant).AddModels(url=gripper_hand("linkage").url)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper))
    plant.Finalize()
    return plant, gripper, pad_geometries(plant, scene_graph, gripper)


def pad_films():
    """The films' Diagram (MakePadFilms) with every optional port (the pad forces through
    LinkagePadStatics)."""
    plant, gripper, pads = welded_linkage_gripper()
    return MakePadFilms(plant=plant, pads=pads, force_indices=(0, 1),
                        config=VibrationSensorConfig(noise_std_mps2=0.05),
                        pad_modulus_pa=PAD_MODULUS, with_texture=True,
                        pad_statics=LinkagePadStatics(plant, gripper),
                        with_drive_vibration=True)


def film_loads() -> FilmLoads:
    plant, gripper, pads = welded_linkage_gripper()
    config = VibrationSensorConfig()
    return FilmLoads(plant=plant, pads=pads, force_indices=(0, 1), config=config,
                     pad_modulus_pa=PAD_MODULUS,
                     matrices=film_step_matrices(film_parameters(config), 1e-3, 20000.0),
                     with_texture=True, pad_statics=LinkagePadStatics(plant, gripper))


@contextlib.contextmanager
def hardware_station():
    """The station on in-process emulators (pty serial ports, memq:// LCM): real device
    threads, no hardware."""
    t = np.arange(0.0, 0.2, 1e-3)
    quiet = TactileRecording(t, np.zeros((len(t), 12)), np.zeros((len(t), 12)), t,
                             np.zeros((len(t), 3)), np.zeros(len(t)))
    with RobotiqEmulator() as gripper, MyRioEmulator(quiet) as myrio:
        config = HardwareStationConfig()
        config.gripper.port, config.tactile.port = gripper.port, myrio.port
        with MakeHardwareStation(config, lcm=DrakeLcm("memq://")) as station:
            yield station


@functools.cache
def carriage():
    """A Carriage (its plant finalized), with the arm's impedance at the box's grasp pose."""
    plant = MultibodyPlant(1e-3)
    made = AddCarriage(plant, station_carriage(LoadScenario(
        name="box", overrides=["station.arm=carriage"])))
    plant.Finalize()
    return made


# Class -> a zero-argument factory of a real instance, or of a context manager yielding one.
# The device drivers get their real I/O objects unstarted: their constructors open nothing.
CONSTRUCTORS = {
    SlowlyAdapting: SlowlyAdapting,
    WindowNormalizer: WindowNormalizer,
    RaEnvelope: lambda: RaEnvelope(cutoff_hz=2.0, ra_rate_hz=1000.0),
    SlipVibrationBand: lambda: SlipVibrationBand(band_hz=80.0, window_s=0.01,
                                                 sample_rate_hz=1000.0),
    EventMatcher: lambda: EventMatcher(  # with the RA noise floor: every optional port
        load_memorized_events(paths.package_events_dir(), "box"),
        EventMatcherConfig(ra_noise_floor_sigmas=5.39)),
    RaNoiseFloor: lambda: RaNoiseFloor(sigmas=5.39, quiet_s=2.0, ra_rate_hz=1000.0,
                                       envelope_hz=2.0),
    EventSequencer: lambda: EventSequencer([0, 1, 2]),
    GraspStateMachine: lambda: GraspStateMachine(
        plan=grasp_plan(box_scenario()), config=GraspControllerConfig(),
        event_indices=EVENT_INDICES, event_trigger=Trigger.MEMORIZED_EVENT),
    HeuristicEventDetector: lambda: HeuristicEventDetector(HeuristicTriggerConfig(),
                                                           grip_force_n=25.0),
    ScriptedGraspSource: lambda: ScriptedGraspSource(plan_scripted_grasp(grasp_plan(box_scenario()))),
    LoopTick: lambda: LoopTick([]),
    GraspWrenchEstimator: GraspWrenchEstimator,
    _InputReader: _InputReader,
    BarePythonOutput: lambda: BarePythonOutput(4),
    PythonPadStatics: lambda: PythonPadStatics(linkage_pad_statics()),
    DeviceWatchdog: DeviceWatchdog,
    FaultLatch: lambda: FaultLatch(["watchdog", "gripper", "tactile"]),
    JacoVelocityTracker: JacoVelocityTracker,
    JacoCommandSender: JacoCommandSender,
    JacoCommandReceiver: JacoCommandReceiver,
    JacoStatusSender: JacoStatusSender,
    JacoStatusReceiver: JacoStatusReceiver,
    TactileStatusSender: TactileStatusSender,
    GripperStatusSender: GripperStatusSender,
    TactileSerialReceiver: lambda: TactileSerialReceiver(TactileSerialReader("/dev/unused")),
    RobotiqDriver: lambda: RobotiqDriver(RobotiqModbusClient(HardwareStationConfig().gripper)),
    HardwareStation: hardware_station,
    FingerDrive: lambda: FingerDrive(program=GripProgram(start_q=0.02), position_gain=4000.0),
    FilmLoads: film_loads,
    CapacitiveTaxels: lambda: CapacitiveTaxels(config=CapacitiveTaxelConfig(),
                                                pad_modulus_pa=2.0e6),
    PadAccelerometers: lambda: PadAccelerometers(sample_rate_hz=1000.0, highpass_cutoff_hz=2.0,
                                                 noise_std_mps2=0.05),
    PadNormalForces: lambda: PadNormalForces(plant=gripper_plant()[0], pads=gripper_plant()[1]),
    SimRobotiqPlanner: lambda: SimRobotiqPlanner(config=GripperDriverConfig()),
    BodyForcePulse: lambda: BodyForcePulse(body_index=BodyIndex(1), p_BQ=[0.0, 0.0, 0.0],
                                           f_W=[0.0, 50.0, 0.0], start_s=1.0),
    PadSlipVibration: lambda: PadSlipVibration(pads=gripper_plant()[1], object_body_index=0,
                                               config=VibrationSensorConfig()),
    TactilePads: lambda: TactilePads(pads=gripper_plant()[1], config=TactileSensorConfig(),
                                     seed=0),
    CarriageCommand: lambda: CarriageCommand(
        carriage(), initial_positions=initial_arm_positions(LoadScenario(name="box").arm),
        period_s=1e-3),
    CarriageWristWrench: lambda: CarriageWristWrench(weld_index=0, gripper_body_index=0),
    TaxelForceDisplay: lambda: TaxelForceDisplay(meshcat=Meshcat(), pads={},
                                                 config=TaxelForceDisplayConfig()),
}

# Documented systems that are not built here, with the reason. Empty: every one is cheap.
NOT_CONSTRUCTED = {}

_OPTIONAL = re.compile(r"\s*\(optional\)$")


def pydrake_system_block(cls) -> dict | None:
    """The `.. pydrake_system::` block of cls's own docstring (a function's: its docstring)
    as {name, input_ports, output_ports} (port names without their "(optional)" note);
    None without one."""
    doc = cls.__dict__.get("__doc__") if inspect.isclass(cls) else cls.__doc__
    lines = inspect.cleandoc(doc or "").splitlines()
    starts = [i for i, line in enumerate(lines) if line.strip() == ".. pydrake_system::"]
    if not starts:
        return None
    indent = len(lines[starts[0]]) - len(lines[starts[0]].lstrip())
    body = []
    for line in lines[starts[0] + 1:]:
        if line.strip() and len(line) - len(line.lstrip()) <= indent:
            break
        body.append(line)
    block = yaml.safe_load(inspect.cleandoc("\n".join(body)))
    return {"name": block["name"],
            **{key: [_OPTIONAL.sub("", port) for port in block.get(key) or []]
               for key in ("input_ports", "output_ports")}}


@functools.cache
def system_classes() -> tuple[type, ...]:
    """Every LeafSystem or Diagram subclass defined in a module of the package."""
    found = []
    for module_info in pkgutil.walk_packages(tegrasp_drake.__path__, "tegrasp_drake."):
        if module_info.name.rsplit(".", 1)[-1] == "__main__":
            continue  # runs the command line when imported
        module = importlib.import_module(module_info.name)
        found += [cls for cls in vars(module).values()
                  if inspect.isclass(cls) and cls.__module__ == module.__name__
                  and issubclass(cls, (LeafSystem, Diagram))]
    return tuple(found)


def port_names(system) -> dict[str, list[str]]:
    return {"input_ports": [system.get_input_port(i).get_name()
                            for i in range(system.num_input_ports())],
            "output_ports": [system.get_output_port(i).get_name()
                             for i in range(system.num_output_ports())]}


def _qualified(cls) -> str:
    return f"{cls.__module__}.{cls.__qualname__}"


@pytest.mark.parametrize("cls", list(CONSTRUCTORS), ids=lambda cls: cls.__name__)
def test_block_lists_the_constructed_systems_ports_in_order(cls):
    block = pydrake_system_block(cls)
    assert block is not None, f"{_qualified(cls)} has no .. pydrake_system:: block"
    assert block["name"] == cls.__name__
    made = CONSTRUCTORS[cls]()
    with made if hasattr(made, "__enter__") else contextlib.nullcontext(made) as system:
        assert isinstance(system, cls)
        assert {key: block[key] for key in ("input_ports", "output_ports")} == \
            port_names(system)


def test_every_system_class_has_a_block():
    missing = [_qualified(cls) for cls in system_classes()
               if pydrake_system_block(cls) is None]
    assert missing == []


# Builder function -> a zero-argument factory of the Diagram it builds.
BUILDERS = {
    MakePadFilms: pad_films,
    MakeMechanoreceptorChannels: MakeMechanoreceptorChannels,
    MakeSimRobotiqDriver: lambda: MakeSimRobotiqDriver(config=GripperDriverConfig(),
                                                       time_step=1e-3),
    MakeSlipVibrationBand: lambda: MakeSlipVibrationBand(band_hz=80.0, window_s=0.01,
                                                         sample_rate_hz=1000.0),
}


@functools.cache
def documented_builders() -> tuple:
    """Every function of the package named Make<Name> whose docstring has a block."""
    found = []
    for module_info in pkgutil.walk_packages(tegrasp_drake.__path__, "tegrasp_drake."):
        if module_info.name.rsplit(".", 1)[-1] == "__main__":
            continue
        module = importlib.import_module(module_info.name)
        found += [function for name, function in vars(module).items()
                  if name.startswith("Make") and inspect.isfunction(function)
                  and inspect.unwrap(function).__module__ == module.__name__
                  and pydrake_system_block(function) is not None]
    return tuple(found)


@pytest.mark.parametrize("builder", list(BUILDERS), ids=lambda f: f.__name__)
def test_builder_block_lists_the_built_diagrams_ports_in_order(builder):
    block = pydrake_system_block(builder)
    assert block is not None, f"{builder.__name__} has no .. pydrake_system:: block"
    assert block["name"] == builder.__name__.removeprefix("Make")
    diagram = BUILDERS[builder]()
    assert isinstance(diagram, Diagram)
    assert {key: block[key] for key in ("input_ports", "output_ports")} == \
        port_names(diagram)


def test_every_documented_builder_is_checked_against_its_ports():
    unchecked = [f"{f.__module__}.{f.__name__}" for f in documented_builders()
                 if inspect.unwrap(f) not in {inspect.unwrap(b) for b in BUILDERS}]
    assert unchecked == [], "add them to BUILDERS"


def test_every_documented_system_is_checked_against_its_ports():
    unchecked = [_qualified(cls) for cls in system_classes()
                 if pydrake_system_block(cls) is not None
                 and cls not in CONSTRUCTORS and cls not in NOT_CONSTRUCTED]
    assert unchecked == [], "add them to CONSTRUCTORS (or NOT_CONSTRUCTED, with the reason)"
