"""The Robotiq 2F-85 finger linkage in closed form: the one source of its dimensions
(docs/model.md, "The hand: the 2F-85 finger linkage").

Each finger is an underactuated five-bar in the base's y-z plane [m] (y along the stroke,
z the approach axis). Angles are the +y finger's SDF joint coordinates: theta, the driver's
turn from open (positive closing); beta, the coupler's turn off its pin (0 on it, negative
off it)."""

import dataclasses
import math
import typing

import numpy as np
from scipy.optimize import brentq

# Open-pose joint coordinates [m], (y, z), finger on +y: Robotiq's Isaac Sim kinematics asset
# (Robotiq_2F_85_kinematics_physics.usda); MuJoCo Menagerie's 2f85.xml agrees within 0.5 mm.
A = np.array([0.03060, 0.05466])
B = np.array([0.06213, 0.05090])
C = np.array([0.06776, 0.09809])
D = np.array([0.04986, 0.10460])
E = np.array([0.01270, 0.06118])

# [m] the pad face's centre, open: Menagerie's stock pad, the face at half the 85 mm stroke
PAD_CENTER_OPEN = np.array([0.0425, 0.1307])
DRIVER_RANGE_RAD = math.radians(47.0)  # the driver's travel (Isaac asset; Menagerie 0.8 rad)
COUPLER_RANGE_RAD = 1.57  # the coupler's travel off its pin (Menagerie: -1.57..0)
FOLLOWER_RANGE_RAD = 0.872664  # the follower's travel against the coupler (Menagerie)
# the spring at C holding B on its pin: 0.0004 N m/deg, 90 deg preload (Robotiq sim guide 4.2)
SPRING_STIFFNESS_NM_PER_RAD = 0.0004 * 180.0 / math.pi
SPRING_REST_ANGLE_RAD = -math.pi / 2.0

_AC = C - A
LINK_RADIUS = float(np.linalg.norm(_AC))  # m, 57.16 mm: the follower's circle on the pin
_PHI_OPEN = math.atan2(_AC[1], _AC[0])  # the angle of A->C from +y, open: 49.4 deg
# Python floats: half_opening and driver_angle run every plant step
_A_Y, _C_Y, _PAD_OPEN_Y, _AC_Y, _AC_Z = (float(x) for x in (A[0], C[0], PAD_CENTER_OPEN[0],
                                                           _AC[0], _AC[1]))


@dataclasses.dataclass(frozen=True)
class Functions:
    """The math functions of half_opening, driver_angle and half_opening_rate: on floats
    (FLOATS) or symbolic (ordered_expressions.SYMBOLIC), so one formula serves both."""
    cos: typing.Callable
    sin: typing.Callable
    acos: typing.Callable
    min: typing.Callable
    max: typing.Callable
    number: typing.Callable


FLOATS = Functions(cos=math.cos, sin=math.sin, acos=math.acos, min=min, max=max, number=float)


def _rotate(v, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def follower_offset(theta: float) -> np.ndarray:
    """The follower's (and pad's) displacement from open [m], (y, z), driver at theta [rad]."""
    return A + _rotate(_AC, theta) - C


def pad_center(theta: float) -> np.ndarray:
    """The pad face's centre [m], (y, z) in the base frame, with B on its pin."""
    return PAD_CENTER_OPEN + follower_offset(theta)


def half_opening(theta: float, f: Functions = FLOATS) -> float:
    """Half the opening [m], pad_center(theta)[0], on the pin (f: floats or expressions)."""
    c, s = f.cos(theta), f.sin(theta)
    return _PAD_OPEN_Y + ((_A_Y + (c * _AC_Y - s * _AC_Z)) - _C_Y)


def pad_travel(theta: float) -> float:
    """The pad's travel along the approach axis from open [m] (positive away from the palm)."""
    return float(follower_offset(theta)[1])


def driver_angle(half_opening_m: float, f: Functions = FLOATS) -> float:
    """The driver angle [rad] of half_opening_m [m] (half_opening's inverse, clipped)."""
    q = f.min(f.max(f.number(half_opening_m), 0.0), _PAD_OPEN_Y)
    cosine = (q - _PAD_OPEN_Y + _C_Y - _A_Y) / LINK_RADIUS
    return f.acos(f.min(f.max(cosine, -1.0), 1.0)) - _PHI_OPEN


THETA_PADS_MEET = driver_angle(0.0)  # rad, 45.96 deg: the pad faces touch


def half_opening_rate(theta: float, f: Functions = FLOATS) -> float:
    """d(half opening)/d(theta) [m/rad] on the pin: minus the pad's lever arm about A."""
    return -LINK_RADIUS * f.sin(_PHI_OPEN + theta)


def pad_travel_at_opening(opening_m: float) -> float:
    """The pad's travel along the approach axis [m] with the pads opening_m [m] apart."""
    return pad_travel(driver_angle(opening_m / 2.0))


@dataclasses.dataclass(frozen=True)
class FingerPose:
    """The moving joints [m], (y, z) in the base frame, and the follower's turn from open
    [rad] (positive: the fingertip tilts toward the object)."""
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    follower_angle: float


def _circle_intersection(p0, r0: float, p1, r1: float, near) -> np.ndarray:
    """The intersection of two circles (centre, radius) nearest `near`."""
    d = float(np.linalg.norm(p1 - p0))
    a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d)
    h = math.sqrt(max(r0 * r0 - a * a, 0.0))
    mid = p0 + a * (p1 - p0) / d
    perpendicular = np.array([-(p1 - p0)[1], (p1 - p0)[0]]) / d
    return min((mid + h * perpendicular, mid - h * perpendicular),
               key=lambda p: float(np.linalg.norm(p - near)))


