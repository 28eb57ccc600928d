"""The pads' PVDF films as one Diagram, compiled Drake systems but for FilmLoads:

    film_signals -> film_loads (FilmLoads, Python) -> film_dynamics (MatrixGain: both films
      over the step, exactly) -> film_step -> film_hold (ZeroOrderHold: the loads' memory and
      the films' states) | film_readout (SymbolicVectorSystem) -> film_samples ([0, 0, a] per pad)

The states live in a ZeroOrderHold, not a LinearSystem, whose state would draw from the
random generator and shift every noise stream seeded after it."""

import numpy as np
from pydrake.common import RandomDistribution
from pydrake.symbolic import Variable, floor, if_then_else, logical_and
from pydrake.symbolic import abs as symbolic_abs
from pydrake.symbolic import max as symbolic_max
from pydrake.symbolic import min as symbolic_min
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import (Demultiplexer, MatrixGain, Multiplexer, RandomSource,
                                        SymbolicVectorSystem, ZeroOrderHold)

from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.simulation.drive_vibration import AddDriveVibration
from tegrasp_drake.simulation.film_dynamics import (STATE_SIZE, FilmStepMatrices,
                                                    film_step_matrices, symbolic_signed_peak)
from tegrasp_drake.simulation.film_loads import (DIRECT_START, HELD_SIZE, LOADS, MEMORY,
                                                 FilmLoads, film_loads_size)
from tegrasp_drake.simulation.film_readout import Arithmetic, adc_input, reading_mps2
from tegrasp_drake.simulation.pad_accelerometers import AddPadFrameAccelerometer
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           film_parameters, noise_draw_std_v,
                                                           volts_per_mps2)

# reading_mps2 on expressions.
SYMBOLIC = Arithmetic(min=symbolic_min, max=symbolic_max, floor=floor)
SAMPLE_AXIS = 2  # the film's axis, the pad frame's z, in each 3-vector sample


def steps_per_sample(time_step: float, sample_rate_hz: float) -> int:
    """Plant steps per RA sample (at least 1); ValueError unless a whole number."""
    steps = 1.0 / (sample_rate_hz * time_step)
    if steps > 1.0 and abs(steps - round(steps)) > 1e-6:
        raise ValueError(f"the RA period 1/{sample_rate_hz:g} s must be a whole "
                         f"number of plant steps ({time_step:g} s)")
    return max(1, int(round(steps)))


def film_step_matrix(matrices: FilmStepMatrices, passed_through: int) -> np.ndarray:
    """Both films over one plant step as one matrix M: [m; s'; y; p] = M [h; film_loads; p],
    h the chain's hold (FilmLoads' memory one step ago, then both films' five states), m the
    memory now and s' the states at the step's end, y each film's n internal outputs [m/s^2]
    (advance_films in matrix form), p `passed_through` entries unchanged."""
    n = matrices.substeps
    held, direct = matrices.held, matrices.direct
    memory = MEMORY.stop - MEMORY.start
    columns = HELD_SIZE + film_loads_size(n) + passed_through
    M = np.zeros((HELD_SIZE + 2 * n + passed_through, columns))
    M[:memory, HELD_SIZE + MEMORY.start:HELD_SIZE + MEMORY.stop] = np.eye(memory)
    for k in range(len(FINGER_NAMES)):
        state = slice(memory + k * STATE_SIZE, memory + (k + 1) * STATE_SIZE)
        outputs = slice(HELD_SIZE + k * n, HELD_SIZE + (k + 1) * n)
        load = HELD_SIZE + LOADS.start + k
        pad_direct = slice(HELD_SIZE + DIRECT_START + k * n,
                           HELD_SIZE + DIRECT_START + (k + 1) * n)
        for rows, part in ((state, slice(n, None)), (outputs, slice(0, n))):
            M[rows, state] = held[part, :STATE_SIZE]
            M[rows, load] = held[part, STATE_SIZE]
            M[rows, pad_direct] = direct[part]
    M[HELD_SIZE + 2 * n:, columns - passed_through:] = np.eye(passed_through)
    return M


