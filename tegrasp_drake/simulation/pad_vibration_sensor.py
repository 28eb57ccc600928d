"""The PVDF film on each pad and its charge amplifier (the RA source), from the plant's physics.

What the film measures is the bending strain of the fingertip's printed circuit board, which
it is glued to (the paper's Sec. IV-A): the deflection of the fingertip's first structural
mode. A charge amplifier turns its charge into a voltage and high-passes it at 1/(2 pi R_f
C_f). Per pad, the mode is driven by (film_dynamics.py):

  - the slow load L = F + m a_n: the pad's normal contact force F from the plant (the
    prismatic finger joint's generalized contact force, which moves along the pad normal;
    on the linkage hand the finger body's contact force along the pad normal)
    plus the fingertip's inertia under the finger body's acceleration a_n along the pad's
    inward normal (a Drake Accelerometer on the pad frame, without gravity). A plant step
    resolves a contact's first millisecond into one or two force samples whose size depends
    on the step (measured on this scene with pydrake 1.51), so L passes a 60 Hz low-pass, where the plant's force history
    converges with the step;
  - the impact, which the plant cannot resolve: on the plant step where the pad's contact
    begins, a half-sine of impulse J = (1 + e) m_eff v_n over the contact's physical
    duration T_c = pi sqrt(m_eff / k_c), with v_n the closing speed of the pad and the
    struck body's material points at the contact, before that step; m_eff the reduced mass
    of the fingertip's modal mass and the struck body (the rest of the finger lies behind the
    mode's spring, which is softer than the contact, so it takes no part in the first
    half millisecond); e the Hunt-Crossley restitution of the pad's dissipation;
  - the slip texture (pad_slip_vibration.py) as a base acceleration of the film, directly
    (it is smooth in time and converges with the step).

The whole is linear and integrated exactly at an internal rate (20 kHz) between plant steps,
once per plant step for both pads together. The RA sample is, each sensor period (1 ms), the
internal sample of largest magnitude, with its sign (a peak-hold: a 400 Hz ring sampled at
1 kHz would alias, and its amplitude would depend on the phase of the contact against the
sample grid). The drives' vibration (drive_vibration.py: the gripper's motor and gears, the
arm's actuators, from their joint rates) and Gaussian noise are added to each sample, which
then passes the charge amplifier's output swing and the NI myRIO-1900's 12-bit converter
(film_readout.py): the RA stream moves in steps of one code, 4.88 mV on the default +-10 V
input, i.e. 1.23 m/s^2 at the default sensitivity. The readout runs inside this system's
update (a few float operations on the sample it already computes), not as a system of its
own: it adds no Python call per sample.

Units: the film's voltage is V = -G_Q (y - z) / C_f (film_dynamics.py). It is reported in
acceleration-equivalent units, a = -V / S with S = G_Q / (w^2 C_f) the film's mid-band
sensitivity to base acceleration (`film_sensitivity`; 3.96e-3 V per m/s^2 with the defaults,
i.e. 253 (m/s^2)/V, the hardware's `PadCalibration.piezo_gain`), so that a slow base
acceleration of the finger reads as itself and a load F on the pad reads F / m. The station
keeps the 3-vector ports of an accelerometer; the film has one axis, which is put on the pad
frame's z (the inward normal), x and y stay zero, so Eq. 2's magnitude is |a|.

Seed the noise with `diagram.SetRandomContext(context, RandomGenerator(seed))`.
"""

import dataclasses
import math

import numpy as np
from pydrake.common import RandomDistribution
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialAcceleration, SpatialVelocity
from pydrake.multibody.plant import ContactResults
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import LeafSystem
from pydrake.systems.primitives import RandomSource

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.modelgen.robotiq_sdf import PAD_DISSIPATION, PAD_MODULUS
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH
from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.simulation.drive_vibration import (AddDriveVibration, DriveVibrationConfig,
                                                     arm_drive_default, gripper_drive_default)
from tegrasp_drake.simulation.film_dynamics import (STATE_SIZE, FilmParameters, advance_films,
                                                    film_sensitivity, film_step_matrices,
                                                    halfsine_mean_forces, impact_pulse)
from tegrasp_drake.simulation.film_readout import (adc_input, noise_at_amplifier_v,
                                                  reading_mps2, reading_noise_std)
