"""Fixed-input tests of the simulation's small LeafSystems: fix each input, evaluate each
output, compare with the value worked out by hand here (Drake's own system-test pattern).

BodyForcePulse puts a force on the plant (the object's hit, the bench's pad push); FingerDrive is the validation scenes'
force-limited finger loop; PadSlipVibration turns a pad's slip speed into the texture's
vibration, h (2 pi v / lambda)^2 sin(2 pi v t / lambda) at a constant slip speed v.
"""

import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.math import SpatialVelocity
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.analysis import Simulator

from tegrasp_drake.simulation.body_force_pulse import BodyForcePulse, DisturbanceConfig
from tegrasp_drake.simulation.pad_slip_vibration import UPDATE_PERIOD_S, PadSlipVibration
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.simulation.tactile_pads import PadGeometry
from tegrasp_drake.simulation.validation_scenes import FingerDrive, GripProgram


def _forces_at(system, port_name: str, t: float) -> list:
    context = system.CreateDefaultContext()
    context.SetTime(t)
    return system.GetOutputPort(port_name).Eval(context)


# BodyForcePulse --------------------------------------------------------------------------

def test_object_force_pulse_acts_only_during_the_hit():
    config = DisturbanceConfig(hit_time_s=0.5, hit_force_n=[1.0, -20.0, 3.0],
                               hit_duration_s=0.02)
    pulse = BodyForcePulse.object_hit(body_index=BodyIndex(7), config=config)
    for t in (0.0, 0.499, 0.52, 0.6):  # before, and from the end on (half-open interval)
        assert _forces_at(pulse, "applied_spatial_force", t) == [], t
    for t in (0.5, 0.51, 0.5199):
        (force,) = _forces_at(pulse, "applied_spatial_force", t)
        assert force.body_index == BodyIndex(7)
        np.testing.assert_array_equal(force.p_BoBq_B, np.zeros(3))
        np.testing.assert_array_equal(force.F_Bq_W.translational(), [1.0, -20.0, 3.0])
        np.testing.assert_array_equal(force.F_Bq_W.rotational(), np.zeros(3))


def test_object_force_pulse_without_a_hit_never_pushes():
    pulse = BodyForcePulse.object_hit(body_index=BodyIndex(1), config=DisturbanceConfig())
    assert all(_forces_at(pulse, "applied_spatial_force", t) == [] for t in (0.0, 1.0, 100.0))


def test_a_pulse_without_an_end_pushes_at_its_point_from_its_start_on():
    push = BodyForcePulse(body_index=BodyIndex(4), p_BQ=[0.001, 0.002, 0.05],
                          f_W=[0.0, 12.5, 0.0], start_s=0.3)
    for t in (0.0, 0.2999):
        assert _forces_at(push, "applied_spatial_force", t) == [], t
    for t in (0.3, 2.0, 1e6):
        (force,) = _forces_at(push, "applied_spatial_force", t)
        assert force.body_index == BodyIndex(4)
        np.testing.assert_array_equal(force.p_BoBq_B, [0.001, 0.002, 0.05])
        np.testing.assert_array_equal(force.F_Bq_W.translational(), [0.0, 12.5, 0.0])
        np.testing.assert_array_equal(force.F_Bq_W.rotational(), np.zeros(3))


# FingerDrive -----------------------------------------------------------------------------

PROGRAM = GripProgram(start_q=0.02, force_times_s=(0.0, 1.0), force_n=(25.0, 5.0),
                      closing_speed=0.01)
GAIN = 4000.0  # N/m


def _desired_state(t: float, q_left: float) -> np.ndarray:
    drive = FingerDrive(program=PROGRAM, position_gain=GAIN)
    context = drive.CreateDefaultContext()
    context.SetTime(t)
    drive.GetInputPort("finger_state").FixValue(context, [q_left, 0.5, 0.1, 0.2])
    return drive.GetOutputPort("desired_state").Eval(context)


def test_finger_drive_follows_the_ramp_while_the_finger_keeps_up():
    # t = 0.5 s: q_ref = 0.02 - 0.01 * 0.5 = 0.015 m, v_ref = -0.01 m/s; force 15 N, so the
    # set-point may lead the finger by 2 * 15 / 4000 = 7.5 mm: 4 mm behind is within it.
    np.testing.assert_allclose(_desired_state(0.5, 0.019), [0.015, -0.01], rtol=0, atol=1e-12)


