import pathlib

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from scipy import signal

from tests.sample_stream import AddSampleStream, outputs_after_updates

from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.simulation.film_dynamics import (STATE_SIZE, advance_films,
                                                    film_step_matrices, signed_peak)
from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig, film_parameters
from tegrasp_drake.tactile.slip_band_diagram import MakeSlipVibrationBand
from tegrasp_drake.tactile.slip_vibration_band import (AddSlipVibrationBand, SlipVibrationBand,
                                                       biquad_block_map,
                                                       highpass_biquad, highpass_step_floats)

RATE_HZ = 1000.0
# The per-tick band: the Python system (the hardware station's) and the compiled Diagram (a
# simulated station's, slip_band_diagram.py); the fixed-input tests run on both.
BANDS = {"python": SlipVibrationBand, "compiled": MakeSlipVibrationBand}


def highpass_step(coefficients: np.ndarray, x: np.ndarray, z1: np.ndarray,
                  z2: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The biquad's step in numpy form (the form the system had before it ran on Python
    floats), the reference highpass_step_floats must equal bit for bit."""
    b0, b1, b2, a1, a2 = coefficients
    y = b0 * x + z1
    return y, b1 * x - a1 * y + z2, b2 * x - a2 * y


def band_output(samples: np.ndarray, *, band_hz=80.0, window_s=0.01,
                make=SlipVibrationBand) -> np.ndarray:
    """The system's slip_vibration after each row of `samples` (n x 6) is fed, one per
    sample period; `make` builds the band (a BANDS value)."""
    system = make(band_hz=band_hz, window_s=window_s, sample_rate_hz=RATE_HZ)
    simulator = Simulator(system)
    context = simulator.get_mutable_context()
    outputs = []
    for k, row in enumerate(samples):
        system.GetInputPort("pad_acceleration").FixValue(context, row)
        # The update at k / RATE_HZ is done at the start of the step that leaves that time,
        # so it reads row k when the simulator advances past it.
        simulator.AdvanceTo((k + 0.5) / RATE_HZ)
        outputs.append(system.GetOutputPort("slip_vibration").Eval(context).copy())
    return np.array(outputs)


def test_biquad_equals_scipys_butterworth_filter():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(500, 6))
    coefficients = highpass_biquad(80.0, RATE_HZ)
    z1 = z2 = np.zeros(6)
    ours = []
    for row in x:
        y, z1, z2 = highpass_step(coefficients, row, z1, z2)
        ours.append(y)
    sos = signal.butter(2, 80.0, "highpass", fs=RATE_HZ, output="sos")
    np.testing.assert_allclose(ours, signal.sosfilt(sos, x, axis=0), atol=1e-12)


@pytest.mark.parametrize("make", BANDS.values(), ids=BANDS.keys())
def test_texture_vibration_reads_its_rms_and_stays_on_its_pad(make):
    t = np.arange(400) / RATE_HZ
    samples = np.zeros((len(t), 6))
    samples[:, 2] = 3.0 * np.sin(2 * np.pi * 200.0 * t)  # left film, 200 Hz, 3 m/s^2
    out = band_output(samples, make=make)
    # 200 Hz lies 2.5 octaves above the corner: the gain is 1 / sqrt(1 + (80/200)^4) = 0.987;
    # 10 ms hold two periods.
    assert out[-1, 0] == pytest.approx(0.987 * 3.0 / np.sqrt(2), rel=0.02)
    assert out[-1, 1] == 0.0


def film_reading_of_a_squeeze(grip_n: float, ramp_s: float, duration_s: float) -> np.ndarray:
    """The simulated film's RA samples [m/s^2] (1 kHz peak-hold, no noise) while the pad
    load rises linearly to grip_n [N] over ramp_s [s] and stays: a squeeze with the
    sharpest corners a ramp can have."""
    config = VibrationSensorConfig()
    steps = film_step_matrices(film_parameters(config), 1.0 / RATE_HZ, config.internal_rate_hz)
    state = np.zeros((STATE_SIZE + 1, 1))
    samples = []
    for k in range(round(duration_s * RATE_HZ)):
        state[STATE_SIZE, 0] = grip_n * min(k / RATE_HZ / ramp_s, 1.0)
        state[:STATE_SIZE], outputs = advance_films(steps, state)
        samples.append(signed_peak(outputs)[0])
    return np.array(samples)


@pytest.mark.parametrize("make", BANDS.values(), ids=BANDS.keys())
def test_the_films_reading_of_a_squeeze_stays_below_the_slip_threshold(make):
    # The default grip, 25 N reached in about 0.45 s (docs/model.md, "Vibration (RA) model"): the
    # film reads about 180 m/s^2; the slip band reads 0.75 m/s^2 at the ramp's corners.
    film = film_reading_of_a_squeeze(25.0, 0.45, 1.5)
    assert film.max() > 150.0
    samples = np.zeros((len(film), 6))
    samples[:, 2] = film
    out = band_output(samples, make=make)
    assert out.max() < 0.8 * GraspControllerConfig().lift_load.slip_vibration_mps2


def test_a_corner_beyond_nyquist_is_refused():
    with pytest.raises(ValueError, match="Nyquist"):
        highpass_biquad(600.0, RATE_HZ)


def band_output_from_sample_blocks(blocks) -> np.ndarray:
    """The system's slip_vibration after each tick, fed each tick's block of samples (k x 6)
    on its pad_acceleration_samples input."""
    system = SlipVibrationBand(band_hz=80.0, window_s=0.01, sample_rate_hz=RATE_HZ)
    simulator = Simulator(system)
    context = simulator.get_mutable_context()
    system.GetInputPort("pad_acceleration").FixValue(context, np.full(6, np.nan))  # unread
    outputs = []
    for k, block in enumerate(blocks):
        system.GetInputPort("pad_acceleration_samples").FixValue(context, block)
        simulator.AdvanceTo((k + 0.5) / RATE_HZ)  # as in band_output
        outputs.append(system.GetOutputPort("slip_vibration").Eval(context).copy())
    return np.array(outputs)


def test_sample_blocks_give_the_band_of_the_uninterrupted_stream_whatever_the_bursts():
    # A smooth film reading (a squeeze) delivered in random bursts: after each tick the band
    # reads what it would have read after the same samples played one per tick; ticks that
    # bring nothing leave it unchanged.
    film = film_reading_of_a_squeeze(25.0, 0.45, 0.6)
    samples = np.zeros((len(film), 6))
    samples[:, 0], samples[:, 3] = film, -0.5 * film
    steady = band_output(samples)
    rng = np.random.default_rng(3)
    sizes = rng.integers(0, 6, size=len(film))  # 0 to 5 samples per tick, 2.5 on average
    ends = np.minimum(np.cumsum(sizes), len(film))
    starts = np.concatenate([[0], ends[:-1]])
    blocks = [samples[a:b] for a, b in zip(starts, ends)]
    bursty = band_output_from_sample_blocks(blocks)
    for k, end in enumerate(ends):
        if end > 0:
            np.testing.assert_array_equal(bursty[k], steady[end - 1])
        else:
            assert np.all(bursty[k] == 0.0)


def _numpy_band_reference(samples: np.ndarray, *, band_hz: float, window_s: float):
    """The band computed with numpy arrays, highpass_step and np.add.reduce (the form the
    system had before it ran on Python floats): slip_vibration after each sample."""
    coefficients = highpass_biquad(band_hz, RATE_HZ)
    window = max(1, round(window_s * RATE_HZ))
    z1 = z2 = np.zeros(6)
    squares = np.zeros((2, window))
    out = []
    for row in samples:
        y, z1, z2 = highpass_step(coefficients, row, z1, z2)
        squares[:, :-1] = squares[:, 1:]
        squares[:, -1] = np.add.reduce(y.reshape(2, 3) ** 2, axis=1)
        out.append(np.sqrt(squares.mean(axis=1)))
    return np.array(out)


def test_float_filter_step_equals_the_numpy_step_bit_for_bit():
    rng = np.random.default_rng(3)
    coefficients = highpass_biquad(80.0, RATE_HZ)
    z1 = z2 = np.zeros(6)
    delays = [0.0] * 12
    for _ in range(3000):
        x = rng.normal(size=6) * 10.0 ** rng.uniform(-3, 3, size=6)
        y, z1, z2 = highpass_step(coefficients, x, z1, z2)
        y_floats, delays = highpass_step_floats(tuple(coefficients.tolist()), x.tolist(), delays)
        assert y_floats == y.tolist()
        assert delays == z1.tolist() + z2.tolist()


def test_system_equals_the_numpy_form_bit_for_bit():
    rng = np.random.default_rng(4)
    samples = rng.normal(size=(300, 6)) * 10.0 ** rng.uniform(-2, 2, size=(300, 6))
    system = SlipVibrationBand(band_hz=80.0, window_s=0.01, sample_rate_hz=RATE_HZ)
    simulator = Simulator(system)
    context = simulator.get_mutable_context()
    ours = []
    for k, row in enumerate(samples):
        system.GetInputPort("pad_acceleration").FixValue(context, row)
        simulator.AdvanceTo((k + 0.5) / RATE_HZ)  # past the update at k / RATE_HZ
        ours.append(system.GetOutputPort("slip_vibration").Eval(context).tolist())
    reference = _numpy_band_reference(samples, band_hz=80.0, window_s=0.01)
    assert ours == reference.tolist()


def _band_per_tick_and_in_blocks(samples: np.ndarray, block: int):
    """slip_vibration of the per-tick band and of AddSlipVibrationBand's band in blocks of
    `block`, fed the same stream, just after each block boundary."""
    builder = DiagramBuilder()
    stream = AddSampleStream(builder, samples, 1.0 / RATE_HZ)
    per_tick = builder.AddSystem(SlipVibrationBand(band_hz=80.0, window_s=0.01,
                                                   sample_rate_hz=RATE_HZ))
    builder.Connect(stream, per_tick.GetInputPort("pad_acceleration"))
    in_blocks = AddSlipVibrationBand(builder, stream, band_hz=80.0, window_s=0.01,
                                     sample_rate_hz=RATE_HZ, block_samples=block)
    diagram = builder.Build()
    boundaries = np.arange(0, len(samples), block) / RATE_HZ
    return outputs_after_updates(diagram, [per_tick.GetOutputPort("slip_vibration"),
                                           in_blocks], boundaries, period_s=1.0 / RATE_HZ)


@pytest.mark.parametrize("block", [10, 40])  # as long and longer than the 10-sample window
def test_band_in_blocks_equals_the_per_tick_band_at_every_block_boundary(block):
    rng = np.random.default_rng(5)
    film = film_reading_of_a_squeeze(25.0, 0.45, 0.6)[:400]
    samples = np.zeros((len(film), 6))
    samples[:, 2], samples[:, 5] = film, -0.5 * film
    samples += rng.normal(scale=0.05, size=samples.shape)
    samples[200:260, 2] += 30.0 * np.sin(np.arange(60))  # a burst of slip
    per_tick, in_blocks = _band_per_tick_and_in_blocks(samples, block)
    assert per_tick.max() > 1.0  # the burst reads
    # lfilter sums the biquad's terms in another order than the per-tick floats: round-off
    # of the largest sample times the few sums per output.
    np.testing.assert_allclose(in_blocks, per_tick, rtol=0.0,
                               atol=1e-13 * np.abs(samples).max())


def test_band_in_blocks_is_refused_with_no_samples_or_off_the_sample_times():
    with pytest.raises(ValueError, match="block_samples 0"):
        SlipVibrationBand(band_hz=80.0, window_s=0.01, sample_rate_hz=RATE_HZ, block_samples=0)
    with pytest.raises(ValueError, match="25 samples"):  # 3 x 0.025 s != 75 x 0.001 s
        SlipVibrationBand(band_hz=80.0, window_s=0.01, sample_rate_hz=RATE_HZ,
                          block_samples=25)


def test_block_map_equals_the_biquad_run_sample_by_sample_from_any_delays():
    rng = np.random.default_rng(6)
    coefficients = highpass_biquad(80.0, RATE_HZ)
    x = rng.normal(size=(10, 6)) * 20.0
    z1, z2 = rng.normal(size=6), rng.normal(size=6)
    stacked = biquad_block_map(coefficients, 10) @ np.vstack([x, z1, z2])
    outputs = []
    for row in x:
        y, z1, z2 = highpass_step(coefficients, row, z1, z2)
        outputs.append(y)
    # Sums of about 12 terms of up to |x| 60: round-off.
    np.testing.assert_allclose(stacked[:10], outputs, rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(stacked[10:], [z1, z2], rtol=0.0, atol=1e-12)


def recorded_film_samples() -> np.ndarray:
    """The films' samples of a recorded trial through a touch (tests/data/film_recording.npz,
    see simulation/test_film_chain.py) as pad_acceleration rows (n x 6), z axes."""
    recording = np.load(pathlib.Path(__file__).parents[1] / "data" / "film_recording.npz")
    touch = recording["touch_samples"]
    samples = np.zeros((len(touch), 6))
    samples[:, 2], samples[:, 5] = touch[:, 0], touch[:, 1]
    return samples


def test_compiled_band_equals_the_python_band_on_a_recorded_touch_and_on_noise():
    # The same equations; the compiled system sums the biquad's terms and the window in
    # another order: round-off of the largest sample.
    rng = np.random.default_rng(7)
    for samples in (recorded_film_samples(),
                    rng.normal(size=(300, 6)) * 10.0 ** rng.uniform(-2, 2, size=(300, 6))):
        python = band_output(samples, make=SlipVibrationBand)
        compiled = band_output(samples, make=MakeSlipVibrationBand)
        assert python.max() > 1.0
        np.testing.assert_allclose(compiled, python, rtol=1e-12,
                                   atol=1e-14 * np.abs(samples).max())


def test_add_slip_vibration_band_builds_the_compiled_band_per_tick_only():
    def built(**kwargs):
        builder = DiagramBuilder()
        stream = AddSampleStream(builder, np.zeros((3, 6)), 1.0 / RATE_HZ)
        AddSlipVibrationBand(builder, stream, band_hz=80.0, window_s=0.01,
                             sample_rate_hz=RATE_HZ, **kwargs)
        return builder.GetSubsystemByName("slip_vibration_band")
    assert not isinstance(built(), SlipVibrationBand)  # the compiled Diagram
    assert isinstance(built(block_samples=10), SlipVibrationBand)
