"""Wires a controller to the station with the Eq. 1-2 channels and the trial's loggers: any
controller with `X_WG_desired`, `gripper_command` (and `phase`) outputs can be logged."""

import dataclasses
import importlib.metadata

import numpy as np

from pydrake.systems.primitives import Demultiplexer, LogVectorOutput, Multiplexer

from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.scenario.scenario import scenario_to_yaml
from tegrasp_drake.scenario.trial_log_file import TrialLog

SLOW_LOG_PERIOD = 0.01  # s, arm, gripper, phase and object logs




@dataclasses.dataclass
class TrialLoggers:
    taxels: object
    true_taxels: object
    channels: object
    accelerations: tuple
    arm_q: object
    arm_q_desired: object
    gripper_command: object
    gripper_status: object
    phase: object
    object_state: object


def AddTrialLogging(builder, *, scenario, station, channels, arm_desired_state,
                      gripper_command, phase) -> TrialLoggers:
    """Adds a TrialLog's loggers: taxels at the SA rate, signals at the RA rate, the rest slower."""
    sa_period = 1.0 / scenario.tactile.sample_rate_hz
    ra_period = 1.0 / scenario.vibration.sample_rate_hz
    taxel_mux = builder.AddNamedSystem("taxel_log_mux", Multiplexer([12, 12]))
    builder.Connect(station.GetOutputPort(ports.taxel_forces("left")), taxel_mux.get_input_port(0))
    builder.Connect(station.GetOutputPort(ports.taxel_forces("right")),
                    taxel_mux.get_input_port(1))
    q_desired = builder.AddNamedSystem("arm_desired_demux", Demultiplexer([6, 6]))
    builder.Connect(arm_desired_state, q_desired.get_input_port())
    return TrialLoggers(
        taxels=LogVectorOutput(taxel_mux.get_output_port(), builder, sa_period),
        true_taxels=LogVectorOutput(station.GetOutputPort(ports.TRUE_TAXEL_FORCES), builder,
                                    sa_period),
        channels=LogVectorOutput(channels.GetOutputPort("channels"), builder, ra_period),
        accelerations=tuple(
            LogVectorOutput(station.GetOutputPort(ports.pad_acceleration(f)), builder,
                            ra_period) for f in FINGER_NAMES),
        arm_q=LogVectorOutput(station.GetOutputPort(ports.ARM_POSITION_MEASURED), builder,
                              SLOW_LOG_PERIOD),
        arm_q_desired=LogVectorOutput(q_desired.get_output_port(0), builder, SLOW_LOG_PERIOD),
        gripper_command=LogVectorOutput(gripper_command, builder, SLOW_LOG_PERIOD),
        gripper_status=LogVectorOutput(station.GetOutputPort(ports.GRIPPER_STATUS), builder,
                                       SLOW_LOG_PERIOD),
        phase=LogVectorOutput(phase, builder, SLOW_LOG_PERIOD),
        object_state=LogVectorOutput(station.GetOutputPort(ports.OBJECT_STATE), builder,
                                     SLOW_LOG_PERIOD))


def package_versions() -> dict:
    versions = {}
    for name in ("tegrasp-drake", "drake", "numpy"):
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions


def collect_trial_log(loggers: TrialLoggers, context, *, scenario, meta: dict) -> TrialLog:
    """Reads the loggers into a TrialLog."""
    def log(logger):
        return logger.FindLog(context)

    taxels, true_taxels, channels = log(loggers.taxels), log(loggers.true_taxels), log(
        loggers.channels)
    slow = log(loggers.phase)
    n = min(len(slow.sample_times()), len(log(loggers.object_state).sample_times()))
    accelerations = [log(a).data().T for a in loggers.accelerations]
    m = min(len(channels.sample_times()), *(len(a) for a in accelerations))
    full_meta = dict(meta, scenario=scenario_to_yaml(scenario), versions=package_versions())
    return TrialLog(
        t_sa=taxels.sample_times().copy(), taxels=taxels.data().T.copy(),
        true_taxels=true_taxels.data().T[:len(taxels.sample_times())].copy(),
        t_ra=channels.sample_times()[:m].copy(), channels=channels.data().T[:m].copy(),
        pad_acceleration=np.hstack([a[:m] for a in accelerations]),
        t_slow=slow.sample_times()[:n].copy(), arm_q=log(loggers.arm_q).data().T[:n].copy(),
        arm_q_desired=log(loggers.arm_q_desired).data().T[:n].copy(),
        gripper_command=log(loggers.gripper_command).data().T[:n].copy(),
        gripper_status=log(loggers.gripper_status).data().T[:n].copy(),
        phase=slow.data()[0, :n].copy(), object_state=log(loggers.object_state).data().T[:n].copy(),
        meta=full_meta)
