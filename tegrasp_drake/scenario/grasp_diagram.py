"""The grasp diagram: a station (simulated or hardware, by the scenario's `station` tag),
the grasp controller wired to its measured ports, and the trial's loggers unless
`log=False`. Both stations export the same ports, so the controller cannot tell them apart.
`MakeSimulator` is the one simulator set-up for simulated, open-loop and hardware runs."""

import dataclasses

from pydrake.common import RandomGenerator
from pydrake.systems.analysis import ApplySimulatorConfig, Simulator
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.framework import System
from pydrake.geometry import Meshcat
from pydrake.lcm import DrakeLcm

from tegrasp_drake.control.controller_registry import CONTROLLER_CLASSES, controller_entry
from tegrasp_drake.control.grasp_controller import AddGraspController, GraspController
from tegrasp_drake.control.grasp_modes import TERMINAL_MODES, Transition
from tegrasp_drake.control.scripted_grasp import (longest_script_s, plan_duration,
                                                  plan_scripted_grasp)
from tegrasp_drake.scenario.scenario_events import load_controller_events, load_corrective_events
from tegrasp_drake.scenario.trial_log_writer import TrialLoggers, AddTrialLogging
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.scenario.scenario import (grasp_plan, object_pose, ra_noise_std_mps2,
                                             sample_rates_hz)
from tegrasp_drake.simulation.carriage import arm_endpoint_impedance
from tegrasp_drake.simulation.station import (MakeGraspStation, SimulatedStationConfig,
                                              side_grasp_pose)
from tegrasp_drake.scenario.scenario import Scenario, rechecked
from tegrasp_drake.rig.api_boundary import public_api, public_dataclass
from tegrasp_drake.rig.ranges import SIMULATED_DURATION, Range

# Beyond the ideal grasp's duration, for corrections [s] (and the controller's extra_time_s).
EXTRA_TIME_S = 10.0


@public_api
def MakeStation(scenario: Scenario, *, meshcat: Meshcat | None = None,
                lcm: DrakeLcm | None = None):
    """The station of `scenario` as its `station` tag says: MakeSimulatedStation (default) or
    MakeHardwareStation (in a `with` block, as run_on_hardware does), both with the same ports."""
    scenario = rechecked(scenario, "MakeStation: scenario")  # changed after loading?
    if isinstance(scenario.station, HardwareStationConfig):
        from tegrasp_drake.hardware.station import MakeHardwareStation
        return MakeHardwareStation(scenario.station, lcm=lcm)
    return MakeSimulatedStation(scenario, meshcat=meshcat)


def station_carriage(scenario):
    """The carriage's impedance when the simulated station rides the gripper on one
    (`station.arm: carriage`): the arm's at the side grasp over the object's marker; else None.
    That grasp is in reach: validate checks it where the scenario is loaded or handed over."""
    station = scenario.station
    if not (isinstance(station, SimulatedStationConfig) and station.uses_carriage()):
        return None
    return arm_endpoint_impedance(scenario.arm, side_grasp_pose(
        scenario.placement.expected_xy, scenario.grasp.grasp_height))


@public_api
def MakeSimulatedStation(scenario: Scenario, *, meshcat: Meshcat | None = None):
    """MakeGraspStation with the scenario's sections, whatever its `station` tag says."""
    scenario = rechecked(scenario, "MakeSimulatedStation: scenario")  # changed after loading?
    return MakeGraspStation(
        plant_config=scenario.plant_config, arm=scenario.arm, gripper=scenario.gripper,
        object=scenario.object, X_WO=object_pose(scenario), tactile=scenario.tactile,
        vibration=scenario.vibration, disturbance=scenario.disturbance,
        random_seed=scenario.random_seed, grasp_height=scenario.grasp.grasp_height,
        carriage=station_carriage(scenario), contact_geometry=scenario.contact_geometry,
        meshcat=meshcat)


@public_api
def AddScenarioController(builder: DiagramBuilder, scenario: Scenario, *, station: System,
                          events: dict | None = None,
                          corrective_events: dict | None = None) -> GraspController:
    """AddGraspController with the scenario's sections, events and noise-following thresholds."""
    controller = scenario.controller
    if events is None and controller_entry(controller).event_triggered:
        events = load_controller_events(scenario)
    if corrective_events is None and controller.memorized_corrective.events:
        corrective_events = load_corrective_events(scenario)
    return AddGraspController(builder, controller=controller, plan=grasp_plan(scenario),
                              station=station, arm=scenario.arm,
                              sample_rates_hz=sample_rates_hz(scenario), events=events,
                              corrective_events=corrective_events,
                              ra_noise_std_mps2=ra_noise_std_mps2(scenario.vibration),
                              tactile=scenario.tactile)


