"""Vibration of the gripper's and the arm's drives as the films read it: per drive a sum of
tones at f_k = order_k n, n = motor_revolutions_per_unit |v| [rev/s] (v the gripper's
half-opening rate [m/s] or the arm's joint rates [rad/s]), amplitude A_k |v| / full_speed
|H(f_k)|, H the fingertip mode's gain (film_dynamics.py). A drive of several joints is one set
of tones; tones are point samples at the RA rate (the myRIO has no anti-aliasing filter). One
compiled SymbolicVectorSystem; spectra: docs/model.md, "Drive vibration"."""

import dataclasses
import math

from pydrake.symbolic import Variable, floor, sin, sqrt
from pydrake.symbolic import abs as symbolic_abs
from pydrake.symbolic import max as symbolic_max
from pydrake.systems.primitives import Multiplexer, SymbolicVectorSystem

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.rig.api_boundary import public_dataclass


@public_dataclass
@dataclasses.dataclass
class DriveVibrationConfig:
    """One drive's tones (all-zero amplitudes: off); docs/model.md, "Drive vibration"."""
    # Each tone's base acceleration at the fingertip at full speed [m/s^2] (assumed).
    amplitudes_mps2: list[float] = bounded(
        default_factory=list, low=0.0, high=1.0, unit="m/s^2",
        why="a gearmotor's housing vibration is of order 0.1-1 m/s^2",
        below="must be zero (off) or positive [m/s^2]")
    # Each tone's frequency in motor revolutions (a gear mesh's teeth per revolution).
    orders: list[float] = bounded(default_factory=list, low=0.0, high=1000.0,
                                  why="tones per motor revolution: a gear mesh's teeth",
                                  below="must be zero or more")
    # Motor revolutions per unit of the joint's travel.
    motor_revolutions_per_unit: float = bounded(
        0.0, low=0.0, high=1e5, unit="rev/m or rev/rad",
        why="the 2F-85's 1,333 rev/m, the JACO2's 15.9 rev/rad",
        below="must be zero or more")
    # The joint rate [m/s or rad/s] at which the tones reach amplitudes_mps2.
    full_speed: float = bounded(1.0, low=0.0, low_open=True, high=10.0,
                                unit="m/s or rad/s",
                                why="the 2F-85's 0.075 m/s, the JACO2's 0.628 rad/s",
                                below="must be positive (the joint rate of the amplitudes)")

    def enabled(self) -> bool:
        return any(a != 0.0 for a in self.amplitudes_mps2)


def gripper_drive_default() -> DriveVibrationConfig:
    """The 2F-85's motor and gear (assumed): about 100 rev/s at full speed, 75 mm/s of half
    opening (Robotiq 2F-85 specifications), so 1,333 rev/m; its rotation (order 1) and a
    12-tooth pinion's mesh (order 12)."""
    return DriveVibrationConfig(amplitudes_mps2=[0.1, 0.3], orders=[1.0, 12.0],
                                motor_revolutions_per_unit=100.0 / 0.075, full_speed=0.075)


def arm_drive_default() -> DriveVibrationConfig:
    """The JACO2's actuators (assumed): a 100:1 harmonic drive per joint, its wave generator's
    two lobes (order 2, Tuttle and Seering 1996) and 200 flexspline teeth meshing twice a
    revolution (order 400); full speed 36 deg/s (Kinova JACO2 specifications)."""
    return DriveVibrationConfig(amplitudes_mps2=[0.05, 0.05], orders=[2.0, 400.0],
                                motor_revolutions_per_unit=100.0 / (2.0 * math.pi),
                                full_speed=math.radians(36.0))


def mode_gain(frequency_hz: float, mode_frequency_hz: float, damping_ratio: float) -> float:
    """|H(f)| of the module docstring."""
    r = frequency_hz / mode_frequency_hz
    return 1.0 / math.sqrt((1.0 - r * r) ** 2 + (2.0 * damping_ratio * r) ** 2)


def _symbolic_mode_gain(frequency_hz, mode_frequency_hz: float, damping_ratio: float):
    """mode_gain of a symbolic frequency."""
    r = frequency_hz * (1.0 / mode_frequency_hz)
    return 1.0 / sqrt((1.0 - r * r) ** 2 + (2.0 * damping_ratio * r) ** 2)


def drive_tones(drives, period_s: float, mode_frequency_hz: float, damping_ratio: float):
    """(inputs, states, next states, reading) of the symbolic system for `drives`, a list of
    (DriveVibrationConfig, number of joints); one phase [rev, in [0, 1)] per drive and tone."""
    inputs, states, updates, reading = [], [], [], 0.0
    for d, (config, joints) in enumerate(drives):
        rates = [Variable(f"v{d}_{j}") for j in range(joints)]
        inputs.extend(rates)
        fastest = symbolic_abs(rates[0])
        for v in rates[1:]:
            fastest = symbolic_max(fastest, symbolic_abs(v))
        speed = symbolic_abs(rates[0]) if joints == 1 else sqrt(sum(v * v for v in rates))
        for k, (amplitude, order) in enumerate(zip(config.amplitudes_mps2, config.orders)):
            if amplitude == 0.0:
                continue
            phase = Variable(f"phase{d}_{k}")
            states.append(phase)
            frequency = order * config.motor_revolutions_per_unit * fastest
            advanced = phase + frequency * period_s
            updates.append(advanced - floor(advanced))
            gain = _symbolic_mode_gain(frequency, mode_frequency_hz, damping_ratio)
            reading = reading + (amplitude / config.full_speed) * speed * gain * sin(
                2.0 * math.pi * phase)
    return inputs, states, updates, reading


def AddDriveVibration(builder, *, sources, period_s: float, mode_frequency_hz: float,
                      damping_ratio: float, name: str = "drive_vibration"):
    """Adds the drives' vibration to `builder` from `sources`, (DriveVibrationConfig,
    joint-rate port) pairs; returns its [left, right] output [m/s^2], or None when all are off."""
    sources = [(config, port) for config, port in sources if config.enabled()]
    if not sources:
        return None
    drives = [(config, port.size()) for config, port in sources]
    inputs, states, updates, reading = drive_tones(drives, period_s, mode_frequency_hz,
                                                   damping_ratio)
    system = builder.AddNamedSystem(name, SymbolicVectorSystem(
        state=states, input=inputs, dynamics=updates, output=[reading, reading],
        time_period=period_s))
    if len(sources) == 1:
        builder.Connect(sources[0][1], system.get_input_port())
    else:
        mux = builder.AddNamedSystem(f"{name}_joint_rates",
                                     Multiplexer([port.size() for _, port in sources]))
        for k, (_, port) in enumerate(sources):
            builder.Connect(port, mux.get_input_port(k))
        builder.Connect(mux.get_output_port(), system.get_input_port())
    return system.get_output_port()