from tegrasp_drake.simulation.pad_accelerometers import AddPadFrameAccelerometer
from tegrasp_drake.simulation.pad_slip_vibration import UPDATE_PERIOD_S as TEXTURE_PERIOD_S
from tegrasp_drake.simulation.pad_slip_vibration import texture_acceleration

# A pad's contact begins on the plant step whose normal force exceeds this [N] after a step
# at or below it (the plant's force is exactly zero out of contact).
CONTACT_ONSET_N = 1e-6
# The film's gain and the amplifier's capacitor: their words for a value not positive.
_SENSITIVITY_BELOW = "must be positive (it sets the film's volts per m/s^2)"
# Slip textures weaker than this [m/s^2] are not integrated: 5e4 times below the sensor
# noise; creep of a held object (micrometres per second) gives about 1e-7.
TEXTURE_FLOOR_MPS2 = 1e-6


@dataclasses.dataclass
class VibrationSensorConfig:
    """The PVDF film of each pad (RA channel source). Sources and reasoning of every number:
    docs/model.md, "Vibration (RA) model"."""
    # RA output rate (peak-hold over each period)
    sample_rate_hz: float = bounded(1000.0, low=16.0, high=20_000.0, unit="Hz",
                                    why="the 0.5 s event window needs 8 samples; the film is "
                                        "integrated at 20 kHz")
    # per sample, acceleration-equivalent
    noise_std_mps2: float = bounded(0.05, low=0.0, high=100.0, unit="m/s^2",
                                    why="the film's noise is a few hundredths; 100 would bury "
                                        "every event",
                                    below="must be zero (no noise) or positive [m/s^2]")
    # charge amplifier corner 1 / (2 pi R_f C_f)
    highpass_cutoff_hz: float = bounded(2.0, low=0.0, low_open=True, high=1000.0, unit="Hz",
                                        why="the charge amplifier's corner, below the RA band")
    # Texture of the pad cover that sliding drags the film over (pad_slip_vibration.py): a
    # woven fabric of about 0.5 mm pitch with a few micrometres of relief. 0 disables.
    slip_texture_height_m: float = bounded(5e-6, low=0.0, high=1e-3, unit="m",
                                           why="surface roughness, microns")
    slip_texture_period_m: float = bounded(5e-4, low=0.0, low_open=True, high=0.01, unit="m",
                                           why="texture wavelength, sub-millimetre")
    # The fingertip's first structural mode (an estimate: see docs/model.md).
    mode_frequency_hz: float = bounded(400.0, low=0.0, low_open=True, high=10_000.0,
                                       high_open=True, unit="Hz",
                                       why="the fingertip's mode, below half the 20 kHz "
                                           "integration rate; at 0 the film feels no ring")
    mode_damping_ratio: float = bounded(0.05, low=0.0, high=10.0,
                                        why="a lightly damped fingertip is 0.01-0.2",
                                        below="must be zero or positive")
    mode_mass_kg: float = bounded(0.024, low=0.0, low_open=True, high=1.0, unit="kg",
                                  why="the fingertip's moving mass, tens of grams",
                                  below="must be positive [kg] (the fingertip's moving mass)")
    # Corner of the low-pass on the plant's per-step load (where the plant's force converges).
    load_lowpass_hz: float = bounded(60.0, low=0.0, low_open=True, high=10_000.0, unit="Hz")
    # The impact pulse at contact onset: the pad's contact stiffness E A / (t / 2) and its
    # Hunt-Crossley dissipation, both from the pad model.
    impact_enabled: bool = True
    pad_contact_stiffness_n_per_m: float = bounded(
        PAD_MODULUS * PAD_WIDTH * PAD_LENGTH / (PAD_THICKNESS / 2), low=0.0, low_open=True,
        high=1e9, unit="N/m", why="a silicone pad is about 5e5 N/m; 1e9 is steel on steel")
    pad_dissipation_s_per_m: float = bounded(PAD_DISSIPATION, low=0.0, high=1000.0, unit="s/m",
                                             why="Hunt-Crossley dissipation of soft materials is "
                                                 "0.1-50 s/m")
    # Film charge per unit modal deflection G_Q = d31 E_film kappa A_film, and the charge
    # amplifier's feedback capacitance: they set the film's sensitivity at the amplifier's
    # output, S = G_Q / (w^2 C_f) [V/(m/s^2)] (volts_per_mps2; 3.96e-3 with these), and with
    # it the volts the readout below clips and quantises. The range of G_Q (a film bonded
    # behind the board vs a free cantilever) and why S is kept: docs/model.md.
    film_charge_gain_c_per_m: float = bounded(2.5e-5, low=0.0, low_open=True, high=1e-2,
                                              unit="C/m", below=_SENSITIVITY_BELOW)
    feedback_capacitance_f: float = bounded(1e-9, low=0.0, low_open=True, high=1e-6, unit="F",
                                            why="a charge amplifier's feedback capacitor is pF to "
                                                "nF",
                                            below=_SENSITIVITY_BELOW)
    # The readout (film_readout.py): the amplifier's output swing [V] (an op-amp on the
    # myRIO MSP connector's +-15 V supply swings to about +-13.5 V), and the NI myRIO-1900's
    # 12-bit input: "msp" (+-10 V, 4.88 mV a code; the default, for the bipolar amplifier),
    # "mxp" (0-5 V, 1.22 mV a code, the amplifier level-shifted to 2.5 V) or "ideal" (no
    # converter: the amplifier's voltage itself, unclipped by any input range); the
    # converter's own input noise in codes rms (half a code: a 12-bit converter's noise is
    # below one code, or its last bit would carry noise only; NI's 12-bit boards dither with
    # about 0.5 code rms, NI PCI-1200 User Manual).
    amplifier_swing_v: float = bounded(13.5, low=0.0, low_open=True, high=15.0, unit="V",
                                       why="an amplifier on the myRIO's +-15 V supply cannot "
                                           "swing past its rails",
                                       below="must be positive [V]")
    adc_input: str = "msp"
    adc_noise_lsb: float = bounded(0.5, low=0.0, high=1.0, unit="codes rms",
                                   why="a 12-bit converter's noise is below one code, NI "
                                       "PCI-1200 User Manual; 0: none",
                                   below="must be zero (no noise) or positive [codes rms]")
    # Vibration of the gripper's motor and gears while the fingers move, and of the arm's
    # actuators while the arm moves (drive_vibration.py; amplitudes_mps2 [] disables).
    gripper_drive: DriveVibrationConfig = dataclasses.field(
        default_factory=gripper_drive_default)
    arm_drive: DriveVibrationConfig = dataclasses.field(default_factory=arm_drive_default)
    # exact integration points per second
    internal_rate_hz: float = bounded(20000.0, low=0.0, low_open=True, high=200_000.0, unit="Hz",
                                      why="exact integration points per second; the wall time "
                                          "grows with it",
                                      below="must be positive [Hz]")
    # "film": the PVDF film above (the real pad's); "accelerometer": a rigid-body
    # accelerometer on the pad, its normal axis high-passed at highpass_cutoff_hz
    # (pad_accelerometers.py; the paper's simulation had one per pad). The film's own
    # settings are then unused.
    transducer: str = "film"
    # Where the linkage hand's films get their pad forces (linkage_pad_statics.py; the same
    # forces to round-off): "contact_results", a walk over the plant's contact results
    # each step (PadNormalForces); "joint_forces", its joints' generalized contact forces.
    pad_force_source: str = "contact_results"


