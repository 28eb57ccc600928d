"""The film's numerical core against closed forms."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from tegrasp_drake.hardware.myrio.tactile_calibration import PadCalibration
from tegrasp_drake.simulation.film_dynamics import (FilmParameters, advance_films,
                                                    film_sensitivity, film_step_matrices,
                                                    halfsine_mean_forces, impact_pulse,
                                                    restitution, signed_peak)
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           volts_per_mps2)

FILM = FilmParameters(mode_frequency_hz=400.0, damping_ratio=0.05, modal_mass_kg=0.024,
                      load_lowpass_hz=60.0, highpass_hz=2.0)
NO_HIGHPASS = FilmParameters(400.0, 0.05, 0.024, 60.0, 1e-12)
W = 2 * math.pi * 400.0
WD = W * math.sqrt(1 - 0.05 ** 2)


def _run(params, time_step, steps, load=0.0, direct_first=None, substeps_hz=20000.0):
    """Outputs (internal samples, concatenated) and states after `steps` plant steps."""
    m = film_step_matrices(params, time_step, substeps_hz)
    x = np.zeros((6, 1))
    outputs = []
    for k in range(steps):
        x[5, 0] = load
        direct = direct_first if k == 0 else None
        states, out = advance_films(m, x, direct)
        x[:5] = states
        outputs.append(out[:, 0].copy())
    return np.concatenate(outputs), x[:5, 0], m


def _mode_step_response(t):
    """Deflection of the mode under a unit force applied at t = 0, times m w^2 (so 1 at DC)."""
    t = np.maximum(t, 0.0)
    decay = np.exp(-0.05 * W * t)
    return 1 - decay * (np.cos(WD * t) + 0.05 * W / WD * np.sin(WD * t))


def test_a_force_pulse_rings_the_mode_exactly_as_the_closed_form():
    force, h = 2.0, 1.0 / 20000.0
    direct = np.zeros((20, 1))
    direct[0, 0] = force  # held over the first internal step
    outputs, _, m = _run(NO_HIGHPASS, 1e-3, 10, direct_first=direct)
    t = (np.arange(len(outputs)) + 1) * m.h
    # a = w^2 y, and y is the force over m w^2 times the difference of two step responses.
    expected = force / FILM.modal_mass_kg * (_mode_step_response(t) - _mode_step_response(t - h))
    np.testing.assert_allclose(outputs, expected, atol=1e-9 * np.abs(expected).max())


def test_the_ring_decays_at_zeta_omega():
    direct = np.zeros((20, 1))
    direct[0, 0] = 1.0
    outputs, _, m = _run(FILM, 1e-3, 40, direct_first=direct)
    period = int(round(2 * math.pi / WD / m.h))
    envelope = [np.abs(outputs[k * period:(k + 1) * period]).max() for k in range(12)]
    rate = -np.polyfit(np.arange(12) * period * m.h, np.log(envelope), 1)[0]
    assert rate == pytest.approx(0.05 * W, rel=0.02)
    assert envelope[2] > 0.4 * envelope[0]  # 5 ms later: exp(-zeta w 5 ms) = 0.53


def test_the_load_lowpass_follows_the_critically_damped_step_response():
    _, states, _ = _run(FILM, 1e-3, 5, load=1.0)
    w_l, t = 2 * math.pi * 60.0, 5e-3
    assert states[1] == pytest.approx(1 - (1 + w_l * t) * math.exp(-w_l * t), rel=1e-9)


def test_a_held_load_reads_load_over_modal_mass_then_decays_with_the_highpass():
    outputs, _, m = _run(FILM, 1e-3, 400, load=0.5)
    w_h, delay = 2 * math.pi * 2.0, 2 / (2 * math.pi * 60.0)  # the low-pass's group delay
    for t in (0.05, 0.1, 0.4):
        expected = 0.5 / FILM.modal_mass_kg * math.exp(-w_h * (t - delay))
        assert outputs[int(round(t * 1000)) * m.substeps - 1] == pytest.approx(expected,
                                                                               rel=0.01)


def test_held_inputs_give_the_same_state_whatever_the_internal_or_plant_step():
    _, coarse, _ = _run(FILM, 1e-3, 4, load=1.0, substeps_hz=1000.0)
    _, fine, _ = _run(FILM, 1e-3, 4, load=1.0, substeps_hz=20000.0)
    _, halves, _ = _run(FILM, 5e-4, 8, load=1.0)
    np.testing.assert_allclose(coarse, fine, rtol=1e-10, atol=1e-18)
    np.testing.assert_allclose(halves, fine, rtol=1e-10, atol=1e-18)


def test_the_pulse_grid_carries_the_whole_impulse_wherever_it_starts():
    m = film_step_matrices(FILM, 1e-3, 20000.0)
    for onset in (0.0, 1.3e-5, 7.77e-4):
        total = sum(halfsine_mean_forces(step * 1e-3, m.substep_starts, m.h, onset, 2e-3,
                                         4.9e-4).sum() * m.h for step in range(3))
        assert total == pytest.approx(2e-3, rel=1e-12)


def test_signed_peak_keeps_the_sign_of_the_largest_sample():
    samples = np.array([[1.0, -0.5], [-3.0, 0.4], [2.0, 0.1]])
    np.testing.assert_array_equal(signed_peak(samples), [-3.0, -0.5])


def _hunt_crossley_restitution(dissipation, speed):
    mass, stiffness = 0.02, 8.4e5

    def contact(_, y):
        return [y[1], -stiffness * y[0] * (1 + dissipation * y[1]) / mass]

    def separated(_, y):
        return y[0]
    separated.terminal, separated.direction = True, -1
    solution = solve_ivp(contact, [0, 0.01], [0, speed], events=separated, max_step=1e-6,
                         rtol=1e-10, atol=1e-14)
    return -solution.y_events[0][0][1] / speed


@pytest.mark.parametrize("speed", [0.0125, 0.025, 0.05, 0.1, 0.2])
def test_restitution_matches_an_integrated_hunt_crossley_contact(speed):
    assert restitution(speed, 5.0) == pytest.approx(_hunt_crossley_restitution(5.0, speed),
                                                    rel=0.012)


def test_impact_impulse_grows_with_closing_speed_and_vanishes_when_separating():
    slow, duration = impact_pulse(0.025, 0.024, 0.15, 8.4e5, 5.0)
    fast, _ = impact_pulse(0.05, 0.024, 0.15, 8.4e5, 5.0)
    m_eff = 0.024 * 0.15 / 0.174
    assert slow == pytest.approx((1 + restitution(0.025, 5.0)) * m_eff * 0.025)
    assert duration == pytest.approx(math.pi * math.sqrt(m_eff / 8.4e5))
    assert 1.8 < fast / slow < 2.0
    assert impact_pulse(-0.01, 0.024, 0.15, 8.4e5, 5.0)[0] == 0.0
    anchored, _ = impact_pulse(0.025, 0.024, math.inf, 8.4e5, 5.0)
    assert anchored > slow


def test_film_sensitivity_matches_the_hardware_piezo_calibration():
    config = VibrationSensorConfig()
    sensitivity = film_sensitivity(2.5e-5, 400.0, 1e-9)
    assert sensitivity == pytest.approx(2.5e-5 / ((2 * math.pi * 400) ** 2 * 1e-9))
    assert volts_per_mps2(config) == pytest.approx(sensitivity)
    assert PadCalibration().piezo_gain == pytest.approx(1.0 / sensitivity, rel=0.01)
