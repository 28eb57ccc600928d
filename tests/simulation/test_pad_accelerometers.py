"""The pads' high-passed accelerometers on a known motion: a body driven along the pad
normal by a sinusoidal force, gravity on."""

import math

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import PrismaticJoint, SpatialInertia
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, Sine

from tegrasp_drake.simulation.film_dynamics import first_order_highpass
from tegrasp_drake.simulation.pad_accelerometers import AddPadAccelerometers
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
from tegrasp_drake.simulation.tactile_pads import PadGeometry

MASS_KG = 0.1
FORCE_N = 0.5
FREQUENCY_HZ = 20.0


def run_known_motion(config, duration_s=0.5):
    """The left and right output logs of a body on a prismatic joint along z (the pad
    normal) pushed by FORCE_N sin(2 pi f t), both pads on it."""
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    body = plant.AddRigidBody("pad_body", SpatialInertia.SolidSphereWithMass(MASS_KG, 0.01))
    plant.AddJoint(PrismaticJoint("slide", plant.world_frame(), body.body_frame(), [0, 0, 1]))
    # As the station's hand: the plant applies no gravity to it (the arm carries it), but
    # the accelerometer feels it, 9.81 m/s^2 along the normal from the start.
    plant.set_gravity_enabled(body.model_instance(), False)
    plant.Finalize()
    force = builder.AddSystem(Sine(FORCE_N, 2 * math.pi * FREQUENCY_HZ, 0.0, 1))
    builder.Connect(force.get_output_port(0), plant.get_applied_generalized_force_input_port())
    pad = PadGeometry(None, body.index(), RigidTransform())
    system = AddPadAccelerometers(builder, plant=plant, pads={"left": pad, "right": pad},
                                  config=config)
    logs = [LogVectorOutput(system.GetOutputPort(f"{f}_pad_vibration"), builder, 1e-3)
            for f in ("left", "right")]
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.AdvanceTo(duration_s)
    context = simulator.get_context()
    return [log.FindLog(context) for log in logs]


def test_the_output_is_the_high_passed_normal_acceleration_without_gravity():
    config = VibrationSensorConfig(transducer="accelerometer", noise_std_mps2=0.0,
                                   highpass_cutoff_hz=2.0, sample_rate_hz=1000.0)
    left, right = run_known_motion(config)
    # The system's update at k ms reads the plant's acceleration then, F(k ms) / m; the
    # logger at k ms publishes before that update, so it shows the sample of (k - 1) ms.
    t = np.arange(0, 0.5 + 1e-9, 1e-3)
    acceleration = FORCE_N / MASS_KG * np.sin(2 * math.pi * FREQUENCY_HZ * t)
    expected = first_order_highpass(acceleration, 2.0, 1e-3)
    measured = left.data()[2]
    np.testing.assert_allclose(measured[1:], expected[:len(measured) - 1], atol=1e-9)
    np.testing.assert_array_equal(left.data(), right.data())
    assert np.all(left.data()[:2] == 0.0)  # x and y stay zero
    # Gravity (9.81 m/s^2 on the normal from the start) does not appear: the filter starts
    # on its first sample, and 20 Hz passes the 2 Hz high-pass almost whole.
    assert np.abs(measured).max() < 1.05 * FORCE_N / MASS_KG
    assert np.abs(measured[-100:]).max() > 0.95 * FORCE_N / MASS_KG


def test_noise_is_added_per_sample():
    config = VibrationSensorConfig(transducer="accelerometer", noise_std_mps2=0.5)
    left, _ = run_known_motion(config, duration_s=0.2)
    quiet, _ = run_known_motion(VibrationSensorConfig(transducer="accelerometer",
                                                      noise_std_mps2=0.0), duration_s=0.2)
    difference = left.data()[2] - quiet.data()[2]
    assert 0.3 < np.std(difference[10:]) < 0.7
