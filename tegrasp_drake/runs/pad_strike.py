"""A pad strike: the smallest scene with the station's first-contact RA transient.

The gripper welded in the side-grasp pose above the table closes at a constant finger
speed on an object standing nearer its left pad, which strikes first. Used by the RA tests
and analysis/compare_ra_transients.py."""

import dataclasses

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, LogVectorOutput

from tegrasp_drake.control.scripted_grasp import gripper_command
from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.extraction import cut_window
from tegrasp_drake.scenario.grasp_diagram import MakeSimulator
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import R_WG_SIDE_GRASP
from tegrasp_drake.simulation.gripper_hands import (PrismaticHand, actuated_state_selector,
                                                    configure_drive)
from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.simulation.film_chain import finger_force_indices
from tegrasp_drake.simulation.film_dynamics import first_order_highpass
from tegrasp_drake.simulation.object_model import AddObject, object_body
from tegrasp_drake.simulation.sim_robotiq_driver import MakeSimRobotiqDriver
from tegrasp_drake.simulation.station import AddTactileSensors
from tegrasp_drake.simulation.table_model import AddTable
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.tactile.sampling import samples_per_window

GRASP_XY = (0.72, 0.0)  # m, where the object stands; the grasp frame is above it


@dataclasses.dataclass
class PadStrikeConfig:
    """The strike: plant step, finger speed, where the object stands, how long to run."""
    time_step_s: float = 1e-3
    finger_speed_mps: float = 0.025  # each finger; the 2F-85 closes at twice this
    object_offset_m: float = 0.005  # along the stroke, toward the left finger
    gap_m: float = 0.002  # left pad to object once the finger cruises
    grip_force_n: float = 25.0
    before_contact_s: float = 0.25  # simulated before the left pad's contact, at least
    after_contact_s: float = 0.25  # and after it
    grasp_height_m: float = 0.055
    sensor_noise: bool = False


@dataclasses.dataclass(frozen=True)
class PadStrike:
    """What a strike logged, (left, right) columns: t_ra (M,) [s], ra (M, 2) films' signed z
    [m/s^2-equivalent], pad_acceleration (M, 2) along the normals; t_sa (N,), sa (N, 2)
    taxel sums [N]; contact_times (2,) each pad's first contact [s] (nan if none)."""
    t_ra: np.ndarray
    ra: np.ndarray
    pad_acceleration: np.ndarray
    t_sa: np.ndarray
    sa: np.ndarray
    contact_times: np.ndarray
    time_step_s: float

    def accelerometer_ra(self, highpass_hz: float) -> np.ndarray:
        """(M, 2) |high-passed rigid-body acceleration| along the normal [m/s^2]."""
        dt = float(np.median(np.diff(self.t_ra)))
        return np.abs(first_order_highpass(self.pad_acceleration, highpass_hz, dt))

    def contact_peak(self, pad: int, window_s: float = 0.03) -> float:
        """Largest |RA| [m/s^2] of `pad` within window_s after its contact began."""
        start = self.contact_times[pad]
        mask = (self.t_ra > start - 2 * self.time_step_s) & (self.t_ra < start + window_s)
        return float(np.abs(self.ra[mask, pad]).max())

    def eq3_scores(self, event) -> np.ndarray:
        """Gated Eq. 3 scores of the window `event` would cut around the left contact."""
        start = self.contact_times[0] - event.pre_transition_s
        windows = []
        for times, values, rate in ((self.t_sa, self.sa, event.sa_rate_hz),
                                    (self.t_ra, np.abs(self.ra), event.ra_rate_hz)):
            length = samples_per_window(event.window_s, rate)
            windows.extend(normalize_by_max(cut_window(
                times, values, start_s=start, rate_hz=rate, length=length, what="strike")))
        templates = [event.channel(name) for name in
                     ("sa_left", "sa_right", "ra_left", "ra_right")]
        return event_scores_reference(windows, templates, min_contrast=0.25)


def strike_scenario(config: PadStrikeConfig):
    """The default scenario at config's step on the prismatic hand (a finger moving along
    its pad normal), noise-free unless config.sensor_noise."""
    from tegrasp_drake.scenario.scenario import LoadScenario
    scenario = LoadScenario(overrides=[f"plant_config.time_step={config.time_step_s}",
                                       "gripper.model=prismatic"])
    if not config.sensor_noise:
        scenario = dataclasses.replace(
            scenario, tactile=dataclasses.replace(scenario.tactile, noise_std_n=0.0,
                                                  quantization_n=0.0),
            vibration=dataclasses.replace(scenario.vibration, noise_std_mps2=0.0,
                                          adc_input="ideal"))
    return scenario


