"""The PVDF film on each pad and its charge amplifier (the RA source): the settings
(`VibrationSensorConfig`, the scenario's `vibration` section) and the sensitivity and noise that
follow from them. The RA output is in acceleration-equivalent units, a = -V / S, on the pad frame's
z (the inward normal). The model and every number: docs/model.md, "Vibration (RA) model"."""

import dataclasses
import math

from tegrasp_drake.rig.ranges import (SAMPLE_RATE, bounded, within,
                                      chosen, field_range)
from tegrasp_drake.modelgen.robotiq_sdf import PAD_DISSIPATION
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH
from tegrasp_drake.simulation.drive_vibration import (DriveVibrationConfig, arm_drive_default,
                                                     gripper_drive_default)
from tegrasp_drake.simulation.film_dynamics import FilmParameters, film_sensitivity
from tegrasp_drake.simulation.linkage_pad_statics import PAD_FORCE_SOURCES
from tegrasp_drake.simulation.pad_accelerometers import VIBRATION_TRANSDUCERS
from tegrasp_drake.simulation.film_readout import (ADC_INPUTS, adc_input, noise_at_amplifier_v,
                                                  reading_mps2, reading_noise_std)
from tegrasp_drake.rig.api_boundary import public_dataclass, register_moved_fields


def pad_contact_stiffness(pad_modulus_pa: float) -> float:
    """The pad's stiffness under a flat face [N/m]: E A / (t / 2), E its elastomer's modulus
    [Pa] on the pad's face A and half its thickness t (Drake's pressure field of a compliant
    box reaches the modulus at its mid-plane)."""
    return pad_modulus_pa * PAD_WIDTH * PAD_LENGTH / (PAD_THICKNESS / 2)


def impact_stiffness(film: "FilmConfig", pad_modulus_pa: float) -> float:
    """The stiffness [N/m] the film's impact model gives the pad: `film`'s
    pad_contact_stiffness_n_per_m when set, else pad_contact_stiffness of the pads' modulus
    `pad_modulus_pa` [Pa] (tactile.pad_modulus_pa)."""
    if film.pad_contact_stiffness_n_per_m is not None:
        return film.pad_contact_stiffness_n_per_m
    return pad_contact_stiffness(pad_modulus_pa)


@public_dataclass
@dataclasses.dataclass
class FilmConfig:
    """The fingertip's first structural mode, the impact that rings it, and the film's charge per
    deflection with its amplifier's capacitor. Sources: docs/model.md, "Vibration (RA) model"."""
    # The fingertip's first structural mode (an estimate: see docs/model.md).
    # Low end: the bolted fingertip, about 1.5e5 N/m on 24 g, rings at 400 Hz (docs/model.md);
    # below 50 Hz its ring would sit among the grip's own motions (a finger starts and stops
    # in about 0.15 s), no fingertip a hand carries.
    mode_frequency_hz: float = bounded(400.0, low=50.0, high=10_000.0,
                                       high_open=True, unit="Hz",
                                       why="the fingertip's mode: at least 50 Hz, above the "
                                           "grip's own motions; below half the 20 kHz "
                                           "integration rate")
    mode_damping_ratio: float = bounded(0.05, low=0.0, high=10.0,
                                        why="a lightly damped fingertip is 0.01-0.2",
                                        below="must be zero or positive")
    # Low end: a gram is the film and its cover alone, with no fingertip behind them.
    mode_mass_kg: float = bounded(0.024, low=0.001, high=1.0, unit="kg",
                                  why="the fingertip's moving mass, tens of grams; at least "
                                      "the film and its cover's gram")
    # Corner of the low-pass on the plant's per-step load (where the plant's force converges).
    load_lowpass_hz: float = bounded(60.0, low=0.0, low_open=True, high=10_000.0, unit="Hz")
    # Impact at contact onset: the pad's stiffness, its Hunt-Crossley dissipation. The
    # stiffness follows the pads' modulus, E A / (t / 2) of tactile.pad_modulus_pa
    # (impact_stiffness), unless a number here overrides it (null: follow the modulus).
    impact_enabled: bool = True
    pad_contact_stiffness_n_per_m: float | None = bounded(
        None, low=1e3,
        high=1e9, unit="N/m", why="a silicone pad is about 5e5 N/m; below 1e3 N/m a 1 N touch "
                                  "would crush its few millimetres; 1e9 is steel on steel")
    pad_dissipation_s_per_m: float = bounded(PAD_DISSIPATION, low=0.0, high=1000.0, unit="s/m",
                                             why="Hunt-Crossley dissipation of soft materials is "
                                                 "0.1-50 s/m")
    # G_Q = d31 E_film kappa A_film (PVDF film data) and C_f set S = G_Q / (w^2 C_f) [V/(m/s^2)].
    # Low end: a film bonded behind the fingertip's board strains 3-30 times less than the
    # free one of the default: 2.5e-5 / 30 = 8e-7 C/m (docs/model.md, "Vibration (RA) model",
    # the film's sensitivity and its range); 5e-7 leaves room below the bonded film's.
    film_charge_gain_c_per_m: float = bounded(2.5e-5, low=5e-7, high=1e-2, unit="C/m",
                                              why="a film bonded behind the board gives about "
                                                  "1e-6, 30 times less than a free one")
    feedback_capacitance_f: float = bounded(1e-9, low=1e-12, high=1e-6, unit="F",
                                            why="a charge amplifier's feedback capacitor is pF to "
                                                "nF; below 1 pF the board's stray capacitance "
                                                "would set the gain")


