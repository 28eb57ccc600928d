"""The numerical core of the pad's PVDF film (the RA source): pure numpy functions. One pad has
five states s = [l1, l2, y, y', z]: l1, l2 a critically damped low-pass of the slow load L [N]; y
[m] the fingertip's mode, y'' + 2 zeta w y' + w^2 y = (l2 + d) / m with d [N] a direct load
(impact, slip texture); z the charge amplifier's low-pass of y. The output is a = w^2 (y - z)
[m/s^2], integrated exactly over 20 kHz internal steps. docs/model.md, "Vibration (RA) model"."""

import dataclasses
import math

import numpy as np
from pydrake.symbolic import if_then_else
from pydrake.symbolic import max as symbolic_max
from pydrake.symbolic import min as symbolic_min
from scipy.linalg import expm

STATE_SIZE = 5
_L1, _L2, _Y, _YDOT, _Z = range(STATE_SIZE)


@dataclasses.dataclass(frozen=True)
class FilmParameters:
    """The film: mode [Hz], damping ratio, modal mass [kg], load and amplifier corners [Hz]."""
    mode_frequency_hz: float
    damping_ratio: float
    modal_mass_kg: float
    load_lowpass_hz: float
    highpass_hz: float


def film_continuous_matrices(p: FilmParameters):
    """(A (5, 5), B (5, 2), c (5,)) of one pad: s' = A s + B [L, d], a = c s."""
    w = 2.0 * math.pi * p.mode_frequency_hz
    w_l = 2.0 * math.pi * p.load_lowpass_hz
    w_h = 2.0 * math.pi * p.highpass_hz
    A = np.zeros((STATE_SIZE, STATE_SIZE))
    B = np.zeros((STATE_SIZE, 2))
    A[_L1, _L1], B[_L1, 0] = -w_l, w_l
    A[_L2, _L1], A[_L2, _L2] = w_l, -w_l
    A[_Y, _YDOT] = 1.0
    A[_YDOT, _L2], A[_YDOT, _Y], A[_YDOT, _YDOT] = 1.0 / p.modal_mass_kg, -w * w, \
        -2.0 * p.damping_ratio * w
    B[_YDOT, 1] = 1.0 / p.modal_mass_kg
    A[_Z, _Y], A[_Z, _Z] = w_h, -w_h
    c = np.zeros(STATE_SIZE)
    c[_Y], c[_Z] = w * w, -w * w
    return A, B, c


def exact_discretization(A: np.ndarray, B: np.ndarray, h: float):
    """(Phi, Gamma): s[k+1] = Phi s[k] + Gamma u[k] for u held over [k h, (k+1) h)."""
    n, m = B.shape
    augmented = np.zeros((n + m, n + m))
    augmented[:n, :n], augmented[:n, n:] = A, B
    M = expm(augmented * h)
    return M[:n, :n], M[:n, n:]


@dataclasses.dataclass(frozen=True)
class FilmStepMatrices:
    """One plant step of `substeps` internal steps of `h` [s]. held (n + 5, 6) maps [s; L] to
    the n internal outputs and the end state; direct (n + 5, n) maps the n values of d."""
    held: np.ndarray
    direct: np.ndarray
    h: float
    substeps: int

    @property
    def substep_starts(self) -> np.ndarray:
        return np.arange(self.substeps) * self.h


def film_step_matrices(p: FilmParameters, time_step: float,
                       internal_rate_hz: float) -> FilmStepMatrices:
    """The FilmStepMatrices of a plant step `time_step` [s] at about `internal_rate_hz`."""
    n = max(1, int(round(time_step * internal_rate_hz)))
    h = time_step / n
    A, B, c = film_continuous_matrices(p)
    Phi, Gamma = exact_discretization(A, B, h)
    held = np.zeros((n + STATE_SIZE, STATE_SIZE + 1))
    direct = np.zeros((n + STATE_SIZE, n))
    power = np.eye(STATE_SIZE)   # Phi^j
    load = np.zeros(STATE_SIZE)  # sum_{i<j} Phi^i Gamma_L
    impulse = []                 # c Phi^i Gamma_d, i = 0..n-1 (the output's Markov parameters)
    for j in range(1, n + 1):
        load = Phi @ load + Gamma[:, 0]
        power = Phi @ power
        held[j - 1, :STATE_SIZE], held[j - 1, STATE_SIZE] = c @ power, c @ load
        impulse.append(c @ np.linalg.matrix_power(Phi, j - 1) @ Gamma[:, 1])
    held[n:, :STATE_SIZE], held[n:, STATE_SIZE] = power, load
    for j in range(n):
        direct[j, :j + 1] = impulse[j::-1]
        direct[n:, j] = np.linalg.matrix_power(Phi, n - 1 - j) @ Gamma[:, 1]
    return FilmStepMatrices(held=held, direct=direct, h=h, substeps=n)