def test_finger_drive_limits_the_lead_to_twice_the_force_over_the_gain():
    # A blocked finger at 30 mm: the lead is clipped at 7.5 mm (15 N at t = 0.5 s).
    np.testing.assert_allclose(_desired_state(0.5, 0.03), [0.03 - 0.0075, -0.01], rtol=0,
                               atol=1e-12)
    # After the ramp (0.01 m/s covers 20 mm by t = 2 s) the goal 0 holds, at rest; the
    # force profile stays at its last value, 5 N: a lead of 2.5 mm.
    np.testing.assert_allclose(_desired_state(3.0, 0.01), [0.0075, 0.0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(_desired_state(3.0, -0.001), [0.0, 0.0], rtol=0, atol=1e-12)


# PadSlipVibration ------------------------------------------------------------------------

HEIGHT, PERIOD = 5e-6, 5e-4  # m: the texture of the default VibrationSensorConfig
LEFT_BODY, RIGHT_BODY, OBJECT_BODY = 1, 2, 3
# The left pad frame P: on body 1 (at the world origin), 10 mm out along x, turned so that
# P's z (the pad normal) is world x. The right pad frame is body 2's, normal world z.
X_BP_LEFT = RigidTransform(RotationMatrix.MakeYRotation(math.pi / 2), [0.01, 0.0, 0.0])
PADS = {"left": PadGeometry(None, BodyIndex(LEFT_BODY), X_BP_LEFT),
        "right": PadGeometry(None, BodyIndex(RIGHT_BODY), RigidTransform())}


def _slip_system_and_context(left_taxel_n: float, right_taxel_n: float = 1.2):
    """A PadSlipVibration whose pads (left centre at world (0.01, 0, 0), normal x; right at
    (0.03, 0.02, 0), normal z) touch a sliding, spinning object."""
    config = VibrationSensorConfig(slip_texture_height_m=HEIGHT, slip_texture_period_m=PERIOD)
    system = PadSlipVibration(pads=PADS, object_body_index=OBJECT_BODY, config=config)
    context = system.CreateDefaultContext()
    poses = [RigidTransform(), RigidTransform(), RigidTransform([0.03, 0.02, 0.0]),
             RigidTransform([0.03, 0.0, 0.0])]
    # The object's origin translates at (0.005, 0, -0.02) and it spins at w = (0.4, 0.5,
    # -1.5) rad/s. At the left pad centre (r = (-0.02, 0, 0) from the object's origin)
    # w x r = (0, 0.03, 0.01); the pad moves at (0.001, 0.005, 0): relative velocity
    # (0.004, 0.025, -0.01), of which 4 mm/s is along the normal. At the right pad centre
    # (r = (0, 0.02, 0)) w x r = (0.03, 0, 0.008); the pad moves at (0.002, 0, 0.001):
    # relative (0.033, 0, -0.013), of which -13 mm/s is along the normal.
    velocities = [SpatialVelocity(), SpatialVelocity(np.zeros(3), [0.001, 0.005, 0.0]),
                  SpatialVelocity(np.zeros(3), [0.002, 0.0, 0.001]),
                  SpatialVelocity([0.4, 0.5, -1.5], [0.005, 0.0, -0.02])]
    system.GetInputPort("body_poses").FixValue(context, poses)
    system.GetInputPort("body_spatial_velocities").FixValue(context, velocities)
    system.GetInputPort("true_taxel_forces").FixValue(
        context, np.concatenate([np.full(12, left_taxel_n / 12), np.full(12, right_taxel_n / 12)]))
    return system, context


SLIP_SPEED = {"left": math.hypot(0.025, 0.01), "right": 0.033}  # the in-plane parts, m/s
AMPLITUDE = {finger: HEIGHT * (2 * math.pi * v / PERIOD) ** 2  # about 0.57 and 0.86 m/s^2
             for finger, v in SLIP_SPEED.items()}


def _texture(finger: str, t: float) -> float:
    return AMPLITUDE[finger] * math.sin(2 * math.pi * SLIP_SPEED[finger] * t / PERIOD)


def test_slip_vibration_is_the_texture_sine_at_the_pads_tangential_slip_speed():
    system, context = _slip_system_and_context(left_taxel_n=1.2)
    simulator = Simulator(system, context)
    for t in (0.0025, 0.0075, 0.0123, 0.0301):  # between samples, over several of them
        simulator.AdvanceTo(t)
        for finger in ("left", "right"):
            np.testing.assert_allclose(
                system.GetOutputPort(f"{finger}_slip_vibration").Eval(context),
                [0.0, 0.0, _texture(finger, t)], rtol=0, atol=1e-9)
    samples = math.floor(0.0301 / UPDATE_PERIOD_S)  # the last sample was taken at 0.030 s
    phases = [math.fmod(2 * math.pi * SLIP_SPEED[f] * samples * UPDATE_PERIOD_S / PERIOD,
                        2 * math.pi) for f in ("left", "right")]
    np.testing.assert_allclose(
        system.GetOutputPort("texture_state").Eval(context),
        [phases[0], AMPLITUDE["left"], SLIP_SPEED["left"],
         phases[1], AMPLITUDE["right"], SLIP_SPEED["right"]], rtol=1e-9, atol=1e-12)


def test_slip_vibration_is_silent_on_a_pad_that_touches_less_than_the_contact_force():
    system, context = _slip_system_and_context(left_taxel_n=0.15)  # CONTACT_FORCE_N is 0.2
    Simulator(system, context).AdvanceTo(0.0123)
    np.testing.assert_array_equal(system.GetOutputPort("texture_state").Eval(context)[:3],
                                  np.zeros(3))
    np.testing.assert_array_equal(system.GetOutputPort("left_slip_vibration").Eval(context),
                                  np.zeros(3))
    np.testing.assert_allclose(system.GetOutputPort("right_slip_vibration").Eval(context),
                               [0.0, 0.0, _texture("right", 0.0123)], rtol=0, atol=1e-9)


def test_slip_vibration_amplitude_grows_with_the_square_of_the_slip_speed():
    amplitudes = []
    for scale in (1.0, 2.0):
        system, context = _slip_system_and_context(left_taxel_n=1.2)
        velocities = system.GetInputPort("body_spatial_velocities").Eval(context)
        system.GetInputPort("body_spatial_velocities").FixValue(
            context, [SpatialVelocity(V.rotational() * scale, V.translational() * scale)
                      for V in velocities])
        Simulator(system, context).AdvanceTo(0.001)
        amplitudes.append(system.GetOutputPort("texture_state").Eval(context)[[1, 4]])
    np.testing.assert_allclose(amplitudes[1], 4.0 * amplitudes[0], rtol=1e-9)
    np.testing.assert_allclose(amplitudes[0], [AMPLITUDE["left"], AMPLITUDE["right"]],
                               rtol=1e-9)
