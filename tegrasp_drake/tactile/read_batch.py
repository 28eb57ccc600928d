"""Read batches: a fast signal's samples taken in one update just before its reader's tick.

A system that takes every 1 kHz RA sample in a Python update, but whose outputs only the
state machine reads at its 5 ms tick, takes each tick's samples in one update a quarter
sample period before the tick, each at its own time stamp, from a register that holds them
(AddHeldSampleRegister: a ZeroOrderHold shifted by a MatrixGain, C++ only, nothing drawn
when the context is randomised). The reader at the tick finds the per-sample state; a read
at another instant may find it up to one tick old. Why it is exact, and why a quarter
period: docs/controller.md (read batches).
"""

import numpy as np
from pydrake.systems.primitives import MatrixGain, Multiplexer, ZeroOrderHold

# Read instants checked to fall on the sample times: 1e5 reads, 500 s of 5 ms ticks.
CHECKED_READS = 100_000


def samples_per_read(rate_hz: float, read_period_s: float) -> int:
    """Samples at `rate_hz` [Hz] per read period [s] that a read batch takes: S, when the
    period holds a whole number S >= 2 of sample periods and its multiples k P fall on the
    sample times k S T in floating point for the first CHECKED_READS reads; else 1 (one
    update per sample; read_period_s 0: no reader's tick given)."""
    if not (rate_hz > 0.0 and read_period_s >= 0.0):
        raise ValueError(f"rate_hz ({rate_hz}) must be positive and read_period_s "
                         f"({read_period_s}) non-negative")
    exact = read_period_s * rate_hz
    samples = int(round(exact))
    if samples < 2 or abs(exact - samples) > 1e-9 * exact:
        return 1
    k = np.arange(CHECKED_READS, dtype=float)
    if not np.array_equal(k * read_period_s, (k * samples) * (1.0 / rate_hz)):
        return 1
    return samples


def batch_update_offset(rate_hz: float, read_period_s: float) -> float:
    """When [s] the batch update of each read period falls: a quarter sample period
    before each read (the updates are at this offset plus multiples of read_period_s)."""
    return read_period_s - 0.25 / rate_hz


def batch_first_sample(time_s: float, rate_hz: float, read_period_s: float,
                       samples: int) -> int:
    """The index (time / sample period) of the oldest of the `samples` samples that the
    batch update at time_s takes."""
    reads = int(round((time_s - batch_update_offset(rate_hz, read_period_s))
                      / read_period_s))
    return reads * samples


def AddHeldSampleRegister(builder, port, *, samples: int, sample_period_s: float,
                          entries=None, name: str):
    """Adds a shift register (module docstring) of the last `samples` samples of `entries`
    of `port` (indices into it; default all), taken every sample_period_s from t = 0; its
    systems are named `name`_*. Returns its output port: the samples, oldest first, flat
    row-major (samples x entries), the newest the one taken at the last sample time (held
    until the next)."""
    size = port.size()
    rows = np.eye(size)[list(range(size)) if entries is None else list(entries)]
    width = rows.shape[0]
    if samples < 1:
        raise ValueError(f"a sample register holds 1 or more samples, not {samples}")
    stored = samples * width
    gather = builder.AddNamedSystem(f"{name}_inputs", Multiplexer([stored, size]))
    # [stored; u] -> [stored without its oldest sample; the entries of u]
    shift = np.zeros((stored, stored + size))
    shift[:stored - width, width:stored] = np.eye(stored - width)
    shift[stored - width:, stored:] = rows
    step = builder.AddNamedSystem(f"{name}_shift", MatrixGain(shift))
    hold = builder.AddNamedSystem(f"{name}_samples", ZeroOrderHold(sample_period_s, stored))
    builder.Connect(hold.get_output_port(), gather.get_input_port(0))
    builder.Connect(port, gather.get_input_port(1))
    builder.Connect(gather.get_output_port(), step.get_input_port())
    builder.Connect(step.get_output_port(), hold.get_input_port())
    return hold.get_output_port()
