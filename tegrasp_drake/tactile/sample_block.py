"""Sample blocks: the last B samples of a signal, kept in C++, read by Python once per block.

The tactile devices deliver their samples in bursts: the myRIO streams the films' samples in
frames, the AD7147 converts a pad's 12 taxels in one 9.26 ms sequence. The Python systems
that process the 1 kHz vibration samples (the event matcher's RA window, the slip band)
therefore run once per block of B samples, not once per sample: a Python call costs a few
microseconds of dispatch, a copy of the system's state and its port reads, several times
the arithmetic of one sample.

The samples are collected by a shift register built from Drake's own discrete LinearSystem
(no Python per sample): every sample period T its state takes the input, and its output is
the last B samples, oldest first, the newest being the input now (direct feedthrough),

    y(t) = [u(t - (B-1) T), ..., u(t - T), u(t)]      (B rows of the selected entries)

A block system updates every B T from time 0 (`block_update_period`) and, at time t, takes
the rows of y(t) the signal has had since the previous update: all B of them, except on the
update at t = 0, which takes the one sample taken at 0 (`samples_in_block`). So at every
block boundary its state equals that of a per-sample system fed the same samples.

BLOCK_PERIOD_S, 10 ms: about one AD7147 frame (9.26 ms at decimation 64, AD7147 data sheet), the
period at which the SA channels change anyway; a decision waits at most one block longer
than per sample, within the 10 ms latency the project allows a cheaper representation. Ten
1 kHz samples divide the 0.5 s event window (500) and its compaction slack (100).
"""

import math

import numpy as np
from pydrake.systems.primitives import LinearSystem

BLOCK_PERIOD_S = 0.010


def block_samples(rate_hz: float, block_s: float = BLOCK_PERIOD_S) -> int:
    """Samples of a signal at `rate_hz` [Hz] per block of `block_s` [s]: the whole samples
    that fit (a slower signal, such as the 108 Hz taxels, gets 1: it is processed per
    sample, its own frame being about a block); block_s = 0 gives 1 (per sample)."""
    if not (rate_hz > 0.0 and block_s >= 0.0):
        raise ValueError(f"rate_hz ({rate_hz}) must be positive and block_s ({block_s}) "
                         "non-negative")
    return max(1, math.floor(block_s * rate_hz + 1e-9))


# Block updates checked to fall on the register's sample times: 1e5 blocks, 1000 s of
# 10 ms blocks, longer than any trial or hardware run.
CHECKED_BLOCKS = 100_000


def block_update_period(sample_period_s: float, samples: int) -> float:
    """The period P = samples x sample_period_s [s] of a block system taking `samples`
    samples per update.

    Drake puts a periodic event at k P (doubles) and the register's samples at j T; an
    update must fall exactly on a sample time, or the simulator runs it a round-off before
    or after the register's update and the block is off by one sample. Raises ValueError
    when k P differs from (k samples) T for some of the first CHECKED_BLOCKS blocks (at
    1 kHz: blocks of 10, 16, 20 samples pass, 25 does not)."""
    period = samples * sample_period_s
    k = np.arange(CHECKED_BLOCKS, dtype=float)
    if not np.array_equal(k * period, (k * samples) * sample_period_s):
        raise ValueError(
            f"blocks of {samples} samples of {sample_period_s:g} s do not fall on the "
            "sample times in floating point; choose another block length (such as 10 or "
            "16 samples at 1 kHz)")
    return period


def samples_in_block(time_s: float, sample_period_s: float, samples: int) -> int:
    """How many of the register's rows a block update at `time_s` takes: the samples taken
    since the previous update (every update is at a multiple of samples x the period; the
    one at 0 has only the sample taken at 0)."""
    return min(samples, int(round(time_s / sample_period_s)) + 1)


def sample_register(input_size: int, samples: int, sample_period_s: float,
                    entries=None) -> LinearSystem:
    """A discrete LinearSystem (C++) whose output is the last `samples` samples of
    `entries` (indices into its input of `input_size`; default all), oldest first, flat
    row-major (samples x entries), the newest being its input now (module docstring)."""
    rows = np.eye(input_size)[list(range(input_size)) if entries is None else list(entries)]
    width = rows.shape[0]
    if samples < 2:
        raise ValueError(f"a sample register holds 2 or more samples, not {samples}")
    stored = (samples - 1) * width  # the samples before the newest
    A = np.eye(stored, k=width)  # each stored sample moves one row older
    B = np.zeros((stored, input_size))
    B[stored - width:] = rows  # the input becomes the newest stored sample
    C = np.vstack([np.eye(stored), np.zeros((width, stored))])
    D = np.vstack([np.zeros((stored, input_size)), rows])
    return LinearSystem(A, B, C, D, sample_period_s)


def AddSampleRegister(builder, port, *, samples: int, sample_period_s: float, entries=None,
                      name: str):
    """Adds a sample_register named `name` fed by `port` (an output port); returns its
    output port (samples x entries, oldest first)."""
    register = builder.AddNamedSystem(name, sample_register(
        port.size(), samples, sample_period_s, entries))
    builder.Connect(port, register.get_input_port())
    return register.get_output_port()
