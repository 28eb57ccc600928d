"""Fixed-input tests of PadFilms, the pads' PVDF films: a held load and a held base
acceleration read as themselves (F / m and a, film_dynamics.py's acceleration-equivalent
units), each on its own pad; the charge amplifier's high-pass takes them away at its corner;
the sample is the peak over each sensor period, plus std times the noise input.

The films need only a discrete plant's time step and bodies here: the impact pulse (the one
path that reads the contact inputs) is off, and film_dynamics' own tests check the pulse.
"""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ContactResults, MultibodyPlant
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.analysis import Simulator

from tegrasp_drake.simulation.pad_vibration_sensor import PadFilms, VibrationSensorConfig
from tegrasp_drake.simulation.tactile_pads import PadGeometry

TIME_STEP = 5e-4  # s: two plant steps per 1 ms sensor period
MODAL_MASS, MODE_HZ, ZETA, LOWPASS_HZ = 0.024, 400.0, 0.05, 60.0  # kg, Hz, -, Hz
PADS = {finger: PadGeometry(None, BodyIndex(0), RigidTransform()) for finger in ("left", "right")}
LEFT_FORCE_N, LEFT_ACCELERATION, RIGHT_ACCELERATION = 2.0, -1.5, 3.0  # N, m/s^2, m/s^2
# What each film reads mid-band [m/s^2]: the load F + m a over the modal mass.
HELD = np.array([LEFT_FORCE_N / MODAL_MASS + LEFT_ACCELERATION, RIGHT_ACCELERATION])


def _films(highpass_hz: float, noise_std: float = 0.0) -> tuple[PadFilms, object]:
    """Films with the left pad's force at entry 2 of the force input, the right one's at 0,
    entry 1 a distractor; the left pad pressed by LEFT_FORCE_N and its frame accelerating
    at LEFT_ACCELERATION along its inward normal z, the right one's frame at
    RIGHT_ACCELERATION (and 7 m/s^2 along x, which a film along z does not feel)."""
    plant = MultibodyPlant(TIME_STEP)
    plant.Finalize()
    config = VibrationSensorConfig(
        highpass_cutoff_hz=highpass_hz, noise_std_mps2=noise_std, mode_mass_kg=MODAL_MASS,
        mode_frequency_hz=MODE_HZ, mode_damping_ratio=ZETA, load_lowpass_hz=LOWPASS_HZ,
        impact_enabled=False)
    films = PadFilms(plant=plant, pads=PADS, force_indices=(2, 0), config=config)
    context = films.CreateDefaultContext()
    films.GetInputPort("generalized_contact_forces").FixValue(context, [0.0, 100.0,
                                                                         LEFT_FORCE_N])
    films.GetInputPort("left_pad_frame_acceleration").FixValue(
        context, [0.0, 0.0, LEFT_ACCELERATION])
    films.GetInputPort("right_pad_frame_acceleration").FixValue(
        context, [7.0, 0.0, RIGHT_ACCELERATION])
    films.GetInputPort("contact_results").FixValue(context, ContactResults())
    films.GetInputPort("body_poses").FixValue(context, [RigidTransform()])
    return films, context


def _held_reading(highpass_hz: float, t_s: float) -> np.ndarray:
    """[left, right] readings t_s after the load and acceleration were applied, once the
    fast poles have died: a step input u through the film's chain, (1/m) w_l^2/(s + w_l)^2
    w^2/(s^2 + 2 zeta w s + w^2) s/(s + w_h) u/s in acceleration-equivalent units (u = F
    or m a), leaves the residue at -w_h: (u/m) w_l^2/(w_l - w_h)^2 w^2/(w^2 - 2 zeta w w_h
    + w_h^2) exp(-w_h t)."""
    w, w_l, w_h = (2 * math.pi * f for f in (MODE_HZ, LOWPASS_HZ, highpass_hz))
    residue = w_l ** 2 / (w_l - w_h) ** 2 * w ** 2 / (w ** 2 - 2 * ZETA * w * w_h + w_h ** 2)
    return HELD * residue * math.exp(-w_h * t_s)


def _vibration(films, context) -> np.ndarray:
    return np.concatenate([films.GetOutputPort(f"{f}_pad_vibration").Eval(context)
                           for f in ("left", "right")])


def test_held_load_and_base_acceleration_read_as_themselves_on_their_own_pads():
    # With a 0.01 Hz high-pass, 60 ms on, the reading is within 0.4 % of F / m and a. The
    # sample at 60 ms is the peak over (59, 60] ms: the first 20 kHz internal sample, at
    # 59.05 ms. What is left of the fast terms: the mode's ring, excited only by the
    # smooth load, decayed by exp(-zeta w 0.059) = 6e-4.
    films, context = _films(highpass_hz=0.01)
    Simulator(films, context).AdvanceTo(0.0602)
    reading = _vibration(films, context)
    np.testing.assert_array_equal(reading[[0, 1, 3, 4]], np.zeros(4))  # the film's axis is z
    np.testing.assert_allclose(reading[[2, 5]], _held_reading(0.01, 0.05905), rtol=1e-3)
    np.testing.assert_allclose(reading[[2, 5]], HELD, rtol=5e-3)


def test_charge_amplifier_high_pass_takes_a_held_load_away_at_its_corner():
    # The samples at 100 and 300 ms, each the peak of its period (99.05 and 299.05 ms):
    # only the slow residue is left (the ring: exp(-zeta w 0.099) = 4e-6).
    films, context = _films(highpass_hz=2.0)
    simulator = Simulator(films, context)
    simulator.AdvanceTo(0.1002)
    early = _vibration(films, context)[[2, 5]]
    simulator.AdvanceTo(0.3002)
    late = _vibration(films, context)[[2, 5]]
    np.testing.assert_allclose(early, _held_reading(2.0, 0.09905), rtol=1e-4)
    np.testing.assert_allclose(late, _held_reading(2.0, 0.29905), rtol=1e-4)


def test_sample_is_held_over_the_sensor_period_and_carries_std_times_the_noise():
    films, context = _films(highpass_hz=0.01, noise_std=0.05)
    films.GetInputPort("noise").FixValue(context, [1.0, -2.0])
    simulator = Simulator(films, context)
    simulator.AdvanceTo(0.0602)  # the last sample was taken at 60 ms
    sample = _vibration(films, context)
    np.testing.assert_allclose(sample[[2, 5]],
                               _held_reading(0.01, 0.05905) + [0.05 * 1.0, 0.05 * -2.0],
                               rtol=1e-3)
    simulator.AdvanceTo(0.0607)  # one more plant step, at 60.5 ms: no new sample
    np.testing.assert_array_equal(_vibration(films, context), sample)
