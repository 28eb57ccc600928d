"""The plant-alone floor of a trial: the station's MultibodyPlant with the same contacts, its
inputs replayed, and nothing else (no tactile pads, films, gripper driver, matcher, state
machine, Cartesian controller or loggers).

`record_plant_inputs` runs one closed-loop trial and records, at every plant step, the two
inputs the plant read: the arm's desired state (the Cartesian controller's output) and the
gripper's PD set-point (the simulated 2F-85 controller's output). `run_plant_floor` builds
the same plant (simulation/station.py `AddStationPlant`) and drives it with those samples
held over each step, so it makes the same contacts for the same time. Its cost is what the
trial would cost if every system around the plant were free.
"""

import dataclasses
import time

import numpy as np
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.control.grasp_modes import TERMINAL_MODES
from tegrasp_drake.control.scripted_grasp import plan_duration, plan_scripted_grasp
from tegrasp_drake.scenario.grasp_diagram import (EXTRA_TIME_S, AddScenarioController,
                                                  MakeSimulatedStation, MakeSimulator,
                                                  station_carriage)
from tegrasp_drake.scenario.scenario import grasp_plan, object_pose
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.simulation.station import AddStationPlant

END_MARGIN_S = 0.5  # as a trial: simulated after the state machine ends
CHECK_PERIOD_S = 0.25


@dataclasses.dataclass
class PlantInputs:
    """The plant's inputs at each plant step of one trial and where the object ended."""
    times: np.ndarray  # (N,) [s]
    arm_desired_state: np.ndarray  # (12, N): q, v of the arm [rad] or the carriage [m, rad]
    gripper_desired_state: np.ndarray  # (2, N): q [m], v [m/s]
    final_object_position: np.ndarray  # (3,) p_WO [m] at the end of the trial


def _unique_samples(log) -> tuple[np.ndarray, np.ndarray]:
    """A logger's (times, data) with repeated times (the initial publish) dropped."""
    times, data = log.sample_times(), log.data()
    keep = np.concatenate([[True], np.diff(times) > 0.0])
    return times[keep], data[:, keep]


def record_plant_inputs(scenario, *, events=None) -> PlantInputs:
    """Runs the closed-loop trial of `scenario` (its controller; memorized `events`, default
    the package's) to its end and records the plant's inputs at every plant step."""
    builder = DiagramBuilder()
    station = builder.AddNamedSystem("station", MakeSimulatedStation(scenario))
    grasp = AddScenarioController(builder, scenario, station=station, events=events)
    # The set-point the plant's arm PD reads: the arm's servo's, or the carriage's.
    arm_log = LogVectorOutput(station.GetOutputPort(ports.CARRIAGE_DESIRED_STATE)
                              if station.HasOutputPort(ports.CARRIAGE_DESIRED_STATE)
                              else station.GetOutputPort(ports.ARM_SERVO_SET_POINT), builder)
    gripper_log = LogVectorOutput(station.GetOutputPort(ports.GRIPPER_PLANT_DESIRED_STATE),
                                  builder)
    object_port = station.GetOutputPort(ports.OBJECT_STATE)
    diagram = builder.Build()
    simulator = MakeSimulator(diagram, scenario)
    context = simulator.get_mutable_context()
    limit = plan_duration(plan_scripted_grasp(grasp_plan(scenario))) + EXTRA_TIME_S
    simulator.Initialize()
    ended = False
    while context.get_time() < limit - 1e-9:
        simulator.AdvanceTo(min(context.get_time() + CHECK_PERIOD_S, limit))
        if not ended and grasp.current_mode(context) in TERMINAL_MODES:
            ended = True
            limit = min(limit, context.get_time() + END_MARGIN_S)
    times, arm = _unique_samples(arm_log.FindLog(context))
    gripper_times, gripper = _unique_samples(gripper_log.FindLog(context))
    if not np.array_equal(times, gripper_times):
        raise RuntimeError("the arm and gripper inputs were not logged at the same steps")
    station_context = station.GetMyContextFromRoot(context)
    final = object_port.Eval(station_context)[4:7].copy()
    return PlantInputs(times, arm, gripper, final)


def _held(times: np.ndarray, values: np.ndarray) -> TrajectorySource:
    """A source that outputs values[:, k] from times[k] until times[k + 1]."""
    return TrajectorySource(PiecewisePolynomial.ZeroOrderHold(times, values))


@dataclasses.dataclass
class FloorRun:
    """One plant-alone run: simulated, wall and process CPU time [s], and how far the
    object ended from where the trial left it [m]."""
    sim_time_s: float
    wall_time_s: float
    cpu_time_s: float
    object_deviation_m: float


def build_plant_floor(scenario, inputs: PlantInputs):
    """(Simulator, StationPlant) of the station's plant alone, driven by `inputs`."""
    builder = DiagramBuilder()
    parts = AddStationPlant(builder, plant_config=scenario.plant_config, arm=scenario.arm,
                            gripper=scenario.gripper, object=scenario.object,
                            X_WO=object_pose(scenario),
                            pad_modulus_pa=scenario.tactile.pad_modulus_pa,
                            random_seed=scenario.random_seed,
                            carriage=station_carriage(scenario),
                            contact_geometry=scenario.contact_geometry)
    plant = parts.plant
    arm = builder.AddSystem(_held(inputs.times, inputs.arm_desired_state))
    builder.Connect(arm.get_output_port(), plant.get_desired_state_input_port(parts.arm))
    gripper = builder.AddSystem(_held(inputs.times, inputs.gripper_desired_state))
    builder.Connect(gripper.get_output_port(),
                    plant.get_desired_state_input_port(parts.gripper))
    diagram = builder.Build()
    return MakeSimulator(diagram, scenario), parts


def run_plant_floor(scenario, inputs: PlantInputs) -> FloorRun:
    """The station's plant alone, driven by `inputs` for the trial's duration."""
    simulator, parts = build_plant_floor(scenario, inputs)
    plant = parts.plant
    end = float(inputs.times[-1])
    wall, cpu = time.perf_counter(), time.process_time()
    simulator.Initialize()
    simulator.AdvanceTo(end)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    plant_context = plant.GetMyContextFromRoot(simulator.get_context())
    p_WO = plant.GetPositions(plant_context, parts.object_instance)[4:7]
    return FloorRun(end, wall, cpu, float(np.linalg.norm(p_WO - inputs.final_object_position)))
