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

The filter runs once per device sample, in one of three modes:

- per tick (`block_samples` 1): each update reads `pad_acceleration`;
- in blocks (`block_samples` B > 1, simulation): every B samples one update filters the
  block of the last B samples that a sample register (tactile/sample_block.py) kept on
  `pad_acceleration_block`, by one matrix product: the biquad is linear, so its B outputs
  and its delays after the block are a fixed matrix times the block's samples and the
  delays before it (`biquad_block_map`); at each block boundary the band equals the
  per-tick band (to round-off), between boundaries it holds the last block's value, at
  most B - 1 samples old;
- device samples (hardware): the samples arrive in bursts and the receiver holds or merges
  them to give one value per tick, and a held value followed by a jump is a step the
  high-pass rings on (beside a CPU hog, bursts of a few ticks rang above the slip threshold
  during a smooth lift). So when the `pad_acceleration_samples` input is connected (the
  hardware station's port of that name), each tick filters exactly the samples the device
  sent since the last one, in order, and a tick with none leaves the band as it was.

A slip slower than band_hz x 0.5 mm (40 mm/s at 80 Hz) is attenuated at 12 dB per octave:
the trigger sees fast slips (the object falling or the pads sliding along it at lift
speed), not creep.
"""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import BasicVector, LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.tactile.slip_band_diagram import MakeSlipVibrationBand, highpass_biquad
from tegrasp_drake.tactile.sample_block import (AddSampleRegister, block_update_period,
                                               samples_in_block)

_AXES = 3 * len(FINGER_NAMES)  # (x, y, z) of each pad's vibration vector


def biquad_block_map(coefficients: np.ndarray, samples: int) -> np.ndarray:
    """The biquad (transposed direct form II, [b0, b1, b2, a1, a2]) over `samples` samples
    as one matrix M ((samples + 2) x (samples + 2)): [y; z_after] = M [x; z_before], with x
    and y the block's inputs and outputs (oldest first) and z = [z1, z2] its delays (each
    column an axis)."""
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
        - pad_acceleration_block (optional)
        output_ports:
        - slip_vibration

    Ports:
        pad_acceleration: (6) [left x, y, z, right x, y, z] the pads' vibration [m/s^2],
            pad frames, sampled every 1 / sample_rate_hz.
        pad_acceleration_samples: (abstract, an (n, 6) array) when connected, the rows of
            pad_acceleration the device sampled since the last tick, oldest first; then
            pad_acceleration is not read.
        pad_acceleration_block: (block_samples x 6) the last block_samples rows of
            pad_acceleration, oldest first (a sample register's output); read, in place of
            pad_acceleration, when block_samples > 1.
        slip_vibration: (2) [left, right] RMS of the high-passed vibration over the last
            window_s [m/s^2].

    State (discrete, updated every block_samples / sample_rate_hz): the filter's two delays
    per axis (12) and the last window_s of squared magnitudes per pad (2 x n).
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
        # The mean as ndarray.mean computes it (its sum, then divided by the count),
        # without the Python wrapper that costs more than the sum.
        sums = np.add.reduce(squares.reshape(len(FINGER_NAMES), self._window), axis=1)
        output.SetFromVector(np.sqrt(sums / self._window))


def filter_block(block_map: np.ndarray, block: np.ndarray, s: np.ndarray,
                 window: int) -> None:
    """Advances a SlipVibrationBand's state vector s by the rows of `block` (k x 6, oldest
    first) [m/s^2], in place: the biquad over the block (block_map: biquad_block_map of k
    samples) from the delays in s, then each row's squared magnitude per pad into the
    window of the last `window`."""
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
    """Adds the slip band fed by `pad_acceleration` (an output port, 6): per tick, the
    compiled band (slip_band_diagram.py); with `pad_acceleration_samples` (an abstract
    output port, see the class) a SlipVibrationBand that runs per tick on the device's
    samples; else, with block_samples > 1, a SlipVibrationBand in blocks of that many
    samples, kept by a sample register (`slip_vibration_block`) on `pad_acceleration`.
    Returns its slip_vibration output port."""
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