def run_pad_strike(config: PadStrikeConfig = PadStrikeConfig(), scenario=None) -> PadStrike:
    """Simulates the strike; `scenario` (default strike_scenario) gives object and sensors."""
    scenario = scenario or strike_scenario(config)
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(scenario.plant_config, builder)
    parser = paths.make_parser(plant)
    hand = PrismaticHand()
    (gripper,) = parser.AddModels(url=hand.url)
    X_BG = plant.GetFrameByName("grasp_frame", gripper).GetFixedPoseInBodyFrame()
    X_WG = RigidTransform(R_WG_SIDE_GRASP, [*GRASP_XY, config.grasp_height_m])
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper),
                     X_WG @ X_BG.inverse())
    AddTable(parser, scenario.contact_geometry)
    obj = AddObject(parser, scenario.object, scenario.contact_geometry)
    plant.set_gravity_enabled(gripper, False)
    configure_drive(plant, gripper, hand, scenario.gripper)
    plant.Finalize()

    speed, acceleration = config.finger_speed_mps, scenario.gripper.acceleration
    half_width = scenario.object.width_along_stroke() / 2
    q0 = half_width + config.object_offset_m + config.gap_m + speed ** 2 / (2 * acceleration)
    # Cruise long enough that the window before contact holds only free motion.
    q0 += speed * max(0.0, config.before_contact_s - speed / acceleration)
    plant.SetDefaultPositions(gripper, [q0, q0])
    plant.SetDefaultFloatingBaseBodyPose(
        object_body(plant, obj), RigidTransform([GRASP_XY[0], config.object_offset_m, 0.0]))
    driver = builder.AddNamedSystem("gripper_driver", MakeSimRobotiqDriver(
        config=scenario.gripper, time_step=plant.time_step(), initial_opening=2 * q0))
    command = builder.AddNamedSystem("command", ConstantVectorSource(
        gripper_command(0.0, 2 * speed, config.grip_force_n)))
    builder.Connect(command.get_output_port(), driver.GetInputPort("command"))
    selector = builder.AddSystem(actuated_state_selector(plant, gripper, hand))
    builder.Connect(plant.get_state_output_port(gripper), selector.get_input_port())
    builder.Connect(selector.get_output_port(), driver.GetInputPort("finger_state"))
    builder.Connect(driver.GetOutputPort("desired_state"),
                    plant.get_desired_state_input_port(gripper))
    taxels, films = AddTactileSensors(builder, plant=plant, scene_graph=scene_graph,
                                      gripper=gripper, object_body=object_body(plant, obj),
                                      tactile=scenario.tactile, vibration=scenario.vibration,
                                      gripper_model=scenario.gripper.model,
                                      random_seed=scenario.random_seed)
    ra_period = 1.0 / scenario.vibration.sample_rate_hz
    logs = {f"ra_{f}": LogVectorOutput(films.GetOutputPort(f"{f}_pad_vibration"), builder,
                                       ra_period) for f in FINGER_NAMES}
    for f in FINGER_NAMES:
        accelerometer = builder.GetSubsystemByName(f"{f}_pad_accelerometer")
        logs[f"a_{f}"] = LogVectorOutput(accelerometer.get_measurement_output_port(), builder,
                                         ra_period)
    logs["sa"] = LogVectorOutput(taxels.GetOutputPort("true_taxel_forces"), builder,
                                 1.0 / scenario.tactile.sample_rate_hz)
    logs["force"] = LogVectorOutput(plant.get_generalized_contact_forces_output_port(gripper),
                                    builder, scenario.plant_config.time_step)
    diagram = builder.Build()

    simulator = MakeSimulator(diagram, scenario)
    context = simulator.get_mutable_context()
    expected_contact = speed / acceleration + (q0 - half_width - config.object_offset_m
                                               - speed ** 2 / (2 * acceleration)) / speed
    simulator.AdvanceTo(expected_contact + config.after_contact_s + 0.05)

    def data(name):
        log = logs[name].FindLog(context)
        return log.sample_times(), log.data().T

    t_ra, ra_left = data("ra_left")
    ra = np.column_stack([ra_left[:, 2], data("ra_right")[1][:, 2]])
    accelerations = np.column_stack([data("a_left")[1][:, 2], data("a_right")[1][:, 2]])
    t_sa, taxel_forces = data("sa")
    sa = np.column_stack([taxel_forces[:, :TAXELS_PER_PAD].sum(axis=1),
                          taxel_forces[:, TAXELS_PER_PAD:].sum(axis=1)])
    t_force, forces = data("force")
    indices = finger_force_indices(plant, gripper)
    contact_times = np.array([
        t_force[np.argmax(np.abs(forces[:, i]) > 0)] if np.any(np.abs(forces[:, i]) > 0)
        else np.nan for i in indices])
    return PadStrike(t_ra=t_ra, ra=ra, pad_acceleration=accelerations, t_sa=t_sa, sa=sa,
                     contact_times=contact_times, time_step_s=scenario.plant_config.time_step)