def film_parameters(config: VibrationSensorConfig) -> FilmParameters:
    return FilmParameters(mode_frequency_hz=config.mode_frequency_hz,
                          damping_ratio=config.mode_damping_ratio,
                          modal_mass_kg=config.mode_mass_kg,
                          load_lowpass_hz=config.load_lowpass_hz,
                          highpass_hz=config.highpass_cutoff_hz)


def volts_per_mps2(config: VibrationSensorConfig) -> float:
    """The film's mid-band sensitivity S [V/(m/s^2)]: its voltage is -S times the output."""
    return film_sensitivity(config.film_charge_gain_c_per_m, config.mode_frequency_hz,
                            config.feedback_capacitance_f)


def noise_draw_std_v(config: VibrationSensorConfig) -> float:
    """The Gaussian noise [V rms] added to each film sample ahead of the readout: the
    amplifier's and the converter's (film_readout.py)."""
    return noise_at_amplifier_v(config.noise_std_mps2, config.adc_noise_lsb,
                                volts_per_mps2(config), adc_input(config.adc_input))


def ra_noise_std_mps2(config: VibrationSensorConfig) -> float:
    """The RA channel's noise at rest [m/s^2 rms], in closed form from the electronics:
    the film's readout (film_readout.reading_noise_std), or the accelerometer's own noise."""
    if config.transducer != "film":
        return config.noise_std_mps2
    return reading_noise_std(config.noise_std_mps2, config.adc_noise_lsb,
                             volts_per_mps2(config), adc_input(config.adc_input))


