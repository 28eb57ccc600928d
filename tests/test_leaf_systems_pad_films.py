"""Fixed-input tests of the pads' PVDF films (MakePadFilms): a held load and a held base
acceleration read as themselves (F / m and a, film_dynamics.py's acceleration-equivalent
units), each on its own pad; the charge amplifier's high-pass takes them away at its corner;
the sample is the peak over each sensor period, plus std times the noise input; through the
myRIO's converter the readings lie on its code grid, a ramp steps one code at a time, and
the amplifier's swing and the input range clip them.

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

from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
from tegrasp_drake.simulation.film_chain import MakePadFilms
from tegrasp_drake.simulation.pad_vibration_sensor import (FilmConfig, VibrationSensorConfig,
                                                           volts_per_mps2)
from tegrasp_drake.simulation.tactile_pads import PadGeometry

TIME_STEP = 5e-4  # s: two plant steps per 1 ms sensor period
MODAL_MASS, MODE_HZ, ZETA, LOWPASS_HZ = 0.024, 400.0, 0.05, 60.0  # kg, Hz, -, Hz
PADS = {finger: PadGeometry(None, BodyIndex(0), RigidTransform()) for finger in ("left", "right")}
LEFT_FORCE_N, LEFT_ACCELERATION, RIGHT_ACCELERATION = 2.0, -1.5, 3.0  # N, m/s^2, m/s^2
# What each film reads mid-band [m/s^2]: the load F + m a over the modal mass.
HELD = np.array([LEFT_FORCE_N / MODAL_MASS + LEFT_ACCELERATION, RIGHT_ACCELERATION])


def _films(highpass_hz: float, noise_std: float = 0.0, adc_input: str = "ideal",
           adc_noise_lsb: float = 0.0, swing_v: float = 13.5,
           left_force_n: float = LEFT_FORCE_N) -> tuple[object, object]:
    """Films with the left pad's force at entry 2 of the force input, the right one's at 0,
    entry 1 a distractor; the left pad pressed by LEFT_FORCE_N and its frame accelerating
    at LEFT_ACCELERATION along its inward normal z, the right one's frame at
    RIGHT_ACCELERATION (and 7 m/s^2 along x, which a film along z does not feel)."""
    plant = MultibodyPlant(TIME_STEP)
    plant.Finalize()
    config = VibrationSensorConfig(
        highpass_cutoff_hz=highpass_hz, noise_std_mps2=noise_std, film=FilmConfig(
            mode_mass_kg=MODAL_MASS, mode_frequency_hz=MODE_HZ, mode_damping_ratio=ZETA,
            load_lowpass_hz=LOWPASS_HZ, impact_enabled=False),
        adc_input=adc_input, adc_noise_lsb=adc_noise_lsb, amplifier_swing_v=swing_v)
    films = MakePadFilms(plant=plant, pads=PADS, force_indices=(2, 0), config=config,
                         pad_modulus_pa=PAD_MODULUS)
    context = films.CreateDefaultContext()
    films.GetInputPort("generalized_contact_forces").FixValue(context, [0.0, 100.0,
                                                                         left_force_n])
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


MSP_LSB_V = 20.0 / 4096


# The film's sensitivity [V/(m/s^2)]: the tests change none of the settings it depends on.
SENSITIVITY = volts_per_mps2(VibrationSensorConfig(film=FilmConfig(mode_frequency_hz=MODE_HZ)))


def _lsb_mps2() -> float:
    return MSP_LSB_V / SENSITIVITY


def test_through_the_msp_converter_a_held_reading_lies_on_the_code_grid():
    ideal_films, ideal_context = _films(highpass_hz=0.01)
    films, context = _films(highpass_hz=0.01, adc_input="msp")
    for system, system_context in ((ideal_films, ideal_context), (films, context)):
        Simulator(system, system_context).AdvanceTo(0.0602)
    ideal = _vibration(ideal_films, ideal_context)[[2, 5]]
    read = _vibration(films, context)[[2, 5]]
    codes = read / _lsb_mps2()
    np.testing.assert_allclose(codes, np.round(codes), atol=1e-9)
    # The nearest code to the ideal reading (83 and 3 m/s^2: 68 and 2 codes of 1.23).
    np.testing.assert_allclose(read, np.round(ideal / _lsb_mps2()) * _lsb_mps2(),
                               rtol=1e-12)
    assert not np.allclose(read, ideal, rtol=1e-4)


def test_a_slow_ramp_reads_in_steps_of_one_code():
    # The left pad's load rises by 2 mN a sample, 0.083 m/s^2 (a code, 1.23 m/s^2, every
    # 15 samples): once the ring of the held -1.5 m/s^2 base acceleration has died (tau
    # 8 ms; the first 50 samples are left out), consecutive distinct readings differ by
    # exactly one code.
    films, context = _films(highpass_hz=0.01, adc_input="msp", left_force_n=0.0)
    simulator = Simulator(films, context)
    lsb = _lsb_mps2()
    readings = []
    for k in range(1, 400):
        films.GetInputPort("generalized_contact_forces").FixValue(
            context, [0.0, 0.0, 0.002 * k])  # +2 mN a sample: 0.083 m/s^2, 1/15 code
        simulator.AdvanceTo(0.001 * k + 2e-4)
        readings.append(_vibration(films, context)[2])
    steps = np.diff(np.asarray(readings[50:]))
    moves = steps[np.abs(steps) > 1e-12]
    assert len(moves) >= 15  # 0.7 N of ramp after the first 50 samples: about 23 codes
    np.testing.assert_allclose(moves, lsb, rtol=1e-9)


@pytest.mark.parametrize("adc_input, highest_v", [("msp", 2047 * MSP_LSB_V),
                                                  ("mxp", 4095 * 5.0 / 4096 - 2.5)])
def test_a_reading_beyond_the_input_range_reads_its_end_code(adc_input, highest_v):
    # 200 N on the left pad reads 8,333 m/s^2, 33 V at S: beyond both ranges.
    films, context = _films(highpass_hz=0.01, adc_input=adc_input, left_force_n=200.0)
    Simulator(films, context).AdvanceTo(0.0602)
    left = _vibration(films, context)[2]
    assert left == pytest.approx(highest_v / SENSITIVITY, rel=1e-12)


def test_the_amplifier_swing_clips_an_ideal_readout():
    films, context = _films(highpass_hz=0.01, swing_v=0.1, left_force_n=200.0)
    Simulator(films, context).AdvanceTo(0.0602)
    reading = _vibration(films, context)[[2, 5]]
    # The left pad's 8,333 m/s^2 stops at the swing; the right's 3 m/s^2 (12 mV) passes.
    assert reading[0] == pytest.approx(0.1 / SENSITIVITY, rel=1e-12)
    assert reading[1] == pytest.approx(_held_reading(0.01, 0.05905)[1], rel=1e-3)


def test_the_converter_noise_is_drawn_with_the_amplifier_noise():
    # 0.05 m/s^2 at S (0.2 mV) and 0.5 codes (2.44 mV): one Gaussian of their
    # root-sum-square, 2.45 mV, times the unit noise input, then rounded to a code.
    films, context = _films(highpass_hz=0.01, noise_std=0.05, adc_input="msp",
                            adc_noise_lsb=0.5)
    films.GetInputPort("noise").FixValue(context, [1.0, -2.0])
    Simulator(films, context).AdvanceTo(0.0602)
    sensitivity = SENSITIVITY
    std_v = np.hypot(0.05 * sensitivity, 0.5 * MSP_LSB_V)
    volts = _held_reading(0.01, 0.05905) * sensitivity + std_v * np.array([1.0, -2.0])
    expected = np.round(volts / MSP_LSB_V) * MSP_LSB_V / sensitivity
    np.testing.assert_allclose(_vibration(films, context)[[2, 5]], expected, rtol=1e-9)