def film_readout_system(*, config, substeps: int, time_step: float, steps: int,
                        with_drive: bool, noise_std_v: float) -> SymbolicVectorSystem:
    """Both films' readout as a SymbolicVectorSystem of period time_step: inputs each film's
    n internal outputs, the drive vibration and unit noise (when used); every `steps` plant
    steps a pad's sample is reading_mps2 of its peak plus drive and noise. Output: [0, 0, left,
    0, 0, right] [m/s^2]."""
    readout = (volts_per_mps2(config), config.amplifier_swing_v, adc_input(config.adc_input))
    t = Variable("t")
    outputs = [[Variable(f"{finger}_output_{j}") for j in range(substeps)]
               for finger in FINGER_NAMES]
    drive = [Variable(f"{finger}_drive") for finger in FINGER_NAMES] if with_drive else None
    noise = [Variable(f"{finger}_noise") for finger in FINGER_NAMES] if noise_std_v > 0 else None
    samples = [Variable(f"{finger}_sample") for finger in FINGER_NAMES]
    inputs = [v for pad in outputs for v in pad] + (drive or []) + (noise or [])
    step = floor(t / time_step + 0.5)
    started = step >= 1.0

    def sample(k, peak):
        value = peak if drive is None else peak + drive[k]
        noise_v = 0.0 if noise is None else noise_std_v * noise[k]
        return reading_mps2(value, noise_v, *readout, arithmetic=SYMBOLIC)

    peaks = [symbolic_signed_peak(pad) for pad in outputs]
    if steps == 1:
        state = samples
        updates = [if_then_else(started, sample(k, peaks[k]), samples[k]) for k in range(2)]
    else:  # the peak so far of the RA period, kept between its plant steps
        running = [Variable(f"{finger}_peak") for finger in FINGER_NAMES]
        state = running + samples
        taken = step - steps * floor(step / steps) == 0.0
        held = [if_then_else(symbolic_abs(peaks[k]) > symbolic_abs(running[k]), peaks[k],
                             running[k]) for k in range(2)]
        updates = ([if_then_else(started, if_then_else(taken, 0.0, held[k]), running[k])
                    for k in range(2)]
                   + [if_then_else(logical_and(started, taken), sample(k, held[k]), samples[k])
                      for k in range(2)])
    output = []
    for k in range(2):
        axes = [0.0, 0.0, 0.0]
        axes[SAMPLE_AXIS] = samples[k]
        output += axes
    return SymbolicVectorSystem(time=t, state=state, input=inputs, dynamics=updates,
                                output=output, time_period=time_step)


def AddFilmSamples(builder, *, film_loads, config: VibrationSensorConfig, time_step: float,
                   with_drive_vibration: bool, with_noise: bool):
    """Adds the compiled part of the films to `builder`, fed by `film_loads` (FilmLoads'
    output), for plant steps of time_step [s]. Returns ((left, right) sample ports, [0, 0, a]
    [m/s^2]; the hold's output, FilmLoads' `held`; {name: input port} still to connect:
    `drive_vibration` (2, m/s^2) and `noise` (2 unit Gaussians) when asked for)."""
    matrices = film_step_matrices(film_parameters(config), time_step, config.internal_rate_hz)
    extra = [name for name, wanted in (("drive_vibration", with_drive_vibration),
                                       ("noise", with_noise)) if wanted]
    gather = builder.AddNamedSystem("film_inputs", Multiplexer(
        [HELD_SIZE, film_loads.size()] + [2] * len(extra)))
    step = builder.AddNamedSystem("film_dynamics", MatrixGain(
        film_step_matrix(matrices, 2 * len(extra))))
    split = builder.AddNamedSystem("film_step", Demultiplexer(
        [HELD_SIZE, 2 * matrices.substeps + 2 * len(extra)]))
    hold = builder.AddNamedSystem("film_hold", ZeroOrderHold(time_step, HELD_SIZE))
    builder.Connect(hold.get_output_port(), gather.get_input_port(0))
    builder.Connect(film_loads, gather.get_input_port(1))
    builder.Connect(gather.get_output_port(), step.get_input_port())
    builder.Connect(step.get_output_port(), split.get_input_port())
    builder.Connect(split.get_output_port(0), hold.get_input_port())
    inputs = {name: gather.get_input_port(2 + k) for k, name in enumerate(extra)}
    readout = builder.AddNamedSystem("film_readout", film_readout_system(
        config=config, substeps=matrices.substeps, time_step=time_step,
        steps=steps_per_sample(time_step, config.sample_rate_hz),
        with_drive=with_drive_vibration,
        noise_std_v=noise_draw_std_v(config) if with_noise else 0.0))
    builder.Connect(split.get_output_port(1), readout.get_input_port())
    samples = builder.AddNamedSystem("film_samples", Demultiplexer([3] * len(FINGER_NAMES)))
    builder.Connect(readout.get_output_port(), samples.get_input_port())
    return (tuple(samples.get_output_port(k) for k in range(len(FINGER_NAMES))),
            hold.get_output_port(), inputs)


