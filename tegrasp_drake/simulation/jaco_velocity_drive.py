"""The simulated JACO2 driven as the real one is: by joint velocities, sampled, late.
`arm.desired_state` -> JacoVelocityTracker -> ZeroOrderHold at the command rate ->
DiscreteTimeDelay -> the servo set-point q_ref = q0 + integral of v_cmd (as the JACO2's DSP does)
-> the plant's implicit PD per joint. Why, and the settings' sources: docs/model.md, "The arm"."""

import dataclasses

import numpy as np
from pydrake.systems.framework import InputPort, OutputPort
from pydrake.systems.primitives import AffineSystem, DiscreteTimeDelay, ZeroOrderHold

from tegrasp_drake.modelgen.jaco2_dh import continuous_joints_problem
from tegrasp_drake.rig.jaco_velocity_tracker import JacoVelocityTracker
from tegrasp_drake.rig.station_interface import ARM_JOINTS

# How far a period may be from a whole number of plant steps and still count as one [s]
# (round-off in 1 / 100 Hz = 10 x 0.001).
STEP_TOLERANCE_S = 1e-9


def plant_steps(duration_s: float, time_step: float) -> int | None:
    """`duration_s` as a whole number of plant steps of `time_step` [s], or None if not one."""
    steps = round(duration_s / time_step)
    return steps if abs(steps * time_step - duration_s) <= STEP_TOLERANCE_S else None


def drive_problem(arm, time_step: float):
    """(field, words, value) that name what is wrong with the velocity drive's settings of
    `arm` (ArmDriverConfig) on a plant of step `time_step` [s], or None: what relates them to
    the plant's step. Each setting's own range (a positive rate and latency, the tracker's
    gain and six positive speeds) is its declared Range, checked before (validate)."""
    rate, latency = arm.command_rate_hz, arm.command_latency_s
    steps = f"plant steps ({time_step:g} s)"
    if plant_steps(1.0 / rate, time_step) in (None, 0, 1):
        return ("command_rate_hz", f"must make a period of a whole number of {steps}, at "
                "least two, e.g. 100 or 50 [Hz]", rate)
    if plant_steps(latency, time_step) in (None, 0):
        return ("command_latency_s", f"must be a whole number of {steps}, at least one, "
                "e.g. 0.01 [s] (the JACO2's is about 0.01)", latency)
    problem = continuous_joints_problem(arm.tracker.continuous_joints)
    if problem:
        return (f"tracker.{problem[0]}",) + problem[1:]
    return None


def latency_register(arm, time_step: float, size: int):
    """The compiled system that delays each held command to act arm.command_latency_s after
    it was sampled, or None when nothing needs to (the plant reads a set-point one step late, a
    hold adds one step, a DiscreteTimeDelay of m steps m + 1)."""
    steps = plant_steps(arm.command_latency_s, time_step)
    if steps == 1:
        return None
    if steps == 2:
        return ZeroOrderHold(time_step, size)
    return DiscreteTimeDelay(time_step, steps - 2, size)


def velocity_servo_set_point(initial_positions, time_step: float) -> AffineSystem:
    """The arm's velocity servo as a set-point for the plant's PD: input the commanded state
    [q_des; v_cmd] (12), output [q_ref; v_ref] = [q0 + integral of v_cmd; v_cmd] (12), the
    integral by the plant's step `time_step` [s] (forward Euler: x+ = x + h v_cmd)."""
    n = ARM_JOINTS
    zero, one = np.zeros((n, n)), np.eye(n)
    return AffineSystem(
        A=one, B=np.hstack([zero, time_step * one]), f0=np.zeros(n),
        C=np.vstack([one, zero]), D=np.block([[zero, zero], [zero, one]]),
        y0=np.concatenate([np.asarray(initial_positions, dtype=float), np.zeros(n)]),
        time_period=time_step)


@dataclasses.dataclass
class JacoVelocityDrive:
    """The drive's ends: `desired_state` in; `set_point` (plant PD) and `commanded_state` out."""
    tracker: JacoVelocityTracker
    desired_state: InputPort
    commanded_state: OutputPort
    set_point: OutputPort


def AddJacoVelocityDrive(builder, *, arm, time_step: float, initial_positions,
                         position_measured: OutputPort,
                         prefix: str = "arm") -> JacoVelocityDrive:
    """Adds the velocity drive of `arm` (ArmDriverConfig) for a plant of step `time_step` [s]
    starting at `initial_positions` [rad]; `position_measured` is the tracker's feedback."""
    n = ARM_JOINTS
    tracker = builder.AddNamedSystem(f"{prefix}_velocity_tracker",
                                     JacoVelocityTracker(arm.tracker))
    builder.Connect(position_measured, tracker.GetInputPort("position_measured"))
    hold = builder.AddNamedSystem(f"{prefix}_command_hold",
                                  ZeroOrderHold(1.0 / arm.command_rate_hz, 2 * n))
    builder.Connect(tracker.GetOutputPort("commanded_state"), hold.get_input_port())
    command = hold.get_output_port()
    register = latency_register(arm, time_step, 2 * n)
    if register is not None:
        builder.AddNamedSystem(f"{prefix}_command_latency", register)
        builder.Connect(command, register.get_input_port())
        command = register.get_output_port()
    servo = builder.AddNamedSystem(f"{prefix}_velocity_servo",
                                   velocity_servo_set_point(initial_positions, time_step))
    builder.Connect(command, servo.get_input_port())
    return JacoVelocityDrive(tracker, tracker.GetInputPort("desired_state"),
                             hold.get_output_port(), servo.get_output_port())
