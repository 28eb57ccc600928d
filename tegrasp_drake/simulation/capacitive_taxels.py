"""The real pad's SA transducer: each taxel a parallel-plate capacitor read by an AD7147
(paper, Sec. IV-A): Delta C = eps_r eps_0 A (1/d1 - 1/d0), d1 = d0 - d0 p / E under the
taxel's mean pressure p = F / A. The AD7147 reports Delta C in whole 16-bit counts with
noise; the station reports counts above baseline or, by default, newtons through the
hardware's per-taxel calibration (hardware/myrio/tactile_calibration.py). Numbers and
sources: docs/model.md, "The capacitive taxel"."""

import dataclasses

import numpy as np
from pydrake.common import RandomDistribution
from pydrake.systems.framework import LeafSystem
from pydrake.systems.primitives import RandomSource

from tegrasp_drake.rig.ranges import bounded, chosen
from tegrasp_drake.rig.tactile_fingertip import PAD_THICKNESS
from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y
from tegrasp_drake.rig.api_boundary import public_dataclass

VACUUM_PERMITTIVITY_F_PER_M = 8.8541878128e-12
TAXEL_TRANSDUCERS = ("force", "capacitive")
CAPACITIVE_OUTPUTS = ("calibrated", "counts")
# AD7147 data sheet: a 16-bit CDC over +-8 pF, 4096 counts per pF (0.244 fF a count); no
# touch reads mid-scale once the offset DACs trim the stray capacitance.
AD7147_COUNTS_PER_PF = 65536 / 16.0
AD7147_BASELINE_COUNTS = 32768
AD7147_MAX_COUNTS = 65535
# AD7147 data sheet: up to 12 conversion stages, each 0.768 ms at decimation 64 and twice or
# four times that at 128 or 256; a pad's 12 taxels are its 12 stages, one after the other.
AD7147_DECIMATIONS = (64, 128, 256)
AD7147_STAGES = 12
AD7147_STAGE_S_AT_64 = 0.768e-3
# A sample rate within this fraction of the frame rate matches the decimation (the data
# sheet's stage time is typical and the rates are quoted rounded).
FRAME_RATE_TOLERANCE = 0.01


def ad7147_stage_s(decimation: int) -> float:
    """One conversion stage [s] at `decimation` (64, 128 or 256)."""
    return AD7147_STAGE_S_AT_64 * decimation / 64


def ad7147_frame_rate_hz(decimation: int) -> float:
    """Frames per second [Hz] of the 12-stage sequence at `decimation`: 108.5, 54.3, 27.1."""
    return 1.0 / (AD7147_STAGES * ad7147_stage_s(decimation))


def frame_rate_matches(sample_rate_hz: float, decimation: int) -> bool:
    """Whether `sample_rate_hz` is the AD7147's frame rate at `decimation` (within tolerance)."""
    frame = ad7147_frame_rate_hz(decimation)
    return abs(sample_rate_hz - frame) <= FRAME_RATE_TOLERANCE * frame