def advance_films(m: FilmStepMatrices, states_and_loads: np.ndarray,
                  direct: np.ndarray | None = None):
    """One plant step of P pads: states_and_loads (6, P), each pad's state and its held load
    L [N]; direct (n, P) [N] or None. Returns (new states (5, P), outputs (n, P) [m/s^2])."""
    stacked = m.held @ states_and_loads
    if direct is not None:
        stacked += m.direct @ direct
    return stacked[m.substeps:], stacked[:m.substeps]


def signed_peak(samples: np.ndarray) -> np.ndarray:
    """Per column, the sample of largest magnitude, with its sign."""
    rows = np.abs(samples).argmax(axis=0)
    return samples[rows, np.arange(samples.shape[1])]


def symbolic_signed_peak(samples):
    """signed_peak of a column of expressions, symbolically: the largest sample if at least as large
    as the smallest is negative, else the smallest (opposite-sign ties differ from signed_peak)."""
    highest = lowest = samples[0]
    for sample in samples[1:]:
        highest, lowest = symbolic_max(highest, sample), symbolic_min(lowest, sample)
    return if_then_else(highest >= -lowest, highest, lowest)


def halfsine_mean_forces(step_start: float, substep_starts: np.ndarray, h: float,
                         onset: float, impulse: float, duration: float) -> np.ndarray:
    """The mean force [N] over each internal step of a half-sine pulse of `impulse` [N s]
    lasting `duration` [s] from `onset` [s]; exact, so the steps carry the whole impulse."""
    start = np.clip(step_start + substep_starts - onset, 0.0, duration)
    end = np.clip(step_start + substep_starts + h - onset, 0.0, duration)
    phase = math.pi / duration
    return 0.5 * impulse * (np.cos(phase * start) - np.cos(phase * end)) / h


def effective_mass(tip_mass: float, other_mass: float) -> float:
    """The reduced mass [kg] of the fingertip and the body it strikes (inf: anchored)."""
    return tip_mass if math.isinf(other_mass) else tip_mass * other_mass / (tip_mass + other_mass)


def restitution(closing_speed: float, dissipation: float) -> float:
    """Restitution of a Hunt-Crossley contact F = k x (1 + d x') struck at `closing_speed`
    [m/s], d [s/m]: 1 / (1 + 2/3 d v), whose small-dv limit is Hunt & Crossley's 1 - 2/3 d v."""
    return 1.0 / (1.0 + 2.0 / 3.0 * dissipation * max(closing_speed, 0.0))


def impact_pulse(closing_speed: float, tip_mass: float, other_mass: float,
                 contact_stiffness: float, dissipation: float) -> tuple[float, float]:
    """(impulse [N s], duration [s]) of the fingertip striking a body at `closing_speed`
    [m/s]: J = (1 + e) m_eff v over the half period of the contact spring,
    T_c = pi sqrt(m_eff / k_c). Zero impulse when the bodies separate."""
    m_eff = effective_mass(tip_mass, other_mass)
    duration = math.pi * math.sqrt(m_eff / contact_stiffness)
    if closing_speed <= 0.0:
        return 0.0, duration
    return (1.0 + restitution(closing_speed, dissipation)) * m_eff * closing_speed, duration


def film_sensitivity(charge_gain: float, mode_frequency_hz: float,
                     feedback_capacitance: float) -> float:
    """Mid-band sensitivity [V/(m/s^2)] to base acceleration: S = G_Q / (w^2 C_f), G_Q [C/m]
    the charge per unit modal deflection, C_f [F] the amplifier's feedback capacitance."""
    w = 2.0 * math.pi * mode_frequency_hz
    return charge_gain / (w * w * feedback_capacitance)


def first_order_highpass(samples: np.ndarray, cutoff_hz: float, dt: float) -> np.ndarray:
    """y[k] = a (y[k-1] + u[k] - u[k-1]), a = RC / (RC + dt), along axis 0, from rest: the
    rigid-body accelerometer's filter, kept to compare (analysis/compare_ra_transients.py)."""
    samples = np.asarray(samples, dtype=float)
    rc = 1.0 / (2.0 * math.pi * cutoff_hz)
    a = rc / (rc + dt)
    out = np.zeros_like(samples)
    previous = np.zeros_like(samples[0])
    y = np.zeros_like(samples[0])
    for k, u in enumerate(samples):
        y = a * (y + u - previous)
        previous = u
        out[k] = y
    return out
