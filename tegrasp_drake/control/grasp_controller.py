"""The grasp controller wired to a station: Eq. 1-2 channels -> event detector (the
memorized events' EventMatcher, the paper's Fig. 3, or heuristic thresholds) ->
GraspStateMachine -> Cartesian arm controller; or the open-loop script. It connects to any
system with the station's port names (rig/station_interface.py), simulated or hardware."""

import dataclasses
import math
from typing import Annotated

import numpy as np

from pydrake.systems.primitives import Multiplexer
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.framework import OutputPort, System

from tegrasp_drake.rig import paths
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.control.cartesian_arm_controller import AddCartesianArmController
from tegrasp_drake.control.controller_config import EventTriggeredConfig
from tegrasp_drake.control.noise_thresholds import resolve_noise_thresholds
from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger, detects
from tegrasp_drake.control.grasp_state_machine import GraspPlan, GraspStateMachine
from tegrasp_drake.control.grasp_wrench_estimator import GraspWrenchEstimator
from tegrasp_drake.control.heuristic_event_detector import HeuristicEventDetector
from tegrasp_drake.control.scripted_grasp import (PHASES, ScriptedGraspSource, ScriptSegment,
                                                  plan_scripted_grasp)
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.tactile.mechanoreceptor_channels import AddMechanoreceptorChannels
from tegrasp_drake.tactile.ra_tick_peak import AddRaTickPeak
from tegrasp_drake.tactile.sample_block import block_samples
from tegrasp_drake.tactile.slip_vibration_band import AddSlipVibrationBand
from tegrasp_drake.simulation.station import ArmDriverConfig
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig
from tegrasp_drake.control.controller_registry import (ControllerConfig, ControllerEntry,
                                                       controller_entry)
from tegrasp_drake.rig.api_boundary import public_api, public_dataclass
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import field_range

# The open-loop script's phases as the state machine's modes (for its timeline).
_MODE_OF_PHASE = {"settle": Mode.REACH, "reach": Mode.REACH, "load": Mode.LOAD,
                  "lift": Mode.LIFT, "hold": Mode.HOLD, "place": Mode.PLACE,
                  "unload": Mode.UNLOAD, "retract": Mode.UNLOAD, "done": Mode.DONE}


def modes_of_phases(phases) -> np.ndarray:
    """The Mode values (float, as logged) of the open-loop script's phase indices `phases`
    (into PHASES)."""
    values = np.array([_MODE_OF_PHASE[phase] for phase in PHASES], dtype=float)
    return values[np.asarray(phases, dtype=int)]


@public_dataclass
@dataclasses.dataclass
class GraspController:
    """The controller's systems and its ports of interest."""
    name: str
    channels: System  # MakeMechanoreceptorChannels' diagram
    detector: System | None  # EventMatcher, HeuristicEventDetector or None (open loop)
    state_machine: GraspStateMachine | ScriptedGraspSource  # ScriptedGraspSource: open loop
    gripper_command: OutputPort
    arm_desired_state: OutputPort
    mode: OutputPort  # the Mode value (open loop: the script's phase index)
    segments: list[ScriptSegment] | None = None  # the open-loop script's segments

    def current_mode(self, root_context) -> Mode:
        """The mode now (open loop: the mode of the script's phase)."""
        value = self.mode.Eval(self._system_context(root_context))
        return Mode(int(self.logged_modes(value)[0]))

    def logged_modes(self, values) -> np.ndarray:
        """The Mode values of samples of the `mode` port (open loop: of its phase indices)."""
        return np.asarray(values) if self.segments is None else modes_of_phases(values)

    def _system_context(self, root_context):
        return self.state_machine.GetMyContextFromRoot(root_context)

    def transitions(self, root_context) -> list[Transition]:
        """The transitions so far (open loop: the script's mode changes, without scores; a
        phase that lasts no time, grasp.hold_s = 0, is passed over as sample_plan does)."""
        if self.segments is None:
            return list(self.state_machine.transitions(self._system_context(root_context)))
        t_now = root_context.get_time()
        log, previous = [], Mode.REACH
        for segment in self.segments[1:]:
            mode = _MODE_OF_PHASE[segment.phase]
            lasts = segment.t_end > segment.t_start
            if lasts and segment.t_start <= t_now and mode != previous:
                log.append(Transition(t=segment.t_start, from_mode=previous, to_mode=mode,
                                      trigger=Trigger.TIMER,
                                      reason=f"script phase {segment.phase}"))
                previous = mode
        end = self.segments[-1].t_end
        if end <= t_now:
            log.append(Transition(t=end, from_mode=previous, to_mode=Mode.DONE,
                                  trigger=Trigger.TIMER, reason="script ended"))
        return log


