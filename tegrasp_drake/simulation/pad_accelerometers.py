"""The idealised RA transducer of the paper's simulation (Sec. III-A, Fig. 4c;
`vibration.transducer: accelerometer`): per pad a Drake `Accelerometer` on the pad frame
(with gravity), its inward-normal (z) component through the first-order high-pass
y[k] = a (y[k-1] + u[k] - u[k-1]), a = RC / (RC + T), at the RA rate, plus Gaussian noise.
The outputs are the film's: [0, 0, y] per pad."""

import math

import numpy as np
from pydrake.common import RandomDistribution
from pydrake.systems.framework import LeafSystem
from pydrake.systems.primitives import RandomSource
from pydrake.systems.sensors import Accelerometer

from tegrasp_drake.rig.channels import FINGER_NAMES

VIBRATION_TRANSDUCERS = ("film", "accelerometer")
_NORMAL_AXIS = 2  # the pad frame's z, its inward normal


def highpass_coefficient(cutoff_hz: float, period_s: float) -> float:
    """a = RC / (RC + T) of the first-order high-pass at cutoff_hz sampled every period_s."""
    rc = 1.0 / (2.0 * math.pi * cutoff_hz)
    return rc / (rc + period_s)


class PadAccelerometers(LeafSystem):
    """Both pads' high-passed accelerometers (see the module docstring).

    .. pydrake_system::

        name: PadAccelerometers
        input_ports:
        - left_pad_frame_acceleration
        - right_pad_frame_acceleration
        - noise (optional)
        output_ports:
        - left_pad_vibration
        - right_pad_vibration

    Ports: *_pad_frame_acceleration (3, m/s^2, pad frame; a Drake Accelerometer's); noise (2
    unit Gaussians at the RA rate, when noise_std_mps2 > 0); *_pad_vibration: [0, 0, y]
    (m/s^2, pad frame), the high-passed normal acceleration plus noise, every RA period.
    """

    def __init__(self, *, sample_rate_hz: float, highpass_cutoff_hz: float,
                 noise_std_mps2: float = 0.0):
        super().__init__()
        period = 1.0 / sample_rate_hz
        self._a = highpass_coefficient(highpass_cutoff_hz, period)
        self._noise_std = float(noise_std_mps2)
        self._accelerations = [self.DeclareVectorInputPort(f"{f}_pad_frame_acceleration", 3)
                               for f in FINGER_NAMES]
        self._noise = (self.DeclareVectorInputPort("noise", 2) if noise_std_mps2 > 0
                       else None)
        # Filter state: [started, u_left, u_right, y_left, y_right] (y without noise).
        self._filter = self.DeclareDiscreteState(5)
        self._samples = [self.DeclareDiscreteState(3) for _ in FINGER_NAMES]
        self.DeclarePeriodicDiscreteUpdateEvent(period, 0.0, self._update)
        for finger, sample in zip(FINGER_NAMES, self._samples):
            self.DeclareStateOutputPort(f"{finger}_pad_vibration", sample)

    def _update(self, context, discrete_state):
        state = context.get_discrete_state(self._filter).value()
        u = np.array([port.Eval(context)[_NORMAL_AXIS] for port in self._accelerations])
        if state[0] == 0.0:  # the first sample: start at rest on it
            previous, y = u, np.zeros(2)
        else:
            previous, y = state[1:3], state[3:5]
        y = self._a * (y + u - previous)
        discrete_state.get_mutable_value(self._filter)[:] = np.concatenate([[1.0], u, y])
        measured = y if self._noise is None else y + self._noise_std * self._noise.Eval(context)
        for sample, value in zip(self._samples, measured):
            discrete_state.get_mutable_value(sample)[_NORMAL_AXIS] = value


def AddPadFrameAccelerometer(builder, *, plant, pad, name: str, gravity) -> Accelerometer:
    """A Drake Accelerometer on `pad`'s frame of `plant`, adding `gravity` (zeros: none)."""
    accelerometer = builder.AddNamedSystem(name, Accelerometer(
        plant.get_body(pad.body_index), pad.X_BP, np.asarray(gravity, dtype=float)))
    builder.Connect(plant.get_body_poses_output_port(), accelerometer.get_body_poses_input_port())
    builder.Connect(plant.get_body_spatial_velocities_output_port(),
                    accelerometer.get_body_velocities_input_port())
    builder.Connect(plant.get_body_spatial_accelerations_output_port(),
                    accelerometer.get_body_accelerations_input_port())
    return accelerometer


def AddPadAccelerometers(builder, *, plant, pads: dict, config,
                         name: str = "pad_accelerometers") -> PadAccelerometers:
    """Adds both pads' accelerometers, their high-pass and its noise source to `builder`;
    `config`: the scenario's VibrationSensorConfig. Returns the PadAccelerometers system."""
    system = builder.AddNamedSystem(name, PadAccelerometers(
        sample_rate_hz=config.sample_rate_hz, highpass_cutoff_hz=config.highpass_cutoff_hz,
        noise_std_mps2=config.noise_std_mps2))
    gravity = plant.gravity_field().gravity_vector()
    for finger in FINGER_NAMES:
        accelerometer = AddPadFrameAccelerometer(
            builder, plant=plant, pad=pads[finger], name=f"{finger}_pad_accelerometer",
            gravity=gravity)
        builder.Connect(accelerometer.get_measurement_output_port(),
                        system.GetInputPort(f"{finger}_pad_frame_acceleration"))
    if config.noise_std_mps2 > 0:
        noise = builder.AddNamedSystem(f"{name}_noise", RandomSource(
            RandomDistribution.kGaussian, 2, 1.0 / config.sample_rate_hz))
        builder.Connect(noise.get_output_port(), system.GetInputPort("noise"))
    return system
