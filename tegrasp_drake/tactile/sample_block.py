"""Sample blocks: the last B samples of a signal, kept in C++ by a discrete LinearSystem shift
register, y(t) = [u(t - (B-1) T), ..., u(t)], and read by a Python system once per block, since one
Python call costs several times one sample's arithmetic. A block system updates every B T from 0
and takes the samples since its last update (`samples_in_block`), so at each block end it equals a
per-sample system. BLOCK_PERIOD_S, 10 ms: about one AD7147 frame (9.26 ms at decimation 64, AD7147
data sheet), and ten 1 kHz samples divide the 0.5 s event window."""

import math

import numpy as np
from pydrake.systems.primitives import LinearSystem

from tegrasp_drake.rig.number_text import number_text

BLOCK_PERIOD_S = 0.010


def block_samples(rate_hz: float, block_s: float = BLOCK_PERIOD_S) -> int:
    """Whole samples at `rate_hz` [Hz] per `block_s` [s] block, at least 1 (0: per sample)."""
    if not (rate_hz > 0.0 and block_s >= 0.0):
        raise ValueError(f"rate_hz ({number_text(rate_hz)}) must be positive and block_s "
                         f"({number_text(block_s)}) non-negative")
    return max(1, math.floor(block_s * rate_hz + 1e-9))


# blocks checked to fall on sample times: 1000 s of 10 ms blocks, longer than any run
CHECKED_BLOCKS = 100_000


def block_update_period(sample_period_s: float, samples: int) -> float:
    """The period P = samples x sample_period_s [s] of a block system. ValueError when k P
    differs from (k samples) T in floating point for one of the first CHECKED_BLOCKS blocks:
    such an update would run a round-off off the register's (at 1 kHz 10, 16, 20 pass)."""
    period = samples * sample_period_s
    k = np.arange(CHECKED_BLOCKS, dtype=float)
    if not np.array_equal(k * period, (k * samples) * sample_period_s):
        raise ValueError(
            f"blocks of {samples} samples of {sample_period_s:g} s do not fall on the "
            "sample times in floating point; choose another block length (such as 10 or "
            "16 samples at 1 kHz)")
    return period


def samples_in_block(time_s: float, sample_period_s: float, samples: int) -> int:
    """The register's rows a block update at `time_s` takes: those since the last (at 0, one)."""
    return min(samples, int(round(time_s / sample_period_s)) + 1)


def sample_register(input_size: int, samples: int, sample_period_s: float,
                    entries=None) -> LinearSystem:
    """A discrete LinearSystem whose output is the last `samples` samples of `entries`
    (default all), oldest first, flat row-major, the newest being its input now."""
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
    """Adds a sample_register fed by `port`; returns its output, samples x entries, oldest first."""
    register = builder.AddNamedSystem(name, sample_register(
        port.size(), samples, sample_period_s, entries))
    builder.Connect(port, register.get_input_port())
    return register.get_output_port()