def MakePadFilms(*, plant, pads: dict, force_indices, config, pad_modulus_pa: float,
                 with_texture: bool = False, pad_statics=None,
                 with_drive_vibration: bool = False):
    """Both pads' films as a Diagram for the discrete `plant`.

    .. pydrake_system::

        name: PadFilms
        input_ports:
        - generalized_contact_forces
        - gripper_state (optional)
        - left_pad_frame_acceleration
        - right_pad_frame_acceleration
        - texture_state (optional)
        - drive_vibration (optional)
        - noise (optional)
        - contact_results
        - body_poses
        - body_spatial_velocities
        - body_spatial_accelerations
        output_ports:
        - left_pad_vibration
        - right_pad_vibration

    Ports: FilmLoads' inputs (film_loads.py); drive_vibration (2, m/s^2, with
    `with_drive_vibration`) and unit Gaussian noise (2, when noise_draw_std_v > 0) added to
    each sample; the outputs are the read-out sample on z (3, m/s^2-equivalent, pad frame),
    every sensor period. config: the VibrationSensorConfig; force_indices, pad_modulus_pa
    [Pa], pad_statics: as FilmLoads takes them.
    """
    time_step = plant.time_step()
    if not time_step > 0.0:
        raise ValueError("PadFilms needs a discrete-time plant")
    steps_per_sample(time_step, config.sample_rate_hz)  # checks the RA period
    matrices = film_step_matrices(film_parameters(config), time_step, config.internal_rate_hz)
    builder = DiagramBuilder()
    loads = builder.AddNamedSystem("film_loads", FilmLoads(
        plant=plant, pads=pads, force_indices=force_indices, config=config,
        pad_modulus_pa=pad_modulus_pa, matrices=matrices, with_texture=with_texture,
        pad_statics=pad_statics))
    signals = [(name, size) for name, size in zip(loads.layout.names, loads.layout.sizes)
               if size > 0]
    gather = builder.AddNamedSystem("film_signals", Multiplexer([size for _, size in signals]))
    builder.Connect(gather.get_output_port(), loads.GetInputPort("signals"))
    inputs = {name: gather.get_input_port(k) for k, (name, _) in enumerate(signals)}
    samples, held, readout_inputs = AddFilmSamples(
        builder, film_loads=loads.get_output_port(), config=config, time_step=time_step,
        with_drive_vibration=with_drive_vibration, with_noise=noise_draw_std_v(config) > 0)
    builder.Connect(held, inputs.pop("held"))
    inputs.update(readout_inputs)
    for name in ("contact_results", "body_poses", "body_spatial_velocities",
                 "body_spatial_accelerations"):
        inputs[name] = loads.GetInputPort(name)
    for name in ("generalized_contact_forces", "gripper_state", "left_pad_frame_acceleration",
                 "right_pad_frame_acceleration", "texture_state", "drive_vibration", "noise",
                 "contact_results", "body_poses", "body_spatial_velocities",
                 "body_spatial_accelerations"):
        if name in inputs:
            builder.ExportInput(inputs[name], name)
    for finger, port in zip(FINGER_NAMES, samples):
        builder.ExportOutput(port, f"{finger}_pad_vibration")
    diagram = builder.Build()
    diagram.set_name("pad_films")
    return diagram


