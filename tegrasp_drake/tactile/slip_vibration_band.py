"""SlipVibrationBand: the pads' vibration in the band where slip rings, for Lift-Load
(docs/model.md, "Slip: the texture and the slip band"): per axis a second-order Butterworth
high-pass at band_hz, then each pad's RMS of |y| over window_s [m/s^2]. It filters one sample
per tick, blocks of samples, or on hardware exactly the device samples since the last tick
(docs/hardware.md, "Serial bursts and the slip band")."""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import BasicVector, LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.tactile.slip_band_diagram import MakeSlipVibrationBand, highpass_biquad
from tegrasp_drake.tactile.sample_block import (AddSampleRegister, block_update_period,
                                               samples_in_block)

_AXES = 3 * len(FINGER_NAMES)  # (x, y, z) of each pad's vibration vector


def biquad_block_map(coefficients: np.ndarray, samples: int) -> np.ndarray:
    """The biquad (transposed direct form II) over `samples` samples as one matrix M:
    [y; z_after] = M [x; z_before], x and y oldest first, z = [z1, z2] (a column per axis)."""
    b0, b1, b2, a1, a2 = coefficients
    A = np.array([[-a1, 1.0], [-a2, 0.0]])  # the delays' update, [z1, z2]' = A z + B x
    B = np.array([b1 - a1 * b0, b2 - a2 * b0])
    M = np.zeros((samples + 2, samples + 2))
    power = np.eye(2)  # A^k
    for k in range(samples):
        # y_k = b0 x_k + z1_k; z_k = A^k z_0 + sum_{i<k} A^(k-1-i) B x_i.
        M[k, k] = b0
        M[k, samples:] = power[0]
        for i in range(k):
            M[k, i] = (np.linalg.matrix_power(A, k - 1 - i) @ B)[0]
        power = A @ power
    for i in range(samples):
        M[samples:, i] = np.linalg.matrix_power(A, samples - 1 - i) @ B
    M[samples:, samples:] = power
    return M


