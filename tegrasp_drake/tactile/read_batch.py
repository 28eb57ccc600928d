"""Read batches: a fast signal's samples taken in one update just before its reader's tick.

A per-sample Python system read only at a 5 ms tick takes each tick's samples, each at
its own time, in one update a quarter sample period before the tick, from a held register
(AddHeldSampleRegister); a read at another instant may be up to a tick old. Why it is
exact: docs/controller.md (read batches)."""

import numpy as np
from pydrake.systems.primitives import MatrixGain, Multiplexer, ZeroOrderHold

from tegrasp_drake.rig.number_text import number_text

# read instants checked to fall on sample times: 500 s of 5 ms ticks
CHECKED_READS = 100_000


def samples_per_read(rate_hz: float, read_period_s: float) -> int:
    """Samples a read batch takes: S when the read period [s] holds a whole S >= 2 sample
    periods at `rate_hz` and its multiples fall exactly on sample times; else 1."""
    if not (rate_hz > 0.0 and read_period_s >= 0.0):
        raise ValueError(f"rate_hz ({number_text(rate_hz)}) must be positive and read_period_s "
                         f"({number_text(read_period_s)}) non-negative")
    exact = read_period_s * rate_hz
    samples = int(round(exact))
    if samples < 2 or abs(exact - samples) > 1e-9 * exact:
        return 1
    k = np.arange(CHECKED_READS, dtype=float)
    if not np.array_equal(k * read_period_s, (k * samples) * (1.0 / rate_hz)):
        return 1
    return samples


def batch_update_offset(rate_hz: float, read_period_s: float) -> float:
    """The batch updates' offset [s]: a quarter sample period before each read."""
    return read_period_s - 0.25 / rate_hz


def batch_first_sample(time_s: float, rate_hz: float, read_period_s: float,
                       samples: int) -> int:
    """The sample index of the oldest sample the batch update at time_s [s] takes."""
    reads = int(round((time_s - batch_update_offset(rate_hz, read_period_s))
                      / read_period_s))
    return reads * samples


def AddHeldSampleRegister(builder, port, *, samples: int, sample_period_s: float,
                          entries=None, name: str):
    """Adds a shift register (ZeroOrderHold and MatrixGain) of the last `samples` samples of
    `port`'s `entries` (default all), every sample_period_s [s]; returns its output port:
    samples x entries, oldest first, row-major."""
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
