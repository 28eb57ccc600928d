"""The per-tick slip band (slip_vibration_band.py) as one compiled discrete SymbolicVectorSystem
(the biquad's delays and each pad's window of squares in its state), so no Python runs per sample;
bursts and blocks, of varying length, stay with SlipVibrationBand."""

import numpy as np
from pydrake.symbolic import Variable, sqrt
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import SymbolicVectorSystem
from scipy import signal

from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.rig.number_text import number_text

_AXES = 3 * len(FINGER_NAMES)  # (x, y, z) of each pad's vibration vector


def highpass_biquad(band_hz: float, sample_rate_hz: float) -> np.ndarray:
    """[b0, b1, b2, a1, a2] of the Butterworth high-pass at band_hz, sample_rate_hz [Hz]."""
    if not 0.0 < band_hz < sample_rate_hz / 2:
        raise ValueError(f"slip band {number_text(band_hz)} Hz must lie between 0 and the Nyquist "
                         f"frequency {number_text(sample_rate_hz / 2)} Hz of the RA samples")
    sos = signal.butter(2, band_hz, "highpass", fs=sample_rate_hz, output="sos")[0]
    return np.array([sos[0], sos[1], sos[2], sos[4], sos[5]])



def slip_band_system(*, band_hz: float, window_s: float,
                     sample_rate_hz: float) -> SymbolicVectorSystem:
    """The slip band as a SymbolicVectorSystem: vibration (6) in, RMS [left, right] out [m/s^2]."""
    b0, b1, b2, a1, a2 = highpass_biquad(band_hz, sample_rate_hz).tolist()
    window = max(1, round(window_s * sample_rate_hz))
    x = [Variable(f"x{i}") for i in range(_AXES)]
    z1 = [Variable(f"z1_{i}") for i in range(_AXES)]
    z2 = [Variable(f"z2_{i}") for i in range(_AXES)]
    squares = [[Variable(f"{finger}_square_{k}") for k in range(window)]
               for finger in FINGER_NAMES]
    y = [b0 * u + d for u, d in zip(x, z1)]
    updates = ([b1 * u - a1 * v + d for u, v, d in zip(x, y, z2)]
               + [b2 * u - a2 * v for u, v in zip(x, y)])
    for k, pad in enumerate(squares):
        yx, yy, yz = y[3 * k:3 * k + 3]
        updates += pad[1:] + [(yx * yx + yy * yy) + yz * yz]
    output = [sqrt(sum(pad[1:], pad[0]) / window) for pad in squares]
    return SymbolicVectorSystem(state=z1 + z2 + [s for pad in squares for s in pad], input=x,
                                dynamics=updates, output=output,
                                time_period=1.0 / sample_rate_hz)


def MakeSlipVibrationBand(*, band_hz: float, window_s: float, sample_rate_hz: float):
    """The per-tick slip band of a simulated station as a Diagram.

    .. pydrake_system::

        name: SlipVibrationBand
        input_ports:
        - pad_acceleration
        output_ports:
        - slip_vibration

    pad_acceleration (6) [m/s^2, pad frames] in; slip_vibration [left, right] [m/s^2] out.
    """
    builder = DiagramBuilder()
    band = builder.AddNamedSystem("slip_band", slip_band_system(
        band_hz=band_hz, window_s=window_s, sample_rate_hz=sample_rate_hz))
    builder.ExportInput(band.get_input_port(), "pad_acceleration")
    builder.ExportOutput(band.get_output_port(), "slip_vibration")
    diagram = builder.Build()
    diagram.set_name("slip_vibration_band")
    return diagram
