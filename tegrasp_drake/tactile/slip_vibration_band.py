"""SlipVibrationBand: the pads' vibration in the band where slip rings, for Lift-Load.

The PVDF film reads the rate of change of the pad's stress (docs/model.md, "Vibration (RA)
model"), so a grip that is still rising, the lift's load and the charge amplifier's decay
after them read too: several m/s^2 to 165 m/s^2, below about 10 Hz (a 0.45 s squeeze, a
0.3 s lift acceleration, the 2 Hz high-pass's 80 ms decay). Slip rings higher: the pad
cover's texture (0.5 mm pitch) sliding at v reads at v / 0.5 mm, 80 Hz at 40 mm/s, a lift's
speed. Slip detectors on vibration sensors read such a band (Howe and Cutkosky 1989, "Sensing
skin acceleration for slip and texture perception"; Romano et al. 2011 high-pass their
signals for the same reason). This system high-passes each pad's vibration vector and gives
its RMS over a short window, the amplitude the Lift-Load trigger compares with its
threshold.

    y = HP(a), per axis: a second-order Butterworth high-pass at `band_hz`
    slip_vibration_i = sqrt(mean over the last `window_s` of |y_i|^2)   [m/s^2]

The filter runs once per device sample. In simulation that is once per tick; on hardware
the samples arrive in bursts and the receiver holds or merges them to give one value per
tick, and a held value followed by a jump is a step the high-pass rings on (beside a CPU
hog, bursts of a few ticks rang above the slip threshold during a smooth lift). So when
the `pad_acceleration_samples` input is connected (the hardware station's port of that
name), each tick filters exactly the samples the device sent since the last one, in order,
and a tick with none leaves the band as it was.

A slip slower than band_hz x 0.5 mm (40 mm/s at 80 Hz) is attenuated at 12 dB per octave:
the trigger sees fast slips (the object falling or the pads sliding along it at lift
speed), not creep.
"""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import BasicVector, LeafSystem
from scipy import signal

from tegrasp_drake.rig.channels import FINGER_NAMES

_AXES = 3 * len(FINGER_NAMES)  # (x, y, z) of each pad's vibration vector


def highpass_biquad(band_hz: float, sample_rate_hz: float) -> np.ndarray:
    """[b0, b1, b2, a1, a2] of the second-order Butterworth high-pass at band_hz [Hz] for
    samples at sample_rate_hz [Hz] (a0 = 1)."""
    if not 0.0 < band_hz < sample_rate_hz / 2:
        raise ValueError(f"slip band {band_hz} Hz must lie between 0 and the Nyquist "
                         f"frequency {sample_rate_hz / 2} Hz of the RA samples")
    sos = signal.butter(2, band_hz, "highpass", fs=sample_rate_hz, output="sos")[0]
    return np.array([sos[0], sos[1], sos[2], sos[4], sos[5]])


def highpass_step_floats(coefficients: tuple[float, ...], x: list[float],
                         delays: list[float]) -> tuple[list[float], list[float]]:
    """One sample of the biquad (transposed direct form II) on n axes at once, on Python
    floats (numpy's per-call overhead on 6-vectors costs several times the arithmetic):
    x the samples, delays [z1 (n), z2 (n)]; returns (y, the next [z1, z2])."""
    b0, b1, b2, a1, a2 = coefficients
    n = len(x)
    y = [b0 * u + z1 for u, z1 in zip(x, delays[:n])]
    return y, ([b1 * u - a1 * v + z2 for u, v, z2 in zip(x, y, delays[n:])]
               + [b2 * u - a2 * v for u, v in zip(x, y)])