@public_dataclass
@dataclasses.dataclass
class GraspDiagram:
    """A built grasp diagram and the parts that a run reads."""
    diagram: Diagram
    station: object              # the station subsystem
    controller: GraspController  # the controller's systems and ports
    loggers: TrialLoggers | None  # None when built with log=False
    time_limit: float            # [s] the longest the run may take (the plan plus corrections)


@public_api
def MakeGraspDiagram(scenario: Scenario, *, station: System | None = None,
                     events: dict | None = None, corrective_events: dict | None = None,
                     meshcat: Meshcat | None = None, log: bool = True) -> GraspDiagram:
    """Builds the station and the scenario's controller into one Diagram. station: default
    MakeStation's; events, corrective_events: default the package's for the scenario's object;
    log: add the TrialLog loggers."""
    scenario = rechecked(scenario, "MakeGraspDiagram: scenario")  # changed after loading?
    builder = DiagramBuilder()
    if station is None:
        station = MakeStation(scenario, meshcat=meshcat)
    station = builder.AddNamedSystem("station", station)
    grasp = AddScenarioController(builder, scenario, station=station, events=events,
                                  corrective_events=corrective_events)
    machine = grasp.state_machine
    if station.HasOutputPort(ports.DEVICE_FAULT) and machine.HasInputPort(ports.DEVICE_FAULT):
        builder.Connect(station.GetOutputPort(ports.DEVICE_FAULT),
                        machine.GetInputPort(ports.DEVICE_FAULT))
    loggers = None
    if log:
        loggers = AddTrialLogging(builder, scenario=scenario, station=station,
                                    channels=grasp.channels,
                                    arm_desired_state=grasp.arm_desired_state,
                                    gripper_command=grasp.gripper_command, phase=grasp.mode)
    diagram = builder.Build()
    diagram.set_name(f"grasp_{grasp.name}")
    return GraspDiagram(diagram, station, grasp, loggers, scenario_time_limit(scenario))


def longest_trial_s(allow_long: bool = True) -> float:
    """The longest simulated run [s] a trial can last: the longest grasp script (with
    `allow_long` the longest its phases' ranges allow, longest_script_s; without, as a sweep
    loads its scenarios, MAX_SCRIPT_S) plus EXTRA_TIME_S and the largest controller
    extra_time_s, the most scenario_time_limit gives; a trial's times (TrialResult) lie
    within it."""
    from tegrasp_drake.scenario.scenario import MAX_SCRIPT_S
    script_s = longest_script_s() if allow_long else MAX_SCRIPT_S
    return script_s + EXTRA_TIME_S + max(config.extra_time_s for config in CONTROLLER_CLASSES)


def scenario_time_limit(scenario: Scenario) -> float:
    """The longest a run of `scenario` may take [s of simulated time]: its grasp script plus
    EXTRA_TIME_S and its controller's extra_time_s for corrections. The script is bounded by
    its fields' ranges and by LoadScenario (MAX_SCRIPT_S, unless allow_long)."""
    return (plan_duration(plan_scripted_grasp(grasp_plan(scenario))) + EXTRA_TIME_S
            + scenario.controller.extra_time_s)


def simulated_duration_range(scenario: Scenario) -> Range:
    """The simulated time [s] a caller may ask a run of `scenario` for (run_trial's max_time,
    run_ideal_grasp's duration): SIMULATED_DURATION up to scenario_time_limit, the time
    `tegrasp trial` runs to; a longer one would only simulate a machine that has stopped, or
    one that never ends."""
    return dataclasses.replace(SIMULATED_DURATION, high=scenario_time_limit(scenario),
                               why="the scenario's time limit: its grasp script plus time for "
                                   "corrections")


@public_api
def MakeSimulator(diagram: Diagram, scenario: Scenario, *,
                  realtime: bool = False) -> Simulator:
    """A Simulator of `diagram` with the scenario's SimulatorConfig and its random seed
    (sensor noise); realtime: paced at real-time rate 1 (hardware)."""
    simulator = Simulator(diagram)
    ApplySimulatorConfig(scenario.simulator_config, simulator)
    if realtime:
        simulator.set_target_realtime_rate(1.0)
    diagram.SetRandomContext(simulator.get_mutable_context(),
                             RandomGenerator(scenario.random_seed))
    return simulator


def is_finished(transitions: list[Transition]) -> bool:
    """True once the state machine reached Done or Failed."""
    return bool(transitions) and transitions[-1].to_mode in TERMINAL_MODES