@public_dataclass
@dataclasses.dataclass
class VibrationSensorConfig:
    """The PVDF film of each pad (RA source); each number: docs/model.md, "Vibration (RA) model"."""
    sample_rate_hz: float = within(1000.0, SAMPLE_RATE)
    noise_std_mps2: float = bounded(0.05, low=0.0, high=100.0, unit="m/s^2",
                                    why="the film's noise is a few hundredths; 100 would bury "
                                        "every event",
                                    below="must be zero (no noise) or positive [m/s^2]")
    # charge amplifier corner 1 / (2 pi R_f C_f)
    # Low end: 1 nF with a 10 GOhm feedback resistor, the largest a board carries, is 0.016 Hz.
    highpass_cutoff_hz: float = bounded(2.0, low=0.01, high=1000.0, unit="Hz",
                                        why="the charge amplifier's corner, below the RA band; "
                                            "at least the 0.01 Hz a 10 GOhm resistor gives")
    # The pad cover's texture (pad_slip_vibration.py): woven fabric, 0.5 mm pitch; 0 disables.
    slip_texture_height_m: float = bounded(5e-6, low=0.0, high=1e-3, unit="m",
                                           why="surface roughness, microns")
    slip_texture_period_m: float = bounded(5e-4, low=1e-6, high=0.01, unit="m",
                                           why="texture wavelength, sub-millimetre; at least a "
                                               "polished surface's micron")
    film: FilmConfig = dataclasses.field(default_factory=FilmConfig)
    # The readout (film_readout.py): the amplifier's swing on the myRIO's +-15 V supply, and
    # the NI myRIO-1900's 12-bit input: "msp" (+-10 V), "mxp" (0-5 V) or "ideal" (none).
    amplifier_swing_v: float = bounded(13.5, low=0.1, high=15.0, unit="V",
                                       why="an amplifier on the myRIO's +-15 V supply cannot "
                                           "swing past its rails; at least 0.1 V, 20 codes of "
                                           "the 12-bit +-10 V input")
    adc_input: str = chosen("msp", names=ADC_INPUTS, why="the myRIO's +-10 V MSP input, its 0-5 V "
                                                        "MXP input, or no converter")
    adc_noise_lsb: float = bounded(0.5, low=0.0, high=1.0, unit="codes rms",
                                   why="a 12-bit converter's noise is below one code, NI "
                                       "PCI-1200 User Manual; 0: none",
                                   below="must be zero (no noise) or positive [codes rms]")
    # The gripper's and the arm's drive vibration (drive_vibration.py; [] amplitudes: off).
    gripper_drive: DriveVibrationConfig = dataclasses.field(
        default_factory=gripper_drive_default)
    arm_drive: DriveVibrationConfig = dataclasses.field(default_factory=arm_drive_default)
    internal_rate_hz: float = bounded(20000.0, low=1000.0, high=200_000.0, unit="Hz",
                                      why="exact integration points per second; the wall time "
                                          "grows with it; at least the 1 kHz tactile rate")
    # "film", or "accelerometer": a high-passed rigid-body accelerometer on the pad, as in the
    # paper's simulation (pad_accelerometers.py); the film's own settings are then unused.
    transducer: str = chosen("film", names=VIBRATION_TRANSDUCERS,
                             why="the PVDF film, or a high-passed accelerometer on the pad")
    # The linkage hand's pad forces: "contact_results" (PadNormalForces) or "joint_forces"
    # (linkage_pad_statics.py, cheaper); the same forces to round-off.
    pad_force_source: str = chosen("contact_results", names=PAD_FORCE_SOURCES,
                                   why="the contact results, or the linkage's joint statics")

    def problem(self) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first cross-field setting that does not
        fit (each number's range and each text's choices are declared on its field); None
        when all fit."""
        nyquist = self.internal_rate_hz / 2
        lowest = field_range(FilmConfig, "mode_frequency_hz").low
        if not lowest <= self.film.mode_frequency_hz < nyquist:
            return ("film.mode_frequency_hz", f"must lie in [{lowest:g}, {nyquist:g}) Hz (the "
                    "fingertip's mode, integrated at vibration.internal_rate_hz)",
                    self.film.mode_frequency_hz)
        # The film's high-pass runs at its integration rate, the accelerometer's on its samples.
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


# The film's mechanics, moved under `film` (FilmConfig) when the settings were nested by
# concern: assigning one here is refused naming its new path; scenario/moved_keys.py
# refuses and migrates the old keys of YAML from this table.
MOVED_TO_FILM = ("mode_frequency_hz", "mode_damping_ratio", "mode_mass_kg", "load_lowpass_hz",
                 "impact_enabled", "pad_contact_stiffness_n_per_m", "pad_dissipation_s_per_m",
                 "film_charge_gain_c_per_m", "feedback_capacitance_f")
register_moved_fields(VibrationSensorConfig, {name: f"film.{name}" for name in MOVED_TO_FILM})


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
    """The Gaussian noise [V rms] added to each film sample ahead of the readout."""
    return noise_at_amplifier_v(config.noise_std_mps2, config.adc_noise_lsb,
                                volts_per_mps2(config), adc_input(config.adc_input))


def ra_noise_std_mps2(config: VibrationSensorConfig) -> float:
    """The RA channel's noise at rest [m/s^2 rms], in closed form from the electronics:
    the film's readout (film_readout.reading_noise_std), or the accelerometer's own noise."""
    if config.transducer != "film":
        return config.noise_std_mps2
    return reading_noise_std(config.noise_std_mps2, config.adc_noise_lsb,
                             volts_per_mps2(config), adc_input(config.adc_input))


# How far the accelerometer transducer's Gaussian noise can carry one reading, in noise sigmas
# (a trial logs at most 2 pads x 20 kHz x 85 s = 3.4e6 readings; 10 sigma, 7.6e-24 a reading
# on one side, is never reached by noise).
PAD_NOISE_SIGMAS = 10.0


def pad_reading_bound_mps2(config: VibrationSensorConfig, *, time_step_s: float,
                           pad_speed_mps: float) -> float:
    """The largest |reading| [m/s^2] a pad's RA transducer of `config` logs (each of its 3
    axes). The film's: its readout's full scale, the amplifier's swing or the converter's
    last code over the sensitivity S (film_readout.reading_mps2 of an unbounded
    acceleration). The accelerometer's (no electronics): a first-order high-pass of the pad
    frame's acceleration, at most twice its input's largest (y = u - a low-pass of u); in a
    plant of step time_step_s [s] the pad's velocity changes in one step by at most twice
    pad_speed_mps [m/s] (the fastest the pad moves, reversed), and gravity is read too; plus
    PAD_NOISE_SIGMAS of noise."""
    if config.transducer == "film":
        sensitivity, adc = volts_per_mps2(config), adc_input(config.adc_input)
        return max(abs(reading_mps2(value, 0.0, sensitivity, config.amplifier_swing_v, adc))
                   for value in (-math.inf, math.inf))
    from pydrake.multibody.tree import UniformGravityFieldElement  # the plant's gravity
    largest = 2.0 * pad_speed_mps / time_step_s + UniformGravityFieldElement.kDefaultStrength
    return 2.0 * largest + PAD_NOISE_SIGMAS * config.noise_std_mps2

