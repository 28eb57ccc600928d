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
input, i.e. 1.23 m/s^2 at the default sensitivity. This module holds the films' settings;
film_chain.py builds them as one Diagram of compiled Drake systems (film_loads.py, the one
Python system, reads the plant's contacts for the impact).

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

from tegrasp_drake.rig.ranges import bounded
from tegrasp_drake.modelgen.robotiq_sdf import PAD_DISSIPATION, PAD_MODULUS
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH
from tegrasp_drake.simulation.drive_vibration import (DriveVibrationConfig, arm_drive_default,
                                                     gripper_drive_default)
from tegrasp_drake.simulation.film_dynamics import FilmParameters, film_sensitivity
from tegrasp_drake.simulation.film_readout import (ADC_INPUTS, adc_input, noise_at_amplifier_v,
                                                  reading_noise_std)

# The film's gain and the amplifier's capacitor: their words for a value not positive.
_SENSITIVITY_BELOW = "must be positive (it sets the film's volts per m/s^2)"


@dataclasses.dataclass
class FilmConfig:
    """The fingertip's first structural mode that bends the film, the impact that rings it
    at contact onset, and the film's charge per deflection with its amplifier's capacitor
    (film_dynamics.py, film_loads.py). Sources and reasoning of every number:
    docs/model.md, "Vibration (RA) model"."""
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
    # The film's mechanics and charge.
    film: FilmConfig = dataclasses.field(default_factory=FilmConfig)
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
    # settings (`film`, the readout's) are then unused.
    transducer: str = "film"
    # Where the linkage hand's films get their pad forces (linkage_pad_statics.py; the same
    # forces to round-off): "contact_results", a walk over the plant's contact results
    # each step (PadNormalForces); "joint_forces", its joints' generalized contact forces.
    pad_force_source: str = "contact_results"

    def problem(self) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first name that is not one of its
        choices or setting that does not fit another (each number's own range is declared
        on its field); None when all fit."""
        from tegrasp_drake.simulation.linkage_pad_statics import PAD_FORCE_SOURCES
        from tegrasp_drake.simulation.pad_accelerometers import VIBRATION_TRANSDUCERS
        choices = (("transducer", VIBRATION_TRANSDUCERS, "(the PVDF film, or a high-passed "
                    "accelerometer on the pad)"),
                   ("pad_force_source", PAD_FORCE_SOURCES, ""),
                   ("adc_input", ADC_INPUTS, "(the myRIO's +-10 V MSP input, its 0-5 V MXP "
                    "input, or no converter)"))
        for field, names, what in choices:
            if getattr(self, field) not in names:
                return (field, f"must be one of {', '.join(names)}{' ' * bool(what)}{what}",
                        getattr(self, field))
        nyquist = self.internal_rate_hz / 2
        if not 0 < self.film.mode_frequency_hz < nyquist:
            return ("film.mode_frequency_hz", f"must lie in (0, {nyquist:g}) Hz (the "
                    "fingertip's mode, integrated at vibration.internal_rate_hz; at 0 the film "
                    "feels no ring)", self.film.mode_frequency_hz)
        # The charge amplifier's high-pass runs where the film is integrated
        # (internal_rate_hz, film_dynamics.py); the accelerometer's on its samples
        # (pad_accelerometers.py).
        filter_rate_hz, rate_name = ((self.sample_rate_hz, "vibration.sample_rate_hz")
                                     if self.transducer == "accelerometer" else
                                     (self.internal_rate_hz, "vibration.internal_rate_hz"))
        if not self.highpass_cutoff_hz < filter_rate_hz / 2:
            return ("highpass_cutoff_hz", f"must lie below {filter_rate_hz / 2:g} Hz, half the "
                    f"{rate_name} its {self.transducer} filter runs at", self.highpass_cutoff_hz)
        for name in ("gripper_drive", "arm_drive"):
            tones = getattr(self, name)
            if tones.amplitudes_mps2 and len(tones.amplitudes_mps2) != len(tones.orders):
                return (f"{name}.orders", "must give one order per amplitude "
                        f"({len(tones.amplitudes_mps2)} amplitudes; amplitudes_mps2=[] switches "
                        "the drive off)", tones.orders)
        return None


def film_parameters(config: VibrationSensorConfig) -> FilmParameters:
    film = config.film
    return FilmParameters(mode_frequency_hz=film.mode_frequency_hz,
                          damping_ratio=film.mode_damping_ratio,
                          modal_mass_kg=film.mode_mass_kg,
                          load_lowpass_hz=film.load_lowpass_hz,
                          highpass_hz=config.highpass_cutoff_hz)


def volts_per_mps2(config: VibrationSensorConfig) -> float:
    """The film's mid-band sensitivity S [V/(m/s^2)]: its voltage is -S times the output."""
    film = config.film
    return film_sensitivity(film.film_charge_gain_c_per_m, film.mode_frequency_hz,
                            film.feedback_capacitance_f)


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