def controller_events_folders(controller, events_dir=None, hand_folder: str = "") -> list:
    """The folders the controller reads its memorized events from: each events search path
    folder (rig/paths.events_search_path) joined with controller.events_folder."""
    sub = controller.events_folder or ""
    return [folder / sub if sub else folder
            for folder in paths.events_search_path(events_dir, hand_folder)]


def event_matcher_config(config: EventTriggeredConfig, *, gripper_model: str,
                         rates_hz: tuple[float, float]):
    """The EventMatcherConfig of an event-triggered controller (thresholds, SA and RA rates [Hz],
    blocks, RA envelope and floor), shared by the live run and a replay of its log."""
    from tegrasp_drake.events import EventMatcherConfig
    return EventMatcherConfig(
        **dataclasses.asdict(config.matching),
        event_thresholds=config.event_thresholds(
            dict(gripper_hand(gripper_model).ensemble_thresholds)),
        sa_rate_hz=rates_hz[0], ra_rate_hz=rates_hz[1], block_s=config.sensor_block_s)


@detects(Trigger.MEMORIZED_EVENT)
def add_event_matcher_detector(builder, *, config, plan, rates_hz, events, channels):
    """An event-triggered controller's detector: the EventMatcher on `channels`."""
    from tegrasp_drake.events import add_event_matcher
    if events is None:
        raise ValueError(f"AddGraspController: the {config.name} controller needs its "
                         "memorized events (events=load_controller_events(scenario))")
    matcher_config = dataclasses.replace(
        event_matcher_config(config, gripper_model=plan.gripper_model, rates_hz=rates_hz),
        read_period_s=config.update_period_s)
    return add_event_matcher(builder, events, matcher_config, channels=channels)


@detects(Trigger.HEURISTIC_EVENT)
def add_heuristic_detector(builder, *, config, plan, rates_hz, events, channels):
    """The heuristic thresholds' detector on `channels`."""
    detector = builder.AddNamedSystem("heuristic_detector", HeuristicEventDetector(
        config.heuristic, grip_force_n=plan.grip_force))
    builder.Connect(channels, detector.GetInputPort("channels"))
    return detector


def _add_corrective_matcher(builder, config, rates_hz, corrective_events, channels):
    """The `corrective_matcher` of controller.memorized_corrective's events on `channels`."""
    from tegrasp_drake.events import EventMatcher, EventMatcherConfig
    if corrective_events is None:
        raise ValueError("AddGraspController: controller.memorized_corrective.events names "
                         f"{list(config.memorized_corrective.events)}: give their events "
                         "(corrective_events=load_corrective_events(scenario))")
    from tegrasp_drake.tactile.window_normalizer import ConnectWindowChannels
    events = {t: corrective_events[t] for t in config.memorized_corrective.events}
    matcher = builder.AddNamedSystem("corrective_matcher", EventMatcher(
        events, EventMatcherConfig(event_thresholds={
            t: pair for t, pair in config.memorized_corrective.thresholds().items()
            if t in events}, sa_rate_hz=rates_hz[0], ra_rate_hz=rates_hz[1],
            block_s=config.sensor_block_s, read_period_s=config.update_period_s)))
    ConnectWindowChannels(builder, matcher, channels)
    return matcher