# The discrete state. Group 0, one vector: the films' states (5 x 2, row-major: state i of
# pad p at 2 i + p) followed by this step's loads, so that [0:12] reshaped (6, 2) is
# advance_films' input; the last step's normal forces; the impact pulses (onset times,
# impulses, durations); the running peak of the sensor period. Then one group per pad, its
# output sample as the port gives it, [0, 0, a] (x and y stay zero): the output ports are
# Drake state output ports, read with no Python call.
_FILM = slice(0, 2 * STATE_SIZE)
_LOAD = 2 * STATE_SIZE  # left, right
_FILM_AND_LOAD = slice(0, _LOAD + 2)
_FORCE = 12  # left, right
_ONSET, _IMPULSE, _DURATION = slice(14, 16), slice(16, 18), slice(18, 20)
_PEAK = slice(20, 22)
_STATE_LENGTH = 22
_SAMPLE_AXIS = 2  # the film's axis, the pad frame's z, in each sample group


def _point_velocity_before_step(X_WB: RigidTransform, V_WB: SpatialVelocity,
                                A_WB: SpatialAcceleration, p_WQ: np.ndarray,
                                time_step: float) -> np.ndarray:
    """Velocity [m/s] of body B's material point at p_WQ one plant step earlier, from its
    velocity and the step's acceleration now."""
    r = p_WQ - X_WB.translation()
    w, alpha = V_WB.rotational(), A_WB.rotational()
    velocity = V_WB.translational() + np.cross(w, r)
    acceleration = A_WB.translational() + np.cross(alpha, r) + np.cross(w, np.cross(w, r))
    return velocity - time_step * acceleration


