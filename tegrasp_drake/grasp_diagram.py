"""The grasp controller diagram, built the same way around the simulated or the hardware
station, so that the controller cannot tell them apart.

    station (MakeGraspStation or MakeHardwareStation, by the scenario's `station` tag)
      -> controller (add_controller: arm.desired_state, gripper.command from the measured
         arm, gripper and tactile ports; its state machine's `fault` input, if it has one,
         takes the hardware station's `fault`)

`add_controller` is the one place that says which controller runs. The closed-loop state
machine (control/grasp_controller.py, `add_grasp_controller`) is not in the package yet,
so the open-loop script (ScriptedGraspSource) stands in behind the same interface: an
object with `.state_machine` and `.transition_log(context)` -> [{t, from, to, trigger}].
"""

import dataclasses

import numpy as np
from pydrake.common import RandomGenerator
from pydrake.common.value import AbstractValue
from pydrake.systems.analysis import ApplySimulatorConfig, Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantValueSource, LogVectorOutput, Multiplexer

from tegrasp_drake.channels import FINGER_NAMES
from tegrasp_drake.control.cartesian_arm_controller import add_cartesian_arm_controller
from tegrasp_drake.control.scripted_grasp import (PHASES, ScriptedGraspSource, plan_duration,
                                                  plan_scripted_grasp)
from tegrasp_drake.hardware_config import HardwareStationConfig
from tegrasp_drake.scenario import scenario_to_yaml
from tegrasp_drake.station import MakeGraspStation, initial_arm_positions
from tegrasp_drake.trial_log import TrialLog

OPEN_LOOP = "open_loop"
DEFAULT_CONTROLLER = OPEN_LOOP  # "memorized" once control/grasp_controller.py lands
TERMINAL_MODES = ("done", "failed")
END_MARGIN_S = 0.5     # run this long past the controller's planned duration at most
SLOW_LOG_PERIOD = 0.01  # [s]


@dataclasses.dataclass
class ScriptedGraspController:
    """The open-loop script behind GraspController's interface. Its "transitions" are the
    script's phase changes, triggered by the clock."""
    state_machine: ScriptedGraspSource
    segments: list

    @property
    def duration(self) -> float:
        """When the script is done [s]."""
        return plan_duration(self.segments)

    def transition_log(self, context) -> list[dict]:
        """The phase changes up to the root `context`'s time."""
        now = context.get_time()
        phases = [(s.t_start, s.phase) for s in self.segments] + [(self.duration, PHASES[-1])]
        return [{"t": t, "from": before, "to": after, "trigger": "script"}
                for (_, before), (t, after) in zip(phases, phases[1:]) if t <= now]


def add_scripted_grasp_controller(builder, *, scenario, station) -> ScriptedGraspController:
    """The ideal open-loop grasp (ideal_grasp.py's wiring) on `station`'s ports."""
    segments = plan_scripted_grasp(scenario)
    script = builder.AddNamedSystem("scripted_grasp", ScriptedGraspSource(segments))
    X_WG_desired, arm_desired_state = add_cartesian_arm_controller(
        builder, position_measured=station.GetOutputPort("arm.position_measured"),
        velocity_measured=station.GetOutputPort("arm.velocity_measured"),
        q_nominal=initial_arm_positions(scenario), time_step=scenario.plant_config.time_step)
    builder.Connect(script.GetOutputPort("X_WG_desired"), X_WG_desired)
    builder.Connect(arm_desired_state, station.GetInputPort("arm.desired_state"))
    builder.Connect(script.GetOutputPort("gripper_command"),
                    station.GetInputPort("gripper.command"))
    return ScriptedGraspController(script, segments)


def add_controller(builder, *, scenario, station, controller: str = DEFAULT_CONTROLLER,
                   events=None):
    """The grasp controller on `station` (module docstring)."""
    if controller != OPEN_LOOP:
        # One line to change when control/grasp_controller.py lands:
        # return add_grasp_controller(builder, scenario=scenario, station=station,
        #                             controller=controller, events=events)
        raise ValueError(f"controller '{controller}' needs control/grasp_controller.py "
                         f"(issue 4); only '{OPEN_LOOP}' runs today")
    return add_scripted_grasp_controller(builder, scenario=scenario, station=station)


def _connect_faults(builder, station, grasp):
    """The station's `fault` (or, in simulation, no fault) into the state machine's
    `fault` input, when it has one."""
    state_machine = grasp.state_machine
    if not state_machine.HasInputPort("fault"):
        return
    if station.HasOutputPort("fault"):
        builder.Connect(station.GetOutputPort("fault"), state_machine.GetInputPort("fault"))
    else:
        no_fault = builder.AddNamedSystem("no_fault",
                                          ConstantValueSource(AbstractValue.Make(())))
        builder.Connect(no_fault.get_output_port(), state_machine.GetInputPort("fault"))


def MakeStation(scenario, *, meshcat=None, lcm=None):
    """MakeGraspStation or MakeHardwareStation, as the scenario's `station` tag says."""
    if isinstance(scenario.station, HardwareStationConfig):
        from tegrasp_drake.hardware_station import MakeHardwareStation
        return MakeHardwareStation(scenario.station, lcm=lcm)
    return MakeGraspStation(scenario, meshcat=meshcat)


@dataclasses.dataclass
class GraspDiagram:
    diagram: object
    station: object     # the station subsystem
    grasp: object       # what add_controller returned
    duration: float     # [s] the longest the run needs (controller's plan + margin)