# The live SA and RA rates [Hz] and the RA noise [m/s^2] take the ranges the scenario's
# tactile.sample_rate_hz, vibration.sample_rate_hz and vibration.noise_std_mps2 take, so that a
# script and the command line meet the same bounds (the two rates share theirs: 8 samples in
# the 0.5 s event window at the low end, the films' 20 kHz integration at the high end).
SAMPLE_RATE_RANGE = field_range(TactileSensorConfig, "sample_rate_hz")
RA_NOISE_RANGE = field_range(VibrationSensorConfig, "noise_std_mps2")


@public_api
def AddGraspController(builder: DiagramBuilder, *, controller: ControllerConfig,
                       plan: GraspPlan, station: System, arm: ArmDriverConfig,
                       sample_rates_hz: Annotated[tuple[float, float], SAMPLE_RATE_RANGE],
                       events: dict | None = None, corrective_events: dict | None = None,
                       ra_noise_std_mps2: Annotated[float, RA_NOISE_RANGE] = 0.0,
                       tactile: TactileSensorConfig | None = None) -> GraspController:
    """Adds `controller` as its control/controller_registry.py entry says, connected to
    `station`'s ports; returns its GraspController.

    sample_rates_hz: live SA and RA rates [Hz]. events, corrective_events: {transition:
    MemorizedEvent} (load_controller_events, load_corrective_events) when the controller
    needs them. ra_noise_std_mps2 [m/s^2 rms] and tactile raise the RA and SA thresholds to
    their noise sigmas (control/noise_thresholds.py); 0 and None: the numbers alone."""
    entry = controller_entry(controller)
    _refuse_unread_events(controller, entry, events, corrective_events)
    _refuse_other_objects_events(plan, events, corrective_events)
    _refuse_rates_the_station_does_not_deliver(station, sample_rates_hz)
    return entry.load("add_systems")(
        builder, entry=entry, controller=controller, plan=plan,
        station=station, arm=arm, sample_rates_hz=sample_rates_hz, events=events,
        corrective_events=corrective_events, ra_noise_std_mps2=ra_noise_std_mps2,
        tactile=tactile)


def _refuse_unread_events(controller, entry, events, corrective_events) -> None:
    """ValueError when events are given to a controller that would not read them: they would
    be dropped without a word, and the run would not be the one the caller meant."""
    if events is not None and not entry.event_triggered:
        raise ValueError(f"AddGraspController: events: the {controller.name} controller reads "
                         "no memorized events; leave events out, or choose an event-triggered "
                         "controller")
    if corrective_events is not None and not controller.memorized_corrective.events:
        raise ValueError("AddGraspController: corrective_events: the controller's "
                         "memorized_corrective.events names none, so none would be read; leave "
                         "corrective_events out, or name the transitions in "
                         "memorized_corrective.events")


def _refuse_other_objects_events(plan, events, corrective_events) -> None:
    """ValueError when an event was felt on an object other than the plan's: the templates
    would be another object's (load_controller_events refuses those by name too)."""
    if not plan.object_name:
        return
    for argument, given in (("events", events), ("corrective_events", corrective_events)):
        for transition, event in (given or {}).items():
            felt_on = getattr(event, "object_name", plan.object_name)
            if felt_on != plan.object_name:
                raise ValueError(
                    f"AddGraspController: {argument}['{transition}'] was felt on "
                    f"'{felt_on}', but the plan grasps '{plan.object_name}'; load the plan's "
                    "object's events (load_controller_events(scenario)), or record events "
                    "for it (`tegrasp record-events`)")


