"""The films' compiled chain (film_chain.py) against the per-step Python implementation it
replaced, and its pieces against their pure-function forms.

tests/data/film_recording.npz was recorded from that Python implementation (one LeafSystem
that advanced the films with advance_films and read them out with reading_mps2 in its
update) in the default scenario's memorized trial, seed 600: per plant step of two
segments, the films' loads L [N], direct loads d [N] (both pads' n internal instants), the
drives' vibration [m/s^2], the unit noise and the samples it output [m/s^2], and the films'
states at each segment's start. `touch` (3.55-3.85 s) holds the left pad's impact (a 993
m/s^2 sample) and the squeeze; `slip` (9.74-9.82 s) the slip texture's direct loads. The
channels' inputs and outputs through the touch were recorded from its Eq. 1-2 system.
"""

import pathlib

import numpy as np
import pytest
from pydrake.common import RandomDistribution, RandomGenerator
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import PassThrough, RandomSource

from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
from tegrasp_drake.simulation.film_chain import (AddFilmSamples, MakePadFilms,
                                                 film_readout_system, film_step_matrix)
from tegrasp_drake.simulation.film_dynamics import (STATE_SIZE, advance_films,
                                                    film_step_matrices, signed_peak)
from tegrasp_drake.simulation.film_loads import (DIRECT_START, HELD_SIZE, MEMORY,
                                                 film_loads_size)
from tegrasp_drake.simulation.film_readout import adc_input, reading_mps2
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           film_parameters, noise_draw_std_v,
                                                           volts_per_mps2)
from tegrasp_drake.simulation.tactile_pads import PadGeometry
from tegrasp_drake.tactile.mechanoreceptor_channels import MakeMechanoreceptorChannels

TIME_STEP = 1e-3
RECORDING = np.load(pathlib.Path(__file__).parents[1] / "data" / "film_recording.npz")
SUBSTEPS = 20  # the default 20 kHz internal rate over a 1 ms step


def _compiled_samples(segment: str) -> np.ndarray:
    """The compiled part of the films (AddFilmSamples) fed the segment's recorded loads,
    drive and noise from its recorded film states: its samples after each plant step."""
    config = VibrationSensorConfig()
    builder = DiagramBuilder()
    size = film_loads_size(SUBSTEPS)
    loads = builder.AddSystem(PassThrough(size))  # in FilmLoads' place
    samples, _, inputs = AddFilmSamples(builder, film_loads=loads.get_output_port(),
                                           config=config, time_step=TIME_STEP,
                                           with_drive_vibration=True, with_noise=True)
    film_loads = builder.ExportInput(loads.get_input_port(), "film_loads")
    drive = builder.ExportInput(inputs["drive_vibration"], "drive")
    noise = builder.ExportInput(inputs["noise"], "noise")
    outputs = [builder.ExportOutput(port, f"sample_{k}") for k, port in enumerate(samples)]
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    t = RECORDING[f"{segment}_t"]
    context.SetTime(t[0] - 0.5 * TIME_STEP)
    hold = diagram.GetSubsystemByName("film_hold")
    state = np.zeros(HELD_SIZE)
    state[MEMORY.stop - MEMORY.start:] = RECORDING[f"{segment}_film_state"]
    hold.GetMyMutableContextFromRoot(context).SetDiscreteState(state)
    simulator = Simulator(diagram, context)
    read = []
    for k, time in enumerate(t):
        value = np.zeros(size)
        value[:2] = RECORDING[f"{segment}_loads"][k]
        value[DIRECT_START:] = RECORDING[f"{segment}_direct"][k]
        diagram.get_input_port(film_loads).FixValue(context, value)
        diagram.get_input_port(drive).FixValue(context, RECORDING[f"{segment}_drive"][k])
        diagram.get_input_port(noise).FixValue(context, RECORDING[f"{segment}_noise"][k])
        simulator.AdvanceTo(time + 0.5 * TIME_STEP)  # past the update at `time`
        read.append([diagram.get_output_port(p).Eval(context)[2] for p in outputs])
    return np.array(read)


@pytest.mark.parametrize("segment", ["touch", "slip"])
def test_compiled_films_read_a_recorded_trial_as_the_python_films_did(segment):
    # The films' state is advanced by a matrix product in another order than numpy's, so
    # it differs by round-off; the samples, through the myRIO's converter, are whole codes
    # and come out the same.
    compiled = _compiled_samples(segment)
    recorded = RECORDING[f"{segment}_samples"]
    assert np.abs(recorded).max() > 900.0  # the touch's impact, the table's in `slip`
    np.testing.assert_allclose(compiled, recorded, rtol=0.0, atol=1e-9)