class PadFilms(LeafSystem):
    """Both pads' PVDF films, advanced once per plant step (see the module docstring).

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

    Ports:
        generalized_contact_forces: the gripper model instance's generalized contact
            forces; entry force_indices[k] is finger k's joint, positive pushing its pad
            outward (N); or PadNormalForces' output with force_indices (0, 1); or, with
            `pad_statics`, the whole instance's, which pad_statics turns into pad forces.
        gripper_state: the gripper model instance's state; declared only with
            `pad_statics` (linkage_pad_statics.py), which reads its joint angles.
        left_pad_frame_acceleration, right_pad_frame_acceleration: each pad frame's
            acceleration without gravity, in the pad frame (3, m/s^2; Drake Accelerometer).
        texture_state: PadSlipVibration's texture_state (6), from which the texture
            acceleration along each pad normal is synthesised at the internal rate; declared
            only with `with_texture`.
        drive_vibration: the drives' vibration at the fingertips (2, m/s^2,
            drive_vibration.py), added to each sample; declared only with
            `with_drive_vibration`.
        noise: unit Gaussian samples at the sensor rate (2); declared only when the
            amplifier's or the converter's noise is above zero (noise_draw_std_v).
        contact_results, body_poses, body_spatial_velocities, body_spatial_accelerations:
            the plant's; read only on the plant step where a pad's contact begins.
        left_pad_vibration, right_pad_vibration: the film's peak-hold sample plus the drives'
            vibration and noise, through the amplifier's swing and the myRIO's converter
            (film_readout.py), on z, x and y zero (3, m/s^2-equivalent, pad frame); updated
            every sensor period.
    """

    def __init__(self, *, plant, pads: dict, force_indices, config: VibrationSensorConfig,
                 with_texture: bool = False, pad_statics=None,
                 with_drive_vibration: bool = False):
        super().__init__()
        self._dt = plant.time_step()
        if not self._dt > 0.0:
            raise ValueError("PadFilms needs a discrete-time plant")
        self._pads = [pads[finger] for finger in FINGER_NAMES]
        self._force_indices = np.asarray(force_indices, dtype=int)
        self._left_index, self._right_index = (int(i) for i in force_indices)
        self._config = config
        self._matrices = film_step_matrices(film_parameters(config), self._dt,
                                            config.internal_rate_hz)
        self._midpoints = self._matrices.substep_starts + 0.5 * self._matrices.h
        self._texture_period_m = config.slip_texture_period_m
        steps_per_sample = 1.0 / (config.sample_rate_hz * self._dt)
        if steps_per_sample > 1.0 and abs(steps_per_sample - round(steps_per_sample)) > 1e-6:
            raise ValueError(f"the RA period 1/{config.sample_rate_hz:g} s must be a whole "
                             f"number of plant steps ({self._dt:g} s)")
        # A plant step longer than the RA period gives a sample per step.
        self._steps_per_sample = max(1, int(round(steps_per_sample)))
        # What a contact onset needs to know about the other body: which body a collision
        # geometry belongs to, its mass, and whether it is welded to the world.
        self._geometry_body = {}
        self._mass = {}
        for i in range(plant.num_bodies()):
            body = plant.get_body(BodyIndex(i))
            self._mass[i] = body.default_mass()
            for geometry in plant.GetCollisionGeometriesForBody(body):
                self._geometry_body[geometry] = i
        for body in plant.GetBodiesWeldedTo(plant.world_body()):
            self._mass[int(body.index())] = math.inf

        self._statics = pad_statics  # a LinkagePadStatics, or None: force_indices
        self._forces = self.DeclareVectorInputPort(
            "generalized_contact_forces", int(self._force_indices.max()) + 1
            if pad_statics is None else pad_statics.velocities)
        self._gripper_state = (None if pad_statics is None else
                               self.DeclareVectorInputPort("gripper_state", pad_statics.states))
        self._accelerations = [self.DeclareVectorInputPort(f"{f}_pad_frame_acceleration", 3)
                               for f in FINGER_NAMES]
        self._texture = (self.DeclareVectorInputPort("texture_state", 3 * len(FINGER_NAMES))
                         if with_texture else None)
        self._drive = (self.DeclareVectorInputPort("drive_vibration", 2)
                       if with_drive_vibration else None)
        self._noise_std_v = noise_draw_std_v(config)
        self._noise = (self.DeclareVectorInputPort("noise", 2)
                       if self._noise_std_v > 0 else None)
        self._readout = (volts_per_mps2(config), config.amplifier_swing_v,
                         adc_input(config.adc_input))
        self._contacts = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._poses = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        self._velocities = self.DeclareAbstractInputPort(
            "body_spatial_velocities", AbstractValue.Make([SpatialVelocity()]))
        self._body_accelerations = self.DeclareAbstractInputPort(
            "body_spatial_accelerations", AbstractValue.Make([SpatialAcceleration()]))
        self._state = self.DeclareDiscreteState(_STATE_LENGTH)
        self._samples = [self.DeclareDiscreteState(3) for _ in FINGER_NAMES]
        self.DeclarePeriodicDiscreteUpdateEvent(self._dt, 0.0, self._update)
        for finger, sample in zip(FINGER_NAMES, self._samples):
            self.DeclareStateOutputPort(f"{finger}_pad_vibration", sample)

    @property
    def force_indices(self) -> tuple[int, ...]:
        """Where each pad's finger joint sits in the generalized_contact_forces input."""
        return tuple(int(i) for i in self._force_indices)

    def _update(self, context, discrete_state):
        # Scalars are handled as Python floats: per plant step, numpy's scalar overhead
        # would cost more than the integration itself.
        state = discrete_state.get_mutable_value(self._state)  # holds the current state
        forces = self._forces.Eval(context).tolist()
        if self._statics is None:
            left, right = forces[self._left_index], forces[self._right_index]
        else:
            left, right = self._statics.normal_forces(
                forces, self._gripper_state.Eval(context).tolist())
        before_left, before_right = state[_FORCE:_FORCE + 2].tolist()
        m = self._config.mode_mass_kg
        state[_LOAD:_LOAD + 2] = (left + m * self._accelerations[0].Eval(context).item(2),
                                  right + m * self._accelerations[1].Eval(context).item(2))
        state[_FORCE:_FORCE + 2] = (left, right)
        onsets = (abs(left) > CONTACT_ONSET_N >= abs(before_left),
                  abs(right) > CONTACT_ONSET_N >= abs(before_right))
        time = context.get_time()
        step = int(round(time / self._dt))
        if step == 0:  # no plant step has ended yet
            return
        step_start = time - self._dt
        if self._config.impact_enabled and (onsets[0] or onsets[1]):
            self._start_impacts(context, onsets, step_start, state)
        direct = self._impact_loads(step_start, state)
        if self._texture is not None and (left != 0.0 or right != 0.0):
            texture = self._texture_loads(context, step_start)
            if texture is not None:
                direct = texture if direct is None else direct + texture
        films, outputs = advance_films(self._matrices,
                                       state[_FILM_AND_LOAD].reshape(STATE_SIZE + 1, 2), direct)
        state[_FILM] = films.ravel()
        # The sample of largest magnitude, with its sign, held over the sensor period.
        rows = np.abs(outputs).argmax(axis=0).tolist()
        peaks = state[_PEAK].tolist()
        for k in (0, 1):
            peak = outputs.item(rows[k], k)
            if abs(peak) > abs(peaks[k]):
                peaks[k] = peak
        if step % self._steps_per_sample:
            state[_PEAK] = peaks
            return
        if self._drive is not None:
            drive = self._drive.Eval(context).tolist()
            peaks = [peaks[0] + drive[0], peaks[1] + drive[1]]
        noise = (0.0, 0.0)
        if self._noise is not None:
            noise = [self._noise_std_v * n for n in self._noise.Eval(context).tolist()]
        for sample, value, n in zip(self._samples, peaks, noise):
            discrete_state.get_mutable_value(sample)[_SAMPLE_AXIS] = reading_mps2(
                value, n, *self._readout)
        state[_PEAK] = 0.0

    def _impact_loads(self, step_start: float, state: np.ndarray):
        """(n, 2) impact forces [N] over this step's internal steps, or None."""
        impulses = state[_IMPULSE].tolist()
        if impulses[0] <= 0.0 and impulses[1] <= 0.0:
            return None
        direct = None
        for k in (0, 1):
            onset, duration = state.item(_ONSET.start + k), state.item(_DURATION.start + k)
            if impulses[k] <= 0.0 or step_start >= onset + duration:
                continue
            if direct is None:
                direct = np.zeros((self._matrices.substeps, 2))
            direct[:, k] = halfsine_mean_forces(step_start, self._matrices.substep_starts,
                                                self._matrices.h, onset, impulses[k], duration)
            if step_start + self._dt >= onset + duration:
                state[_IMPULSE.start + k] = 0.0  # delivered
        return direct

    def _texture_loads(self, context, step_start: float):
        """(n, 2) the texture's inertial load [N] on each fingertip over this step's internal
        steps, or None when neither pad's texture is above TEXTURE_FLOOR_MPS2."""
        texture = self._texture.Eval(context)
        if (abs(texture.item(1)) <= TEXTURE_FLOOR_MPS2
                and abs(texture.item(4)) <= TEXTURE_FLOOR_MPS2):
            return None
        phase, amplitude, speed = texture[0::3], texture[1::3], texture[2::3]
        # The texture sample in force now is the one taken at the last multiple of its
        # period before this update (an update at that same instant is not applied yet).
        sampled_at = TEXTURE_PERIOD_S * math.floor((step_start + 0.5 * self._dt)
                                                   / TEXTURE_PERIOD_S)
        elapsed = (step_start - sampled_at + self._midpoints)[:, np.newaxis]
        return self._config.mode_mass_kg * texture_acceleration(
            phase, amplitude, speed, elapsed, self._texture_period_m)

    def _start_impacts(self, context, onsets, step_start: float, state: np.ndarray):
        """Sets the impact pulse of each pad whose contact began on this plant step."""
        contacts = self._contacts.Eval(context)
        poses = self._poses.Eval(context)
        velocities = self._velocities.Eval(context)
        accelerations = self._body_accelerations.Eval(context)
        for k in (k for k in range(2) if onsets[k]):
            touch = self._strongest_contact(contacts, self._pads[k].geometry_id)
            if touch is None:
                continue
            other, p_WC = touch
            pad_body = int(self._pads[k].body_index)
            X_WP = poses[pad_body] @ self._pads[k].X_BP
            normal = X_WP.rotation().matrix()[:, 2].copy()  # inward
            v_pad, v_other = (_point_velocity_before_step(
                poses[b], velocities[b], accelerations[b], p_WC, self._dt)
                for b in (pad_body, other))
            impulse, duration = impact_pulse(
                float(np.dot(v_pad - v_other, normal)), self._config.mode_mass_kg,
                self._mass[other], self._config.pad_contact_stiffness_n_per_m,
                self._config.pad_dissipation_s_per_m)
            state[_ONSET.start + k] = step_start
            state[_IMPULSE.start + k] = impulse
            state[_DURATION.start + k] = duration

    def _strongest_contact(self, contacts: ContactResults, pad_geometry):
        """(other body index, contact point in world) of the pad's largest contact force,
        or None when the pad has no contact."""
        best, best_force = None, -1.0
        for i in range(contacts.num_hydroelastic_contacts()):
            info = contacts.hydroelastic_contact_info(i)
            surface = info.contact_surface()
            ids = (surface.id_M(), surface.id_N())
            if pad_geometry not in ids:
                continue
            other = ids[1] if ids[0] == pad_geometry else ids[0]
            force = float(np.linalg.norm(info.F_Ac_W().translational()))
            if force > best_force:
                best, best_force = (self._geometry_body[other], surface.centroid()), force
        for i in range(contacts.num_point_pair_contacts()):
            info = contacts.point_pair_contact_info(i)
            ids = (info.point_pair().id_A, info.point_pair().id_B)
            if pad_geometry not in ids:
                continue
            other = ids[1] if ids[0] == pad_geometry else ids[0]
            force = float(np.linalg.norm(info.contact_force()))
            if force > best_force:
                best, best_force = (self._geometry_body[other], info.contact_point()), force
        return best


