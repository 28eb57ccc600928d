"""The 2F-85's drive in closed form: its motor's rotor, the firmware's position loop, the
current limit and the self-locking screw; the one source of their parameters.

One brushless motor turns a screw whose nut drives both fingers' drivers. Robotiq's
simulation guide for its Isaac Sim assets (robotiq/isaacsim_assets,
`grippers/GRIPPER_SIMULATION_GUIDE.md`, section 4.4) gives the rotor, 181 g cm^2, and the
ratio from the motor to the driver joint, 26-32 depending on the position, about 30 on
average: 1.63e-2 kg m^2 reflected onto the driver. (MuJoCo Menagerie's `2f85.xml` puts an
armature of 0.005 kg m^2 on each driver joint.) The instruction manual (register rFR): the
force setting caps the motor's current while the fingers move; past it the fingers stop and
report an object (gOBJ); the screw does not backdrive, so it holds whatever force was reached
and the motor draws no current (the manual's Modbus example of a finished grasp reads
gCU = 0x00).

The model, in the driver joint's coordinate a [rad] (positive closing on the left finger):

- the firmware's position loop, a PD of bandwidth f on the drive's inertia J:
  tau = K (a_ref - a) + D (v_ref - v), K = J (2 pi f)^2, D = 2 zeta J (2 pi f), critically
  damped (zeta = 1: the 2F-85 does not overshoot a requested position);
- the current limit while moving: |tau| <= 2 F |dy/da| (F the force setting per pad, dy/da
  the pad's lever, both pads on the one motor; robotiq/linkage.py);
- the screw: self-locking, so a load never drives the rotor back. Its efficiency eta (forward
  drive) sets what the rotor's inertia weighs at the fingers while the motor drives them
  through it: J = J_linkage + eta J_rotor_reflected (the firmware calibrates the current to
  the force at the pad, so eta does not enter the force). A lead screw locks itself when its
  friction angle exceeds its lead angle, which holds its forward efficiency below 0.5;
  eta = tan(lead) / tan(lead + atan(mu)) is 0.26-0.47 for lead angles of 3-8 degrees and a
  steel-on-bronze friction of 0.15 (Shigley's Mechanical Engineering Design, power screws):
  0.35 by default.
- a stop: once the rotor stands with the motor at its limit, the firmware reports the
  object and cuts the current; the screw holds the force of that instant, which exceeds the
  setting by what the rotor's kinetic energy pressed into the contact.

`grip_rise` integrates this model against a linear contact (a stiffness and the
Hunt-Crossley dissipation of Drake's hydroelastic contact): the rise time of the grip force
and the force the screw holds.
"""

import dataclasses
import math

ROTOR_INERTIA_KG_M2 = 181e-7  # 181 g cm^2 (the guide, section 4.4)
GEAR_RATIO = 30.0  # motor turns per driver turn: 26-32 over the stroke, about 30 on average
REFLECTED_ROTOR_INERTIA_KG_M2 = ROTOR_INERTIA_KG_M2 * GEAR_RATIO ** 2  # 1.63e-2 kg m^2
# Both fingers' linkage about the left driver's axis, the loops closed: measured on the
# gripper bench with no rotor (the driver's torque over its acceleration as the free
# fingers start to close; the links' masses from Menagerie).
LINKAGE_INERTIA_KG_M2 = 1.7e-4
SCREW_EFFICIENCY = 0.35  # forward efficiency of the self-locking screw (module docstring)
SCREW_EFFICIENCY_RANGE = (0.2, 0.5)  # self-locking needs < 0.5; below 0.2 is a worm drive
POSITION_LOOP_HZ = 60.0
# The position loop's bandwidth [Hz]: the 2F-85 takes position requests at up to 200 Hz, and
# a loop faster than half that rate follows no command faster; from 40 Hz on, the locked
# drive (which holds with the loop's stiffness in this model) moves a pad less than 0.5 mm
# under 50 N. Above 150 Hz a 1 ms plant step no longer resolves the loop (2 pi f h > 1).
POSITION_LOOP_HZ_RANGE = (40.0, 150.0)
POSITION_LOOP_DAMPING_RATIO = 1.0


def drive_inertia(screw_efficiency: float = SCREW_EFFICIENCY) -> float:
    """The drive's inertia about the driver joint [kg m^2] as the motor's force at the
    fingers moves it: the linkage plus the rotor through the screw."""
    return LINKAGE_INERTIA_KG_M2 + screw_efficiency * REFLECTED_ROTOR_INERTIA_KG_M2


def loop_gains(position_loop_hz: float, inertia: float,
               damping_ratio: float = POSITION_LOOP_DAMPING_RATIO) -> tuple[float, float]:
    """(K [N m/rad], D [N m s/rad]) of a position loop of bandwidth position_loop_hz on
    `inertia` [kg m^2]."""
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
    """The grip force per pad from the first touch, by the drive model of the module
    docstring: both pads meet a contact of stiffness_n_per_m [N/m per pad] (force
    k x (1 + d dx/dt), d the Hunt-Crossley dissipation [s/m]) while the fingers close at
    finger_speed_mps [m/s each] with the loop tracking its reference; force_n [N] is the
    force setting, lever_m [m] the pad's |dy/da| at the contact (constant over the
    sub-millimetre squeeze). Integrated by semi-implicit Euler with step dt [s]."""
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