def test_film_step_matrix_is_advance_films():
    config = VibrationSensorConfig()
    matrices = film_step_matrices(film_parameters(config), TIME_STEP, config.internal_rate_hz)
    M = film_step_matrix(matrices, 4)
    rng = np.random.default_rng(8)
    for _ in range(50):
        states_and_loads = rng.normal(size=(STATE_SIZE + 1, 2)) * 1e-3
        states_and_loads[STATE_SIZE] *= 1e3  # loads of newtons, states of millimetres
        direct = rng.normal(size=(SUBSTEPS, 2))
        memory = rng.normal(size=MEMORY.stop - MEMORY.start)
        passed = rng.normal(size=4)
        loads = np.zeros(film_loads_size(SUBSTEPS))
        loads[:2] = states_and_loads[STATE_SIZE]
        loads[MEMORY] = memory
        loads[DIRECT_START:] = direct.T.ravel()
        held = np.concatenate([rng.normal(size=MEMORY.stop - MEMORY.start),
                               states_and_loads[:STATE_SIZE].T.ravel()])
        out = M @ np.concatenate([held, loads, passed])
        states, outputs = advance_films(matrices, states_and_loads, direct)
        scale = np.abs(outputs).max()
        np.testing.assert_array_equal(out[:MEMORY.stop - MEMORY.start], memory)
        np.testing.assert_allclose(out[MEMORY.stop - MEMORY.start:HELD_SIZE],
                                   states.T.ravel(), rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(out[HELD_SIZE:HELD_SIZE + 2 * SUBSTEPS],
                                   outputs.T.ravel(), rtol=0.0, atol=1e-13 * scale)
        np.testing.assert_array_equal(out[HELD_SIZE + 2 * SUBSTEPS:], passed)


@pytest.mark.parametrize("adc", ["msp", "mxp", "ideal"])
def test_the_compiled_readout_is_the_peak_and_reading_mps2_bit_for_bit(adc):
    config = VibrationSensorConfig(adc_input=adc)
    std = noise_draw_std_v(config)
    system = film_readout_system(config=config, substeps=SUBSTEPS, time_step=TIME_STEP, steps=1,
                                 with_drive=True, noise_std_v=std)
    context = system.CreateDefaultContext()
    context.SetTime(0.005)
    readout = (volts_per_mps2(config), config.amplifier_swing_v, adc_input(adc))
    rng = np.random.default_rng(9)
    for _ in range(500):
        outputs = rng.normal(size=(SUBSTEPS, 2)) * 10.0 ** rng.uniform(-2, 3.7)
        drive, noise = rng.normal(size=2) * 0.3, rng.normal(size=2)
        system.get_input_port().FixValue(context, np.concatenate(
            [outputs[:, 0], outputs[:, 1], drive, noise]))
        update = system.EvalUniquePeriodicDiscreteUpdate(context).get_vector().CopyToVector()
        peaks = signed_peak(outputs)
        assert update.tolist() == [reading_mps2(peaks[k] + drive[k], std * noise[k], *readout)
                                   for k in range(2)]


def test_the_first_plant_step_takes_no_sample():
    config = VibrationSensorConfig()
    system = film_readout_system(config=config, substeps=SUBSTEPS, time_step=TIME_STEP, steps=1,
                                 with_drive=False, noise_std_v=noise_draw_std_v(config))
    context = system.CreateDefaultContext()
    system.get_input_port().FixValue(context, np.full(2 * SUBSTEPS + 2, 50.0))
    assert system.EvalUniquePeriodicDiscreteUpdate(context).get_vector().CopyToVector()\
        .tolist() == [0.0, 0.0]
    context.SetTime(TIME_STEP)
    assert np.all(system.EvalUniquePeriodicDiscreteUpdate(context).get_vector()
                  .CopyToVector() > 45.0)


def test_the_films_draw_nothing_from_the_random_generator():
    # A random source after the films gets the seed it gets without them: the films do not
    # shift the station's noise streams.
    def first_noise(with_films: bool) -> float:
        builder = DiagramBuilder()
        if with_films:
            plant = MultibodyPlant(TIME_STEP)
            plant.Finalize()
            pads = {f: PadGeometry(None, BodyIndex(0), RigidTransform()) for f in ("left", "right")}
            builder.AddSystem(MakePadFilms(plant=plant, pads=pads, force_indices=(0, 1),
                                           config=VibrationSensorConfig(),
                                           pad_modulus_pa=PAD_MODULUS))
        noise = builder.AddSystem(RandomSource(RandomDistribution.kGaussian, 1, TIME_STEP))
        diagram = builder.Build()
        context = diagram.CreateDefaultContext()
        diagram.SetRandomContext(context, RandomGenerator(600))
        return noise.get_output_port().Eval(noise.GetMyContextFromRoot(context))[0]
    assert first_noise(True) == first_noise(False)


def test_compiled_channels_give_the_recorded_channels_bit_for_bit():
    channels = MakeMechanoreceptorChannels()
    context = channels.CreateDefaultContext()
    names = ["left_taxel_forces", "right_taxel_forces", "left_pad_acceleration",
             "right_pad_acceleration"]
    sizes = [12, 12, 3, 3]
    inputs, outputs = RECORDING["touch_channels_in"], RECORDING["touch_channels_out"]
    assert np.abs(outputs[:, 2:]).max() > 900.0  # the impact reads on RA
    for row, expected in zip(inputs, outputs):
        for name, part in zip(names, np.split(row, np.cumsum(sizes)[:-1])):
            channels.GetInputPort(name).FixValue(context, part)
        assert channels.GetOutputPort("channels").Eval(context).tolist() == expected.tolist()