def _angle_of(v) -> float:
    return math.atan2(v[1], v[0])


def finger_pose(theta: float, beta: float = 0.0) -> FingerPose:
    """The five-bar with the driver at theta and the coupler at beta [rad]."""
    b = A + _rotate(B - A, theta)
    c = b + _rotate(C - B, theta + beta)
    d_on_pin = D + follower_offset(theta)
    d = _circle_intersection(c, float(np.linalg.norm(D - C)), E,
                             float(np.linalg.norm(D - E)), near=d_on_pin)
    turn = _angle_of(d - c) - _angle_of(D - C)
    return FingerPose(b, c, d, (turn + math.pi) % (2.0 * math.pi) - math.pi)


def point_on_follower(theta: float, beta: float, p_open) -> np.ndarray:
    """Where the follower's point that sits at p_open [m] in the open pose is [m]."""
    pose = finger_pose(theta, beta)
    return pose.c + _rotate(np.asarray(p_open, float) - C, pose.follower_angle)


def _spring_joint_angle(theta: float, beta: float) -> float:
    """The follower's turn against the coupler [rad] (the SDF's follower joint angle)."""
    return finger_pose(theta, beta).follower_angle - (theta + beta)


def coupler_generalized_force(theta: float, contact_height_m: float, force_n: float,
                              step: float = 1e-6) -> float:
    """The generalized force on beta [N m] (negative: B leaves its pin) of force_n [N] pushing
    the pad outward (+y) contact_height_m [m] above its centre, plus the spring's."""
    p_open = PAD_CENTER_OPEN + np.array([0.0, contact_height_m])
    dp = (point_on_follower(theta, step, p_open)
          - point_on_follower(theta, -step, p_open)) / (2.0 * step)
    dgamma = (_spring_joint_angle(theta, step)
              - _spring_joint_angle(theta, -step)) / (2.0 * step)
    spring_torque = SPRING_STIFFNESS_NM_PER_RAD * (SPRING_REST_ANGLE_RAD
                                                   - _spring_joint_angle(theta, 0.0))
    return force_n * float(dp[0]) + spring_torque * dgamma


def flip_height(theta: float, force_n: float) -> float:
    """The contact height [m] above the pad centre below which force_n [N] lifts B off its pin."""
    return brentq(lambda h: coupler_generalized_force(theta, h, force_n), -0.1, 0.1,
                  xtol=1e-7)


def hooked_object_z(theta: float, contact_height_m: float, radius_m: float) -> float | None:
    """The approach-axis coordinate z [m, base frame] of the centre of a round object of
    radius_m [m] on the grasp axis (y = 0) that the +y finger, the driver at theta [rad], touches
    contact_height_m [m] above its pad's centre (along the pad, toward the fingertip) with the
    coupler off its pin: the fingertip curled past the object and hooks its far side. The
    coupler's turn is the one nearest the pin, in (-COUPLER_RANGE_RAD, 0), at which the pad
    face's inward normal at that point passes through the object's centre on y = 0; None when
    no turn does (the pad flat on the pin reaches the object at that opening, or the object
    is too wide for it). Rigid pad and object: the pad face is the open pose's, turned."""
    p_open = PAD_CENTER_OPEN + np.array([0.0, contact_height_m])

    def centre(beta: float) -> np.ndarray:
        pose = finger_pose(theta, beta)
        contact = pose.c + _rotate(p_open - C, pose.follower_angle)
        # the face's inward normal, -y in the open pose, turned with the follower
        return contact + radius_m * _rotate(np.array([-1.0, 0.0]), pose.follower_angle)

    # 1 deg steps from the pin: the first sign change is the curl nearest the pin
    betas = np.linspace(0.0, -COUPLER_RANGE_RAD, int(math.degrees(COUPLER_RANGE_RAD)) + 1)
    y = [float(centre(float(b))[0]) for b in betas]
    for k in range(len(betas) - 1):
        if y[k] == 0.0 or y[k] * y[k + 1] < 0.0:
            beta = brentq(lambda b: float(centre(b)[0]), float(betas[k + 1]), float(betas[k]),
                          xtol=1e-9) if y[k] != 0.0 else float(betas[k])
            return float(centre(beta)[1])
    return None
