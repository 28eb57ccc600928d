"""Each film's peak |RA| over a controller tick, as one compiled Drake system: the largest of
the last n RA samples [m/s^2], n the samples per tick (5 at the 1 kHz film and the 5 ms
tick). A controller that reads the RA channel once a tick sees one sample in n; a strike's
ring a few ms long can fall between its reads (docs/controller.md, "Finger strike"). On the
rig each film sample reaches the host in its own 1 ms frame (hardware/myrio/TACTILE_FRAME.md)
and the receiver keeps a burst's largest (tactile_serial_receiver.py), so the same system
sees every sample there too."""

from pydrake.symbolic import Variable
from pydrake.symbolic import abs as symbolic_abs
from pydrake.symbolic import max as symbolic_max
from pydrake.systems.framework import DiagramBuilder, OutputPort
from pydrake.systems.primitives import SymbolicVectorSystem

from tegrasp_drake.rig.channels import FINGER_NAMES


def samples_per_tick(sample_rate_hz: float, tick_s: float) -> int:
    """RA samples per controller tick (at least 1): tick_s [s] at sample_rate_hz [Hz]."""
    return max(1, int(round(sample_rate_hz * tick_s)))


def ra_tick_peak_system(samples: int, sample_period_s: float) -> SymbolicVectorSystem:
    """Both films' peak |RA| over the last `samples` samples: input [RA_left, RA_right],
    output the same [m/s^2]; the samples-1 before the input's are kept in a shift register
    updated every sample_period_s [s], so at any instant the output covers the input's
    present sample and the samples-1 before it, and reads a tick apart cover each sample
    once."""
    ra = [Variable(f"{finger}_ra") for finger in FINGER_NAMES]
    if samples <= 1:
        return SymbolicVectorSystem(input=ra, output=[symbolic_abs(x) for x in ra])
    kept = [[Variable(f"{finger}_ra_{k}") for k in range(1, samples)] for finger in FINGER_NAMES]
    dynamics, output = [], []
    for x, before in zip(ra, kept):
        dynamics += [symbolic_abs(x)] + before[:-1]
        peak = symbolic_abs(x)
        for value in before:
            peak = symbolic_max(peak, value)
        output.append(peak)
    return SymbolicVectorSystem(state=[v for pad in kept for v in pad], input=ra,
                                dynamics=dynamics, output=output,
                                time_period=sample_period_s)


def AddRaTickPeak(builder: DiagramBuilder, ra: OutputPort, *, sample_rate_hz: float,
                  tick_s: float, name: str = "ra_tick_peak") -> OutputPort:
    """Adds ra_tick_peak_system fed by `ra` ([RA_left, RA_right] [m/s^2] sampled at
    sample_rate_hz [Hz]) for a controller ticking every tick_s [s]; returns its output."""
    system = builder.AddNamedSystem(name, ra_tick_peak_system(
        samples_per_tick(sample_rate_hz, tick_s), 1.0 / sample_rate_hz))
    builder.Connect(ra, system.get_input_port())
    return system.get_output_port()