@public_dataclass
@dataclasses.dataclass
class CapacitiveTaxelConfig:
    """The capacitive taxel's parameters (used when `tactile.transducer` is capacitive)."""
    # PDMS (Dow Sylgard 184 data sheet, 2.72); assumed: the paper does not name its elastomer.
    relative_permittivity: float = bounded(2.7, low=1.0, high=100.0,
                                           why="elastomers lie at 2-10; 100 bounds any dielectric "
                                               "a pad is made of",
                                           below="must be at least 1 (vacuum)")
    # Noise per reading at decimation 64 (assumed, of the AD7147 data sheet's order: about
    # 1 fF resolved, 4 counts); it shrinks as sqrt(64 / decimation).
    noise_std_counts: float = bounded(4.0, low=0.0, high=10_000.0, unit="counts",
                                      why="the AD7147's 16-bit reading",
                                      below="must be zero (no noise) or positive")
    # The AD7147's decimation: frames at 108, 54 or 27 Hz (ad7147_frame_rate_hz), which
    # tactile.sample_rate_hz must match unless ad7147_timing is false (a counterfactual
    # readout at any rate, as the transfer study's 1 kHz worlds use).
    decimation: int = chosen(64, names=AD7147_DECIMATIONS, why="the AD7147's, AD7147 data sheet")
    ad7147_timing: bool = True
    # The elastomer stops compressing at this fraction of its thickness (assumed: the
    # grasps here compress it by 2-30 %).
    minimum_gap_fraction: float = bounded(0.1, low=0.01, high=1.0, high_open=True,
                                          why="an elastomer compresses by at most 99 % of its "
                                              "thickness")
    output: str = chosen("calibrated", names=CAPACITIVE_OUTPUTS,
                         why="newtons, or counts above the baseline")
    # The bench calibration's one point [N on a taxel]: a 0.5 kg weight, within the 1-10 N a
    # taxel carries in 25-100 N grasps.
    calibration_force_n: float = bounded(5.0, low=0.1, high=100.0, unit="N",
                                         why="a calibration weight of at least 10 g; lighter, "
                                             "its change is within the taxel's noise")


def noise_std_at_decimation(config: CapacitiveTaxelConfig) -> float:
    """Counts of noise per reading at the config's decimation (sqrt(64 / decimation) x)."""
    return config.noise_std_counts * (64.0 / config.decimation) ** 0.5


def electrode_area_m2() -> float:
    """A taxel electrode's area [m^2]: one cell of the pad's taxel grid."""
    return CELL_X * CELL_Y


def taxel_compression_m(forces_n, config: CapacitiveTaxelConfig, *,
                        pad_modulus_pa: float) -> np.ndarray:
    """Each taxel's elastomer compression [m] under its normal force [N]: d0 p / E, p the
    taxel's mean pressure, E the pad's modulus (tactile.pad_modulus_pa) [Pa]; zero for no
    (or negative) force, at most (1 - minimum gap) d0."""
    pressure = np.maximum(np.asarray(forces_n, dtype=float), 0.0) / electrode_area_m2()
    return np.minimum(PAD_THICKNESS * pressure / pad_modulus_pa,
                      (1.0 - config.minimum_gap_fraction) * PAD_THICKNESS)


def capacitance_change_f(compression_m, relative_permittivity: float) -> np.ndarray:
    """Delta C = eps_r eps_0 A (1/d1 - 1/d0) [F], d1 = d0 - compression."""
    d0 = PAD_THICKNESS
    d1 = d0 - np.asarray(compression_m, dtype=float)
    return (relative_permittivity * VACUUM_PERMITTIVITY_F_PER_M * electrode_area_m2()
            * (1.0 / d1 - 1.0 / d0))


def counts_above_baseline(forces_n, config: CapacitiveTaxelConfig, noise_counts=0.0, *,
                          pad_modulus_pa: float) -> np.ndarray:
    """The AD7147's reading of each taxel, counts above its baseline: Delta C in counts
    plus noise, rounded to whole counts, clipped to the 16-bit range (pad_modulus_pa [Pa])."""
    delta_c = capacitance_change_f(
        taxel_compression_m(forces_n, config, pad_modulus_pa=pad_modulus_pa),
        config.relative_permittivity)
    counts = np.rint(delta_c * 1e12 * AD7147_COUNTS_PER_PF + noise_counts)
    return np.clip(counts, -AD7147_BASELINE_COUNTS,
                   AD7147_MAX_COUNTS - AD7147_BASELINE_COUNTS)


def calibration_gain_n_per_count(config: CapacitiveTaxelConfig, *,
                                 pad_modulus_pa: float) -> float:
    """The calibration line's gain [N/count]: the bench force over its noise-free counts
    (pad_modulus_pa [Pa]: a stiffer pad compresses less, so a count is more newtons)."""
    delta_c = capacitance_change_f(
        taxel_compression_m(config.calibration_force_n, config, pad_modulus_pa=pad_modulus_pa),
        config.relative_permittivity)
    return config.calibration_force_n / float(delta_c * 1e12 * AD7147_COUNTS_PER_PF)


