"""The ideal open-loop grasp as a runnable trial: build, simulate, log (Sec. III-A)."""

import time

from pydrake.common import RandomGenerator
from pydrake.systems.analysis import ApplySimulatorConfig, Simulator
from pydrake.systems.framework import DiagramBuilder

from tegrasp_drake.control.cartesian_arm_controller import add_cartesian_arm_controller
from tegrasp_drake.control.scripted_grasp import (PHASES, ScriptedGraspSource, plan_duration,
                                                  plan_scripted_grasp)
from tegrasp_drake.simulation.station import MakeGraspStation, initial_arm_positions
from tegrasp_drake.tactile.mechanoreceptor_channels import add_mechanoreceptor_channels
from tegrasp_drake.experiments.trial_logging import add_trial_logging, collect_trial_log

CONTROLLER_NAME = "open_loop"
END_MARGIN_S = 0.5  # simulated after the script ends, to see the object settle


def build_ideal_grasp_diagram(scenario, *, meshcat=None):
    """Returns (diagram, loggers, segments) of the scripted grasp around the station."""
    builder = DiagramBuilder()
    station = builder.AddNamedSystem("station", MakeGraspStation(scenario, meshcat=meshcat))
    segments = plan_scripted_grasp(scenario)
    script = builder.AddNamedSystem("scripted_grasp", ScriptedGraspSource(segments))
    X_WG_desired, arm_desired_state = add_cartesian_arm_controller(
        builder, position_measured=station.GetOutputPort("arm.position_measured"),
        velocity_measured=station.GetOutputPort("arm.velocity_measured"),
        q_nominal=initial_arm_positions(scenario), time_step=scenario.arm.control_period_s)
    builder.Connect(script.GetOutputPort("X_WG_desired"), X_WG_desired)
    builder.Connect(arm_desired_state, station.GetInputPort("arm.desired_state"))
    builder.Connect(script.GetOutputPort("gripper_command"), station.GetInputPort("gripper.command"))
    channels = add_mechanoreceptor_channels(builder, station)
    loggers = add_trial_logging(builder, scenario=scenario, station=station, channels=channels,
                                arm_desired_state=arm_desired_state,
                                gripper_command=script.GetOutputPort("gripper_command"),
                                phase=script.GetOutputPort("phase"))
    diagram = builder.Build()
    diagram.set_name("ideal_grasp")
    return diagram, loggers, segments


def run_ideal_grasp(scenario, *, meshcat=None, duration=None):
    """Simulates the ideal grasp; returns (TrialLog, wall time [s])."""
    diagram, loggers, segments = build_ideal_grasp_diagram(scenario, meshcat=meshcat)
    simulator = Simulator(diagram)
    ApplySimulatorConfig(scenario.simulator_config, simulator)
    context = simulator.get_mutable_context()
    diagram.SetRandomContext(context, RandomGenerator(scenario.random_seed))
    end_time = duration if duration is not None else plan_duration(segments) + END_MARGIN_S
    if meshcat is not None:
        meshcat.StartRecording()
    start = time.perf_counter()
    simulator.Initialize()
    simulator.AdvanceTo(end_time)
    wall = time.perf_counter() - start
    if meshcat is not None:
        meshcat.StopRecording()
        meshcat.PublishRecording()
    meta = {"controller": CONTROLLER_NAME, "phases": list(PHASES),
            "phase_starts": {s.phase: s.t_start for s in segments},
            "grip_force": scenario.grasp.grip_force, "wall_time_s": wall,
            "sim_time_s": end_time}
    return collect_trial_log(loggers, context, scenario=scenario, meta=meta), wall
