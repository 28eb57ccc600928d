"""The piezo film on a pad (the RA source).

Drake's Accelerometer on the pad frame, without the gravity term (a piezo film sees no
constant acceleration), plus the texture vibration of slip when given
(pad_slip_vibration.py), then a first-order discrete high-pass filter at the charge amplifier's
corner frequency (1 / (2 pi R_f C_f)), plus seeded Gaussian noise, all sampled at the
sensor rate. Seed the noise with `diagram.SetRandomContext(context, RandomGenerator(seed))`.
"""

import dataclasses
import math

import numpy as np
from pydrake.common import RandomDistribution
from pydrake.systems.primitives import Adder, Gain, LinearSystem, RandomSource
from pydrake.systems.sensors import Accelerometer


@dataclasses.dataclass
class VibrationSensorConfig:
    """The piezo film of each pad (RA channel source): a high-passed accelerometer."""
    sample_rate_hz: float = 1000.0
    noise_std_mps2: float = 0.05
    highpass_cutoff_hz: float = 2.0  # charge amplifier R_f C_f corner
    # Texture of the pad cover that sliding drags the film over (pad_slip_vibration.py): a
    # woven fabric of about 0.5 mm pitch with a few micrometres of relief. 0 disables.
    slip_texture_height_m: float = 5e-6
    slip_texture_period_m: float = 5e-4


def highpass_matrices(cutoff_hz: float, dt: float):
    """(A, B, C, D) of the discrete first-order high-pass y[k] = a (y[k-1] + u[k] - u[k-1])
    for 3 axes, written with state w[k] = y[k-1] - u[k-1]."""
    rc = 1.0 / (2.0 * math.pi * cutoff_hz)
    a = rc / (rc + dt)
    eye = np.eye(3)
    return a * eye, (a - 1.0) * eye, a * eye, a * eye


def AddPadVibrationSensor(builder, plant, body, X_BS, config: VibrationSensorConfig,
                             name: str, slip_vibration=None):
    """Adds the sensor for `body` (sensor frame S at X_BS); returns its output port (3,
    m/s^2, expressed in S). `slip_vibration`, if given, is an output port (3, m/s^2 in S)
    added to the rigid-body acceleration before the film's high-pass."""
    dt = 1.0 / config.sample_rate_hz
    accelerometer = builder.AddNamedSystem(f"{name}_accelerometer",
                                           Accelerometer(body, X_BS, np.zeros(3)))
    builder.Connect(plant.get_body_poses_output_port(), accelerometer.get_body_poses_input_port())
    builder.Connect(plant.get_body_spatial_velocities_output_port(),
                    accelerometer.get_body_velocities_input_port())
    builder.Connect(plant.get_body_spatial_accelerations_output_port(),
                    accelerometer.get_body_accelerations_input_port())
    A, B, C, D = highpass_matrices(config.highpass_cutoff_hz, dt)
    highpass = builder.AddNamedSystem(f"{name}_highpass", LinearSystem(A, B, C, D, dt))
    film_input = accelerometer.get_measurement_output_port()
    if slip_vibration is not None:
        film = builder.AddNamedSystem(f"{name}_film_adder", Adder(2, 3))
        builder.Connect(film_input, film.get_input_port(0))
        builder.Connect(slip_vibration, film.get_input_port(1))
        film_input = film.get_output_port()
    builder.Connect(film_input, highpass.get_input_port())
    if config.noise_std_mps2 <= 0:
        return highpass.get_output_port()
    noise = builder.AddNamedSystem(f"{name}_noise",
                                   RandomSource(RandomDistribution.kGaussian, 3, dt))
    scale = builder.AddNamedSystem(f"{name}_noise_gain", Gain(config.noise_std_mps2, 3))
    adder = builder.AddNamedSystem(f"{name}_adder", Adder(2, 3))
    builder.Connect(noise.get_output_port(), scale.get_input_port())
    builder.Connect(highpass.get_output_port(), adder.get_input_port(0))
    builder.Connect(scale.get_output_port(), adder.get_input_port(1))
    return adder.get_output_port()