def finger_force_indices(plant, gripper) -> list[int]:
    """Where each finger's joint sits in the gripper instance's generalized forces."""
    indices = []
    for finger in FINGER_NAMES:
        joint = plant.GetJointByName(f"{finger}_finger_joint", gripper)
        marker = np.zeros(plant.num_velocities())
        marker[joint.velocity_start()] = 1.0
        indices.append(int(np.argmax(plant.GetVelocitiesFromArray(gripper, marker))))
    return indices


def AddPadFilms(builder, *, plant, pads: dict, gripper, config: VibrationSensorConfig,
                pad_modulus_pa: float, slip_vibration=None, pad_forces=None, pad_statics=None,
                drive_rates=(), name: str = "pad_films"):
    """Adds both pads' films (with their accelerometers and noise source) to `builder`,
    connected to `plant`, for pads of modulus `pad_modulus_pa` [Pa]; pad forces from the
    fingers' joints, `pad_forces` or `pad_statics`; `slip_vibration` and `drive_rates`
    optional. Returns MakePadFilms' Diagram."""
    drive = AddDriveVibration(builder, sources=list(drive_rates),
                              period_s=1.0 / config.sample_rate_hz,
                              mode_frequency_hz=config.film.mode_frequency_hz,
                              damping_ratio=config.film.mode_damping_ratio,
                              name=f"{name}_drive_vibration")
    force_port = plant.get_generalized_contact_forces_output_port(gripper)
    force_indices = (0, 1)  # PadNormalForces' outputs (pad_statics reads the whole vector)
    if pad_forces is not None:
        force_port = pad_forces.GetOutputPort("pad_normal_forces")
    elif pad_statics is None:
        force_indices = finger_force_indices(plant, gripper)
    films = builder.AddNamedSystem(name, MakePadFilms(
        plant=plant, pads=pads, force_indices=force_indices, config=config,
        pad_modulus_pa=pad_modulus_pa, with_texture=slip_vibration is not None,
        pad_statics=pad_statics, with_drive_vibration=drive is not None))
    if drive is not None:
        builder.Connect(drive, films.GetInputPort("drive_vibration"))
    builder.Connect(force_port, films.GetInputPort("generalized_contact_forces"))
    if pad_statics is not None:
        builder.Connect(plant.get_state_output_port(gripper),
                        films.GetInputPort("gripper_state"))
    for finger in FINGER_NAMES:
        accelerometer = AddPadFrameAccelerometer(
            builder, plant=plant, pad=pads[finger], name=f"{finger}_pad_accelerometer",
            gravity=np.zeros(3))
        builder.Connect(accelerometer.get_measurement_output_port(),
                        films.GetInputPort(f"{finger}_pad_frame_acceleration"))
    if slip_vibration is not None:
        builder.Connect(slip_vibration.GetOutputPort("texture_state"),
                        films.GetInputPort("texture_state"))
    if noise_draw_std_v(config) > 0:
        noise = builder.AddNamedSystem(f"{name}_noise", RandomSource(
            RandomDistribution.kGaussian, 2, 1.0 / config.sample_rate_hz))
        builder.Connect(noise.get_output_port(), films.GetInputPort("noise"))
    builder.Connect(plant.get_contact_results_output_port(),
                    films.GetInputPort("contact_results"))
    builder.Connect(plant.get_body_poses_output_port(), films.GetInputPort("body_poses"))
    builder.Connect(plant.get_body_spatial_velocities_output_port(),
                    films.GetInputPort("body_spatial_velocities"))
    builder.Connect(plant.get_body_spatial_accelerations_output_port(),
                    films.GetInputPort("body_spatial_accelerations"))
    return films