def finger_force_indices(plant, gripper) -> list[int]:
    """Where each finger's joint (FINGER_NAMES order, `<finger>_finger_joint`) sits in the
    gripper model instance's generalized contact forces."""
    indices = []
    for finger in FINGER_NAMES:
        joint = plant.GetJointByName(f"{finger}_finger_joint", gripper)
        marker = np.zeros(plant.num_velocities())
        marker[joint.velocity_start()] = 1.0
        indices.append(int(np.argmax(plant.GetVelocitiesFromArray(gripper, marker))))
    return indices


def AddPadFilms(builder, *, plant, pads: dict, gripper, config: VibrationSensorConfig,
                slip_vibration=None, pad_forces=None, pad_statics=None,
                drive_rates=(), name: str = "pad_films") -> PadFilms:
    """Adds both pads' films (and the accelerometers and noise source they read) to
    `builder`, connected to `plant`; `slip_vibration`, if given, is the PadSlipVibration
    system. The pads' normal contact forces come from the fingers' prismatic joints, or,
    as the linkage hand needs, from `pad_forces` (a PadNormalForces system) or from the
    joints' generalized contact forces through `pad_statics` (a LinkagePadStatics) when
    given. `drive_rates`: (DriveVibrationConfig, joint-rate output port) of each drive
    whose vibration the films read (drive_vibration.py). Returns the PadFilms system
    (outputs `<finger>_pad_vibration`)."""
    drive = AddDriveVibration(builder, sources=list(drive_rates),
                              period_s=1.0 / config.sample_rate_hz,
                              mode_frequency_hz=config.mode_frequency_hz,
                              damping_ratio=config.mode_damping_ratio,
                              name=f"{name}_drive_vibration")
    force_port = plant.get_generalized_contact_forces_output_port(gripper)
    force_indices = (0, 1)  # PadNormalForces' outputs (pad_statics reads the whole vector)
    if pad_forces is not None:
        force_port = pad_forces.GetOutputPort("pad_normal_forces")
    elif pad_statics is None:
        force_indices = finger_force_indices(plant, gripper)
    films = builder.AddNamedSystem(name, PadFilms(
        plant=plant, pads=pads, force_indices=force_indices,
        config=config, with_texture=slip_vibration is not None, pad_statics=pad_statics,
        with_drive_vibration=drive is not None))
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