def build_grasp_diagram(scenario, *, station, controller: str = DEFAULT_CONTROLLER,
                        events=None, builder=None) -> tuple[GraspDiagram, DiagramBuilder]:
    """Adds `station` (a built station Diagram) and the controller to `builder` (a new one
    by default); returns the parts and the builder, not yet built, so that callers can
    add loggers."""
    builder = builder or DiagramBuilder()
    station = builder.AddNamedSystem("station", station)
    grasp = add_controller(builder, scenario=scenario, station=station,
                           controller=controller, events=events)
    _connect_faults(builder, station, grasp)
    duration = getattr(grasp, "duration", plan_duration(plan_scripted_grasp(scenario)))
    return GraspDiagram(None, station, grasp, duration + END_MARGIN_S), builder


def is_finished(transitions: list[dict]) -> bool:
    """True once the state machine reached a terminal mode."""
    return bool(transitions) and str(transitions[-1]["to"]).lower() in TERMINAL_MODES


@dataclasses.dataclass
class SimulatedGraspRun:
    """A pure simulation of the controller diagram: its transitions and the tactile data
    (and arm, gripper, object) as a TrialLog, e.g. for the myRIO emulator to replay."""
    transitions: list
    log: TrialLog


def _add_recording(builder, station, scenario):
    sa_period = 1.0 / scenario.tactile.sample_rate_hz
    ra_period = 1.0 / scenario.vibration.sample_rate_hz
    taxels = builder.AddNamedSystem("taxel_recording_mux", Multiplexer([12, 12]))
    accelerations = builder.AddNamedSystem("acceleration_recording_mux", Multiplexer([3, 3]))
    for i, finger in enumerate(FINGER_NAMES):
        builder.Connect(station.GetOutputPort(f"tactile.{finger}_taxel_forces"),
                        taxels.get_input_port(i))
        builder.Connect(station.GetOutputPort(f"tactile.{finger}_pad_acceleration"),
                        accelerations.get_input_port(i))
    return {
        "taxels": LogVectorOutput(taxels.get_output_port(), builder, sa_period),
        "true_taxels": LogVectorOutput(station.GetOutputPort("tactile.true_taxel_forces"),
                                       builder, sa_period),
        "pad_acceleration": LogVectorOutput(accelerations.get_output_port(), builder,
                                            ra_period),
        "arm_q": LogVectorOutput(station.GetOutputPort("arm.position_measured"), builder,
                                 SLOW_LOG_PERIOD),
        "gripper_status": LogVectorOutput(station.GetOutputPort("gripper.status"), builder,
                                          SLOW_LOG_PERIOD),
        "object_state": LogVectorOutput(station.GetOutputPort("object.state"), builder,
                                        SLOW_LOG_PERIOD),
    }


def _recorded_trial_log(loggers, context, scenario, transitions, controller) -> TrialLog:
    logs = {name: logger.FindLog(context) for name, logger in loggers.items()}
    sa, ra, slow = logs["taxels"], logs["pad_acceleration"], logs["arm_q"]
    acceleration = ra.data().T
    ra_channels = np.column_stack([np.linalg.norm(acceleration[:, :3], axis=1),
                                   np.linalg.norm(acceleration[:, 3:], axis=1)])
    taxels = sa.data().T
    sa_channels = np.column_stack([taxels[:, :12].sum(axis=1), taxels[:, 12:].sum(axis=1)])
    sa_at_ra = sa_channels[np.maximum(np.searchsorted(sa.sample_times(), ra.sample_times(),
                                                      side="right") - 1, 0)]
    n = len(slow.sample_times())
    return TrialLog(
        t_sa=sa.sample_times().copy(), taxels=taxels.copy(),
        true_taxels=logs["true_taxels"].data().T.copy(),
        t_ra=ra.sample_times().copy(), channels=np.hstack([sa_at_ra, ra_channels]),
        pad_acceleration=acceleration.copy(), t_slow=slow.sample_times().copy(),
        arm_q=slow.data().T.copy(), arm_q_desired=np.zeros((0, 6)),
        gripper_command=np.zeros((0, 3)),
        gripper_status=logs["gripper_status"].data().T[:n].copy(), phase=np.zeros(0),
        object_state=logs["object_state"].data().T[:n].copy(),
        meta={"controller": controller, "transitions": transitions,
              "scenario": scenario_to_yaml(scenario)})


def run_simulated_grasp(scenario, *, controller: str = DEFAULT_CONTROLLER, events=None,
                        duration: float | None = None) -> SimulatedGraspRun:
    """Simulates the controller diagram on MakeGraspStation (as fast as it goes) until
    the state machine is done or failed (or `duration`)."""
    parts, builder = build_grasp_diagram(scenario, station=MakeGraspStation(scenario),
                                         controller=controller, events=events)
    loggers = _add_recording(builder, parts.station, scenario)
    diagram = builder.Build()
    simulator = Simulator(diagram)
    ApplySimulatorConfig(scenario.simulator_config, simulator)
    context = simulator.get_mutable_context()
    diagram.SetRandomContext(context, RandomGenerator(scenario.random_seed))
    end = duration if duration is not None else parts.duration
    simulator.Initialize()
    while context.get_time() < end and not is_finished(parts.grasp.transition_log(context)):
        simulator.AdvanceTo(min(end, context.get_time() + 0.1))
    transitions = parts.grasp.transition_log(context)
    return SimulatedGraspRun(transitions, _recorded_trial_log(
        loggers, context, scenario, transitions, controller))
