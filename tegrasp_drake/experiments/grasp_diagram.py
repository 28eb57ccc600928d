"""The grasp controller diagram, built the same way around the simulated or the hardware
station, so that the controller cannot tell them apart.

    station (MakeGraspStation or MakeHardwareStation, by the scenario's `station` tag)
      -> add_grasp_controller (control/grasp_controller.py): arm.desired_state and
         gripper.command from the measured arm, gripper and tactile ports; the hardware
         station's `device_fault` goes to the state machine's `device_fault` input.

trial.py runs this controller on the simulated station in simulated time; hardware_run.py
runs it on the hardware station in real time.
"""

import dataclasses

from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.control.grasp_controller import add_grasp_controller
from tegrasp_drake.control.grasp_modes import TERMINAL_MODES, Transition
from tegrasp_drake.control.scripted_grasp import plan_duration, plan_scripted_grasp
from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.simulation.station import MakeGraspStation
from tegrasp_drake.experiments.trial import EXTRA_TIME_S


def MakeStation(scenario, *, meshcat=None, lcm=None):
    """MakeGraspStation or MakeHardwareStation, as the scenario's `station` tag says."""
    if isinstance(scenario.station, HardwareStationConfig):
        from tegrasp_drake.hardware.station import MakeHardwareStation
        return MakeHardwareStation(scenario.station, lcm=lcm)
    return MakeGraspStation(scenario, meshcat=meshcat)


@dataclasses.dataclass
class GraspDiagram:
    station: object       # the station subsystem
    grasp: object         # the GraspController
    time_limit: float     # [s] the longest the run may take (the plan plus corrections)


def build_grasp_diagram(scenario, *, station, controller: str | None = None, events=None,
                        builder: DiagramBuilder | None = None
                        ) -> tuple[GraspDiagram, DiagramBuilder]:
    """Adds `station` (a built station Diagram) and the controller (default: the
    scenario's) to `builder` (a new one by default); returns the parts and the builder,
    not yet built, so that callers can add to it."""
    builder = builder or DiagramBuilder()
    station = builder.AddNamedSystem("station", station)
    grasp = add_grasp_controller(builder, scenario=scenario, station=station,
                                 controller=controller, events=events)
    machine = grasp.state_machine
    if station.HasOutputPort("device_fault") and machine.HasInputPort("device_fault"):
        builder.Connect(station.GetOutputPort("device_fault"),
                        machine.GetInputPort("device_fault"))
    time_limit = plan_duration(plan_scripted_grasp(scenario)) + EXTRA_TIME_S
    return GraspDiagram(station, grasp, time_limit), builder


def is_finished(transitions: list[Transition]) -> bool:
    """True once the state machine reached Done or Failed."""
    return bool(transitions) and transitions[-1].to_mode in TERMINAL_MODES
