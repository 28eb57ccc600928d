"""tegrasp-drake: Kim and Kim, "Tactile Event Based Grasping Algorithm using Memorized
Triggers and Mechanoreceptive Sensors", on Drake's systems framework.

The public API is importable from here (builders in Drake's CamelCase: Make*, Load*, Add*),
each name imported on first use so that `import tegrasp_drake` does not load pydrake:

    from tegrasp_drake import LoadScenario, MakeGraspDiagram, MakeSimulator
    scenario = LoadScenario(name="box")
    grasp = MakeGraspDiagram(scenario)           # station + controller + loggers
    simulator = MakeSimulator(grasp.diagram, scenario)
    simulator.AdvanceTo(12.0)
    print(grasp.controller.transitions(simulator.get_context()))

- scenario/: the typed Scenario, the grasp diagram, trial logs.
- rig/: shared plumbing: objects, channels, paths, typed YAML, ranges.
- simulation/: the simulated station (plant, hand, pads, sensors).
- hardware/, emulators/, lcmtypes/: the real devices, their emulators, the log's LCM types.
- robotiq/, modelgen/: the 2F-85's kinematics and registers; the SDF model generators.
- tactile/: the live tactile chain of Fig. 3 (Eq. 1-2, the 0.5 s window).
- events/, recording/: memorized events and their matching; recording them.
- control/: the state machine, rule tables and controllers.
- runs/, sweep/, transfer/, sensitivity/: a trial and its judgement; sweeps; the transfer
  study; the guessed parameters swept over their ranges.
- figures/, reports.py: the paper's figures; a results folder's reports.
- cli.py, commands/: the `tegrasp` command line."""

import importlib

__version__ = "0.1.0"

# Public name -> the module that defines it.
_PUBLIC = {
    # Scenarios and configuration (scenario/scenario.py, rig/, hardware/config.py).
    "Scenario": "tegrasp_drake.scenario.scenario",
    "LoadScenario": "tegrasp_drake.scenario.scenario",
    "scenario_to_yaml": "tegrasp_drake.scenario.scenario",
    "ConfigError": "tegrasp_drake.rig.typed_yaml",
    "ObjectConfig": "tegrasp_drake.rig.objects",
    "BUILTIN_OBJECTS": "tegrasp_drake.rig.objects",
    "HardwareStationConfig": "tegrasp_drake.hardware.config",
    "LoadHardwareConfig": "tegrasp_drake.hardware.config",
    "GraspControllerConfig": "tegrasp_drake.control.controller_config",
    "MemorizedControllerConfig": "tegrasp_drake.control.controller_config",
    "HeuristicControllerConfig": "tegrasp_drake.control.controller_config",
    "OpenLoopControllerConfig": "tegrasp_drake.control.controller_config",
    "TaxelAwareControllerConfig": "tegrasp_drake.control.controller_config",
    "CONTROLLER_NAMES": "tegrasp_drake.control.controller_registry",
    "CONTROLLERS": "tegrasp_drake.control.controller_registry",
    "ControllerEntry": "tegrasp_drake.control.controller_registry",
    "controller_entry": "tegrasp_drake.control.controller_registry",
    "with_controller": "tegrasp_drake.scenario.scenario",
    # Stations: the simulation and the real devices behind the same ports.
    "MakeGraspStation": "tegrasp_drake.simulation.station",
    "MakeHardwareStation": "tegrasp_drake.hardware.station",
    "MakeStation": "tegrasp_drake.scenario.grasp_diagram",
    # The controller and the diagram around a station.
    "AddGraspController": "tegrasp_drake.control.grasp_controller",
    "GraspController": "tegrasp_drake.control.grasp_controller",
    "MakeGraspDiagram": "tegrasp_drake.scenario.grasp_diagram",
    "AddScenarioController": "tegrasp_drake.scenario.grasp_diagram",
    "MakeSimulatedStation": "tegrasp_drake.scenario.grasp_diagram",
    "GraspPlan": "tegrasp_drake.control.machine_state",
    "grasp_plan": "tegrasp_drake.scenario.scenario",
    "sample_rates_hz": "tegrasp_drake.scenario.scenario",
    "load_controller_events": "tegrasp_drake.scenario.scenario_events",
    "load_corrective_events": "tegrasp_drake.scenario.scenario_events",
    "GraspDiagram": "tegrasp_drake.scenario.grasp_diagram",
    "MakeSimulator": "tegrasp_drake.scenario.grasp_diagram",
    "Mode": "tegrasp_drake.control.grasp_modes",
    "Transition": "tegrasp_drake.control.grasp_modes",
    "Trigger": "tegrasp_drake.control.grasp_modes",
    # The tactile chain of Fig. 3: Eq. 1-2, the 0.5 s window, Eq. 3.
    "MakeMechanoreceptorChannels": "tegrasp_drake.tactile.mechanoreceptor_channels",
    "AddMechanoreceptorChannels": "tegrasp_drake.tactile.mechanoreceptor_channels",
    "WindowNormalizer": "tegrasp_drake.tactile.window_normalizer",
    "EventMatcher": "tegrasp_drake.events.event_matcher",
    "EventMatcherConfig": "tegrasp_drake.events.event_matcher",
    # Memorized events.
    "MemorizedEvent": "tegrasp_drake.events.memorized_event",
    "MemorizedEventError": "tegrasp_drake.events.event_file",
    "load_memorized_events": "tegrasp_drake.events.events_folder",
    "save_memorized_events": "tegrasp_drake.events.events_folder",
    "record_events": "tegrasp_drake.recording.paper_events",
    # Runs: a simulated trial, the ideal grasp, a run on the devices, a sweep.
    "run_trial": "tegrasp_drake.runs.trial",
    "run_trial_from_spec": "tegrasp_drake.sweep.trial_function",
    "TrialResult": "tegrasp_drake.scenario.trial_result",
    "run_ideal_grasp": "tegrasp_drake.runs.ideal_grasp",
    "TrialLog": "tegrasp_drake.scenario.trial_log_file",
    "load_trial_log": "tegrasp_drake.scenario.trial_log_file",
    "run_on_hardware": "tegrasp_drake.runs.hardware_run",
    "SweepSpec": "tegrasp_drake.sweep.spec",
    "LoadSweepSpec": "tegrasp_drake.sweep.spec_file",
    "run_sweep": "tegrasp_drake.sweep.runner",
    "write_reports": "tegrasp_drake.reports",
    "load_records": "tegrasp_drake.sweep.records",
    "record_result": "tegrasp_drake.sweep.records",
}

__all__ = sorted(_PUBLIC)


def __getattr__(name: str):
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'tegrasp_drake' has no attribute '{name}'")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # imported once
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