class SlipVibrationBand(LeafSystem):
    """Each pad's vibration RMS above the slip band's corner.

    .. pydrake_system::

        name: SlipVibrationBand
        input_ports:
        - pad_acceleration
        - pad_acceleration_samples (optional)
        output_ports:
        - slip_vibration

    Ports:
        pad_acceleration: (6) [left x, y, z, right x, y, z] the pads' vibration [m/s^2],
            pad frames, sampled every 1 / sample_rate_hz.
        pad_acceleration_samples: (abstract, an (n, 6) array) when connected, the rows of
            pad_acceleration the device sampled since the last tick, oldest first; then
            pad_acceleration is not read.
        slip_vibration: (2) [left, right] RMS of the high-passed vibration over the last
            window_s [m/s^2].

    State (discrete, updated every 1 / sample_rate_hz): the filter's two delays per axis
    (12) and the last window_s of squared magnitudes per pad (2 x n).
    """

    def __init__(self, *, band_hz: float, window_s: float, sample_rate_hz: float):
        super().__init__()
        self._coefficients = highpass_biquad(band_hz, sample_rate_hz)
        self._coefficient_floats = tuple(self._coefficients.tolist())
        self._window = max(1, round(window_s * sample_rate_hz))
        self._input = self.DeclareVectorInputPort("pad_acceleration", _AXES)
        self._samples = self.DeclareAbstractInputPort(
            "pad_acceleration_samples", AbstractValue.Make(np.zeros((0, _AXES))))
        size = 2 * _AXES + len(FINGER_NAMES) * self._window
        self._state = self.DeclareDiscreteState(BasicVector(np.zeros(size)))
        self.DeclarePeriodicDiscreteUpdateEvent(1.0 / sample_rate_hz, 0.0, self._update)
        self.DeclareVectorOutputPort("slip_vibration", len(FINGER_NAMES), self._calc,
                                     prerequisites_of_calc={self.xd_ticket()})

    def _update(self, context, discrete_state):
        # In place: discrete_state starts as a copy of the current state.
        s = discrete_state.get_mutable_value(self._state)
        if self._samples.HasValue(context):
            for x in self._samples.Eval(context):
                self._filter_sample(s, x.tolist())
        else:
            self._filter_sample(s, self._input.Eval(context).tolist())

    def _filter_sample(self, s: np.ndarray, x: list[float]):
        """Advances the state vector s by one sample x (6) [m/s^2], in place. The filter
        runs on Python floats (highpass_step_floats)."""
        y, delays = highpass_step_floats(self._coefficient_floats, x, s[:2 * _AXES].tolist())
        s[:2 * _AXES] = delays
        # The oldest squared magnitude of each pad leaves, the newest enters at the end
        # (numpy copies overlapping slices safely; |y|^2 summed x, y, z from the left, as
        # np.add.reduce does over 3 entries).
        squares = s[2 * _AXES:].reshape(len(FINGER_NAMES), self._window)
        squares[:, :-1] = squares[:, 1:]
        squares[:, -1] = [(y[i] * y[i] + y[i + 1] * y[i + 1]) + y[i + 2] * y[i + 2]
                          for i in range(0, _AXES, 3)]

    def _calc(self, context, output):
        squares = context.get_discrete_state(self._state).get_value()[2 * _AXES:]
        mean = squares.reshape(len(FINGER_NAMES), self._window).mean(axis=1)
        output.SetFromVector(np.sqrt(mean))


def AddSlipVibrationBand(builder, pad_acceleration, *, band_hz: float, window_s: float,
                         sample_rate_hz: float, pad_acceleration_samples=None):
    """Adds a SlipVibrationBand fed by `pad_acceleration` (an output port, 6) and, when
    given, `pad_acceleration_samples` (an abstract output port, see the class); returns
    its slip_vibration output port."""
    band = builder.AddNamedSystem("slip_vibration_band", SlipVibrationBand(
        band_hz=band_hz, window_s=window_s, sample_rate_hz=sample_rate_hz))
    builder.Connect(pad_acceleration, band.GetInputPort("pad_acceleration"))
    if pad_acceleration_samples is not None:
        builder.Connect(pad_acceleration_samples,
                        band.GetInputPort("pad_acceleration_samples"))
    return band.GetOutputPort("slip_vibration")