def _refuse_rates_the_station_does_not_deliver(station, sample_rates_hz) -> None:
    """ValueError when sample_rates_hz are not the rates the station declares its tactile
    outputs sampled at: the windows would span other times than the events' 0.5 s."""
    delivered = ports.declared_sample_rates(station)
    if delivered is None or all(math.isclose(float(given), rate, rel_tol=1e-9)
                                for given, rate in zip(sample_rates_hz, delivered)):
        return
    raise ValueError(
        f"AddGraspController: sample_rates_hz ({number_text(sample_rates_hz[0])}, "
        f"{number_text(sample_rates_hz[1])}) Hz: the station samples SA at "
        f"{number_text(delivered[0])} Hz and RA at {number_text(delivered[1])} Hz; give its "
        "rates (sample_rates_hz(scenario) of the scenario the station was made from)")


def _add_arm_controller(builder, *, station: System, arm: ArmDriverConfig):
    """The Cartesian arm controller on the station: (X_WG_desired input, desired_state)."""
    from tegrasp_drake.simulation.station import initial_arm_positions
    X_WG_desired, arm_desired_state = AddCartesianArmController(
        builder, position_measured=station.GetOutputPort(ports.ARM_POSITION_MEASURED),
        velocity_measured=station.GetOutputPort(ports.ARM_VELOCITY_MEASURED),
        q_nominal=initial_arm_positions(arm), time_step=arm.control_period_s)
    builder.Connect(arm_desired_state, station.GetInputPort(ports.ARM_DESIRED_STATE))
    return X_WG_desired, arm_desired_state


def AddScriptedGraspController(builder: DiagramBuilder, *, entry: ControllerEntry,
                               controller, plan: GraspPlan, station: System,
                               arm: ArmDriverConfig, **unused) -> GraspController:
    """The open-loop controller: the scripted grasp of `plan` (control/scripted_grasp.py)
    driving the arm and the gripper; the channels are added for the logs only."""
    channels = AddMechanoreceptorChannels(builder, station)
    X_WG_desired, arm_desired_state = _add_arm_controller(builder, station=station, arm=arm)
    segments = plan_scripted_grasp(plan)
    script = builder.AddNamedSystem("scripted_grasp", ScriptedGraspSource(segments))
    builder.Connect(script.GetOutputPort("X_WG_desired"), X_WG_desired)
    builder.Connect(script.GetOutputPort("gripper_command"),
                    station.GetInputPort(ports.GRIPPER_COMMAND))
    return GraspController(controller.name, channels, None, script,
                           script.GetOutputPort("gripper_command"), arm_desired_state,
                           script.GetOutputPort("phase"), segments)


