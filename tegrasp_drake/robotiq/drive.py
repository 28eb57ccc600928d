"""The 2F-85's drive in closed form, the one source of its parameters, in the left driver's angle a
[rad]: a critically damped position loop (K = J (2 pi f)^2, D = 2 J (2 pi f)) capped at 2 F |dy/da|
while moving, and a self-locking screw that holds the force at the stop; `grip_rise` integrates it
against a linear contact (docs/model.md, "The drive: rotor, position loop")."""

import dataclasses
import math

# Robotiq's simulation guide for its Isaac Sim assets (GRIPPER_SIMULATION_GUIDE.md, 4.4):
ROTOR_INERTIA_KG_M2 = 181e-7  # 181 g cm^2
GEAR_RATIO = 30.0  # motor turns per driver turn: 26-32 over the stroke, about 30 on average
REFLECTED_ROTOR_INERTIA_KG_M2 = ROTOR_INERTIA_KG_M2 * GEAR_RATIO ** 2  # 1.63e-2 kg m^2
# both fingers' linkage about the left driver: measured on the gripper bench, no rotor
LINKAGE_INERTIA_KG_M2 = 1.7e-4
# Forward efficiency tan(lead) / tan(lead + atan(mu)): 0.26-0.47 for 3-8 deg leads, steel on
# bronze mu = 0.15 (Shigley's Mechanical Engineering Design, power screws).
SCREW_EFFICIENCY = 0.35
SCREW_EFFICIENCY_RANGE = (0.2, 0.5)  # self-locking needs < 0.5; below 0.2 is a worm drive
# [Hz], not published: 40 Hz holds a pad within 0.5 mm under 50 N, above 150 Hz a 1 ms
# step does not resolve it, and 200 Hz commands need no more than half that
POSITION_LOOP_HZ = 60.0
POSITION_LOOP_HZ_RANGE = (40.0, 150.0)
POSITION_LOOP_DAMPING_RATIO = 1.0  # the 2F-85 does not overshoot a requested position


def drive_inertia(screw_efficiency: float = SCREW_EFFICIENCY) -> float:
    """The drive's inertia about the driver joint [kg m^2]: linkage plus rotor through screw."""
    return LINKAGE_INERTIA_KG_M2 + screw_efficiency * REFLECTED_ROTOR_INERTIA_KG_M2


def loop_gains(position_loop_hz: float, inertia: float,
               damping_ratio: float = POSITION_LOOP_DAMPING_RATIO) -> tuple[float, float]:
    """(K [N m/rad], D [N m s/rad]) of a position_loop_hz position loop on `inertia` [kg m^2]."""
    omega = 2.0 * math.pi * position_loop_hz
    return inertia * omega * omega, 2.0 * damping_ratio * inertia * omega


@dataclasses.dataclass(frozen=True)
class GripRise:
    """The grip force's rise on contact (`grip_rise`)."""
    rise_s: float  # from 10 % to 90 % of the held force [s]
    held_n: float  # the force per pad the screw holds once the fingers stop [N]
    stop_s: float  # from the first touch to the stop [s]


def grip_rise(*, stiffness_n_per_m: float, force_n: float, finger_speed_mps: float,
              lever_m: float, position_loop_hz: float = POSITION_LOOP_HZ,
              screw_efficiency: float = SCREW_EFFICIENCY, dissipation_s_per_m: float = 0.0,
              damping_ratio: float = POSITION_LOOP_DAMPING_RATIO, dt: float = 2e-6,
              t_max: float = 2.0) -> GripRise:
    """The grip force per pad from the first touch: both pads meet a Hunt-Crossley contact
    (stiffness_n_per_m per pad, dissipation [s/m]) at finger_speed_mps each, force setting
    force_n [N], lever_m the pad's |dy/da| [m]; semi-implicit Euler of step dt [s]."""
    inertia = drive_inertia(screw_efficiency)
    gain, damping = loop_gains(position_loop_hz, inertia, damping_ratio)
    limit = 2.0 * force_n * lever_m  # the motor's torque cap [N m]
    rate = finger_speed_mps / lever_m  # the reference's rate [rad/s]
    a = reference = 0.0  # the driver's angle past the first touch, the reference's
    v = rate
    stuck = False
    times, forces = [], []
    t = 0.0
    while t < t_max:
        squeeze = a * lever_m  # each pad's penetration [m]
        force = (stiffness_n_per_m * squeeze * (1.0 + dissipation_s_per_m * v * lever_m)
                 if squeeze > 0.0 else 0.0)
        load = 2.0 * force * lever_m
        motor = min(max(gain * (reference - a) + damping * (rate - v), -limit), limit)
        if stuck and motor <= load:  # the screw holds the rotor
            if motor >= limit:  # standing at the current limit: the firmware stops
                break
            v = 0.0
        else:
            stuck = False
            v += dt * (motor - load) / inertia
            if v <= 0.0:  # the load would drive the rotor back: the screw locks
                v, stuck = 0.0, True
        a += dt * v
        reference += dt * rate
        t += dt
        times.append(t)
        forces.append(force)
    held = forces[-1]
    rise_start = next(t for t, f in zip(times, forces) if f >= 0.1 * held)
    rise_end = next(t for t, f in zip(times, forces) if f >= 0.9 * held)
    return GripRise(rise_s=rise_end - rise_start, held_n=held, stop_s=times[-1])