def highpass_step_floats(coefficients: tuple[float, ...], x: list[float],
                         delays: list[float]) -> tuple[list[float], list[float]]:
    """One biquad sample on n axes in floats (cheaper than numpy): (y, next delays [z1, z2])."""
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
        - pad_acceleration_block (optional)
        output_ports:
        - slip_vibration

    pad_acceleration: (6) [left xyz, right xyz] [m/s^2, pad frames]; read instead, when
    connected, pad_acceleration_samples ((n, 6), the device's samples since the last tick)
    or, with block_samples > 1, pad_acceleration_block (the register's last rows).
    slip_vibration: [left, right] RMS [m/s^2]. State: the biquad's delays and the windows.
    """

    def __init__(self, *, band_hz: float, window_s: float, sample_rate_hz: float,
                 block_samples: int = 1):
        super().__init__()
        if block_samples < 1:
            raise ValueError(f"block_samples {block_samples} must be 1 or more")
        self._block_samples = block_samples
        self._sample_period = 1.0 / sample_rate_hz
        self._coefficients = highpass_biquad(band_hz, sample_rate_hz)
        self._coefficient_floats = tuple(self._coefficients.tolist())
        # The filter over k samples, for each k a block update may take (samples_in_block).
        self._block_maps = ([None] + [biquad_block_map(self._coefficients, k)
                                      for k in range(1, block_samples + 1)]
                            if block_samples > 1 else None)
        self._window = max(1, round(window_s * sample_rate_hz))
        self._input = self.DeclareVectorInputPort("pad_acceleration", _AXES)
        self._samples = self.DeclareAbstractInputPort(
            "pad_acceleration_samples", AbstractValue.Make(np.zeros((0, _AXES))))
        self._block = self.DeclareVectorInputPort("pad_acceleration_block",
                                                  block_samples * _AXES)
        size = 2 * _AXES + len(FINGER_NAMES) * self._window
        self._state = self.DeclareDiscreteState(BasicVector(np.zeros(size)))
        if block_samples > 1:
            self.DeclarePeriodicDiscreteUpdateEvent(
                block_update_period(self._sample_period, block_samples), 0.0,
                self._update_block)
        else:
            self.DeclarePeriodicDiscreteUpdateEvent(self._sample_period, 0.0, self._update)
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

    @property
    def block_samples(self) -> int:
        """Samples per update: 1 per tick, more in blocks (the module docstring)."""
        return self._block_samples

    def _update_block(self, context, discrete_state):
        s = discrete_state.get_mutable_value(self._state)
        taken = samples_in_block(context.get_time(), self._sample_period, self._block_samples)
        block = self._block.Eval(context).reshape(self._block_samples, _AXES)[-taken:]
        filter_block(self._block_maps[taken], block, s, self._window)

    def _filter_sample(self, s: np.ndarray, x: list[float]):
        """Advances the state vector s by one sample x (6) [m/s^2], in place."""
        y, delays = highpass_step_floats(self._coefficient_floats, x, s[:2 * _AXES].tolist())
        s[:2 * _AXES] = delays
        # |y|^2 summed from the left, as np.add.reduce does, so both paths round alike
        squares = s[2 * _AXES:].reshape(len(FINGER_NAMES), self._window)
        squares[:, :-1] = squares[:, 1:]
        squares[:, -1] = [(y[i] * y[i] + y[i + 1] * y[i + 1]) + y[i + 2] * y[i + 2]
                          for i in range(0, _AXES, 3)]

    def _calc(self, context, output):
        squares = context.get_discrete_state(self._state).get_value()[2 * _AXES:]
        sums = np.add.reduce(squares.reshape(len(FINGER_NAMES), self._window), axis=1)
        output.SetFromVector(np.sqrt(sums / self._window))


def filter_block(block_map: np.ndarray, block: np.ndarray, s: np.ndarray,
                 window: int) -> None:
    """Advances a SlipVibrationBand's state vector s by the rows of `block` (k x 6, oldest
    first) [m/s^2] in place, block_map being biquad_block_map of k samples."""
    k = len(block)
    stacked = block_map @ np.vstack([block, s[:2 * _AXES].reshape(2, _AXES)])
    y = stacked[:k]
    s[:2 * _AXES] = stacked[k:].ravel()
    squares = s[2 * _AXES:].reshape(len(FINGER_NAMES), window)
    per_pad = y.reshape(len(y), len(FINGER_NAMES), 3)
    new = np.einsum("kpi,kpi->pk", per_pad, per_pad)  # |y|^2 per pad (rows) and sample
    entering = min(len(y), window)
    squares[:, :window - entering] = squares[:, entering:]
    squares[:, window - entering:] = new[:, len(y) - entering:]


def AddSlipVibrationBand(builder, pad_acceleration, *, band_hz: float, window_s: float,
                         sample_rate_hz: float, pad_acceleration_samples=None,
                         block_samples: int = 1):
    """Adds the slip band fed by `pad_acceleration` (6): per tick, on the device's samples
    when `pad_acceleration_samples` is given, else in blocks. Returns its output port."""
    if pad_acceleration_samples is not None:
        block_samples = 1
    elif block_samples == 1:
        band = builder.AddNamedSystem("slip_vibration_band", MakeSlipVibrationBand(
            band_hz=band_hz, window_s=window_s, sample_rate_hz=sample_rate_hz))
        builder.Connect(pad_acceleration, band.GetInputPort("pad_acceleration"))
        return band.GetOutputPort("slip_vibration")
    band = builder.AddNamedSystem("slip_vibration_band", SlipVibrationBand(
        band_hz=band_hz, window_s=window_s, sample_rate_hz=sample_rate_hz,
        block_samples=block_samples))
    builder.Connect(pad_acceleration, band.GetInputPort("pad_acceleration"))
    if pad_acceleration_samples is not None:
        builder.Connect(pad_acceleration_samples,
                        band.GetInputPort("pad_acceleration_samples"))
    elif block_samples > 1:
        builder.Connect(AddSampleRegister(builder, pad_acceleration, samples=block_samples,
                                          sample_period_s=1.0 / sample_rate_hz,
                                          name="slip_vibration_block"),
                        band.GetInputPort("pad_acceleration_block"))
    return band.GetOutputPort("slip_vibration")