def AddStateMachineController(builder: DiagramBuilder, *, entry: ControllerEntry,
                              controller, plan: GraspPlan, station: System,
                              arm: ArmDriverConfig, sample_rates_hz: tuple[float, float],
                              events: dict | None, corrective_events: dict | None,
                              ra_noise_std_mps2: float,
                              tactile: TactileSensorConfig | None) -> GraspController:
    """A closed-loop controller: channels, `entry`'s detector, rules and estimator, and the
    Cartesian arm controller (AddGraspController's arguments)."""
    config = resolve_noise_thresholds(controller, ra_noise_std_mps2=ra_noise_std_mps2,
                                      ra_rate_hz=sample_rates_hz[1], tactile=tactile,
                                      sa_rate_hz=sample_rates_hz[0])
    channels = AddMechanoreceptorChannels(builder, station)
    X_WG_desired, arm_desired_state = _add_arm_controller(builder, station=station, arm=arm)
    add_detector = entry.load("detector")
    detector = add_detector(builder, config=config, plan=plan, rates_hz=sample_rates_hz,
                            events=events, channels=channels.GetOutputPort("channels"))
    corrective = None
    if config.memorized_corrective.events:
        corrective = _add_corrective_matcher(builder, config, sample_rates_hz,
                                             corrective_events,
                                             channels.GetOutputPort("channels"))
    make_estimator = entry.load("estimator")
    machine = builder.AddNamedSystem("grasp_state_machine", GraspStateMachine(
        plan=plan, config=config,
        event_indices={t: detector.event_index(t) for t in detector.transitions},
        event_trigger=add_detector.trigger,
        corrective_event_indices=({t: corrective.event_index(t)
                                   for t in corrective.transitions} if corrective else None),
        rules=entry.rule_table(),
        estimator=(make_estimator(config, plan, sa_rate_hz=sample_rates_hz[0])
                   if make_estimator else None)))
    if corrective is not None:
        builder.Connect(machine.GetOutputPort("corrective_expected_event"),
                        corrective.GetInputPort("expected_event"))
        builder.Connect(corrective.GetOutputPort("match"),
                        machine.GetInputPort("corrective_match"))
    builder.Connect(machine.GetOutputPort("expected_event"),
                    detector.GetInputPort("expected_event"))
    builder.Connect(detector.GetOutputPort("match"), machine.GetInputPort("match"))
    builder.Connect(detector.GetOutputPort("scores"), machine.GetInputPort("scores"))
    builder.Connect(channels.GetOutputPort("channels"), machine.GetInputPort("channels"))
    builder.Connect(station.GetOutputPort(ports.GRIPPER_STATUS),
                    machine.GetInputPort(ports.GRIPPER_STATUS))
    accelerations = builder.AddNamedSystem(
        "pad_acceleration_mux", Multiplexer([ports.PAD_ACCELERATION_AXES] * 2))
    for k, finger in enumerate(FINGER_NAMES):
        builder.Connect(station.GetOutputPort(ports.pad_acceleration(finger)),
                        accelerations.get_input_port(k))
    builder.Connect(accelerations.get_output_port(), machine.GetInputPort("pad_acceleration"))
    # hardware: the device's own samples; simulation: the film's, in blocks
    samples = (station.GetOutputPort(ports.TACTILE_PAD_ACCELERATION_SAMPLES)
               if station.HasOutputPort(ports.TACTILE_PAD_ACCELERATION_SAMPLES) else None)
    builder.Connect(AddSlipVibrationBand(builder, accelerations.get_output_port(),
                                         band_hz=config.lift_load.slip_band_hz,
                                         window_s=config.lift_load.slip_window_s,
                                         sample_rate_hz=sample_rates_hz[1],
                                         pad_acceleration_samples=samples,
                                         block_samples=block_samples(
                                             sample_rates_hz[1], config.sensor_block_s)),
                    machine.GetInputPort("slip_vibration"))
    taxels = builder.AddNamedSystem("taxel_forces_mux", Multiplexer([TAXELS_PER_PAD] * 2))
    for k, finger in enumerate(FINGER_NAMES):
        builder.Connect(station.GetOutputPort(ports.taxel_forces(finger)),
                        taxels.get_input_port(k))
    builder.Connect(taxels.get_output_port(), machine.GetInputPort("taxel_forces"))
    if entry.senses_finger_strike and station.HasOutputPort(ports.ARM_TORQUE_MEASURED):
        wrench = builder.AddNamedSystem("grasp_wrench_estimator", GraspWrenchEstimator())
        builder.Connect(station.GetOutputPort(ports.ARM_POSITION_MEASURED),
                        wrench.GetInputPort(ports.ARM_POSITION_MEASURED))
        builder.Connect(station.GetOutputPort(ports.ARM_TORQUE_MEASURED),
                        wrench.GetInputPort(ports.ARM_TORQUE_MEASURED))
        builder.Connect(wrench.GetOutputPort("wrench"), machine.GetInputPort("grasp_wrench"))
    if entry.senses_finger_strike:
        builder.Connect(AddRaTickPeak(builder, channels.GetOutputPort("ra"),
                                      sample_rate_hz=sample_rates_hz[1],
                                      tick_s=config.update_period_s),
                        machine.GetInputPort("ra_peak"))
    builder.Connect(machine.GetOutputPort("X_WG_desired"), X_WG_desired)
    builder.Connect(machine.GetOutputPort("gripper_command"),
                    station.GetInputPort(ports.GRIPPER_COMMAND))
    return GraspController(config.name, channels, detector, machine,
                           machine.GetOutputPort("gripper_command"), arm_desired_state,
                           machine.GetOutputPort("mode"))