def capacitive_readings(forces_n, config: CapacitiveTaxelConfig, noise_counts=0.0, *,
                        pad_modulus_pa: float) -> np.ndarray:
    """What the station reports for true taxel forces [N]: calibrated newtons (clipped at
    zero, as the hardware's calibration does) or counts above the baseline, the elastomer
    of modulus pad_modulus_pa [Pa]."""
    counts = counts_above_baseline(forces_n, config, noise_counts,
                                   pad_modulus_pa=pad_modulus_pa)
    if config.output == "counts":
        return counts
    return np.maximum(
        calibration_gain_n_per_count(config, pad_modulus_pa=pad_modulus_pa) * counts, 0.0)


class CapacitiveTaxels(LeafSystem):
    """Both pads' capacitive taxels: the true taxel forces as an AD7147 reads them.

    .. pydrake_system::

        name: CapacitiveTaxels
        input_ports:
        - true_taxel_forces
        - noise (optional)
        output_ports:
        - left_taxel_forces
        - right_taxel_forces

    Ports: true_taxel_forces (24, N, left then right, held at the taxel rate); noise (24 unit
    Gaussians at the taxel rate, when noise_std_counts > 0); the outputs: 12 readings each,
    newtons or counts (config.output), of an elastomer of modulus pad_modulus_pa [Pa]. No
    state: they change when a taxel sample is taken.
    """

    def __init__(self, *, config: CapacitiveTaxelConfig, pad_modulus_pa: float):
        super().__init__()
        self._config = config
        self._pad_modulus_pa = pad_modulus_pa
        size = TAXELS_PER_PAD * len(FINGER_NAMES)
        self._forces = self.DeclareVectorInputPort("true_taxel_forces", size)
        self._noise = (self.DeclareVectorInputPort("noise", size)
                       if config.noise_std_counts > 0 else None)
        self._noise_std = noise_std_at_decimation(config)
        # The readings depend on the inputs alone: recomputed only when a sample changes.
        inputs = {port.ticket() for port in (self._forces, self._noise) if port is not None}
        for k, finger in enumerate(FINGER_NAMES):
            self.DeclareVectorOutputPort(
                f"{finger}_taxel_forces", TAXELS_PER_PAD,
                lambda context, output, k=k: output.SetFromVector(
                    self._readings(context)[k * TAXELS_PER_PAD:(k + 1) * TAXELS_PER_PAD]),
                prerequisites_of_calc=inputs)

    def _readings(self, context) -> np.ndarray:
        noise = 0.0
        if self._noise is not None:
            noise = self._noise_std * self._noise.Eval(context)
        return capacitive_readings(self._forces.Eval(context), self._config, noise,
                                   pad_modulus_pa=self._pad_modulus_pa)


def AddTaxelTransducer(builder, *, taxels, tactile_config, name: str = "capacitive_taxels"):
    """The system whose `<finger>_taxel_forces` are the station's taxel readings: `taxels`
    for the force transducer, else a CapacitiveTaxels fed by its true forces."""
    if tactile_config.transducer == "force":
        return taxels
    config = tactile_config.capacitive
    readings = builder.AddNamedSystem(name, CapacitiveTaxels(
        config=config, pad_modulus_pa=tactile_config.pad_modulus_pa))
    builder.Connect(taxels.GetOutputPort("true_taxel_forces"),
                    readings.GetInputPort("true_taxel_forces"))
    if config.noise_std_counts > 0:
        noise = builder.AddNamedSystem(f"{name}_noise", RandomSource(
            RandomDistribution.kGaussian, TAXELS_PER_PAD * len(FINGER_NAMES),
            1.0 / tactile_config.sample_rate_hz))
        builder.Connect(noise.get_output_port(), readings.GetInputPort("noise"))
    return readings
