"""Calibration of the tactile pads: AD7147 counts to taxel forces [N], piezo samples to an
acceleration-equivalent [m/s^2] (the film's one axis, in x of the pad frame):

    F_k = max(0, gain_k * (counts_k - offset_k))
    a = piezo_gain * (counts * volts_per_count - piezo_offset)

Offsets are re-estimated at start (zeroing); gains come from a YAML file
(hardware/myrio/TACTILE_FRAME.md, "Calibration")."""

import dataclasses

import numpy as np
from pydrake.common.yaml import yaml_dump_typed

from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.rig.files import write_atomically
from tegrasp_drake.rig.ranges import bounded, check_ranges
from tegrasp_drake.hardware.myrio.tactile_frame import PIEZO_VOLTS_PER_COUNT

COUNT_MAX = 65535
PIEZO_COUNT_LIMIT = 32767


# The most force one AD7147 count may stand for [N/count]: at 0.1 N/count the counts above a
# mid-range offset (about 35,000) span 3,500 N, 15 times the 2F-85's whole grip (235 N, its
# manual) on one taxel; a larger gain is a unit slip (newtons per kilocount, or per volt).
MAX_TAXEL_GAIN_N_PER_COUNT = 0.1
# The myRIO's piezo input: +-10 V (PIEZO_VOLTS_PER_COUNT over the signed 16-bit count).
PIEZO_INPUT_V = PIEZO_VOLTS_PER_COUNT * (PIEZO_COUNT_LIMIT + 1)
# The film's gain, 1 / S [(m/s^2)/V]. A free PVDF film on the fingertip reads S = 3.96e-3 V
# per m/s^2 (docs/model.md, the RA model's film sensitivity), a bonded one 3-30 times
# less: 1 / S of 253-7,600. Below 1, S would be 250 times the free film's; above 1e5 the
# +-10 V input would span 1e6 m/s^2. Either is a unit slip (per millivolt, per kilovolt).
MIN_PIEZO_GAIN = 1.0
MAX_PIEZO_GAIN = 1.0e5
# The most count sequences zeroing may average: one arrives per ~9.2 ms (TACTILE_FRAME.md),
# so 65,000 take 600 s, the longest ready_timeout (HardwareStationConfig).
MAX_ZERO_SAMPLES = 65_000


@dataclasses.dataclass
class PadCalibration:
    """One finger's pad."""
    gain: list[float] = bounded(  # [N/count] placeholder; bench-calibrate
        default_factory=lambda: [1e-3] * TAXELS_PER_PAD, low=0.0, low_open=True,
        high=MAX_TAXEL_GAIN_N_PER_COUNT, unit="N/count", length=TAXELS_PER_PAD,
        why="a press reads as a push; 0.1 N/count spans 15 times the 2F-85's grip on one "
            "taxel, so more is a unit slip")
    offset: list[float] = bounded(  # [counts] mid-range; zeroed at start
        default_factory=lambda: [30000.0] * TAXELS_PER_PAD, low=0.0, high=COUNT_MAX,
        unit="counts", length=TAXELS_PER_PAD, why="the AD7147's 16-bit conversion result")
    # [(m/s^2)/V], 1 / S of the simulated film (docs/model.md)
    piezo_gain: float = bounded(
        253.0, low=MIN_PIEZO_GAIN, high=MAX_PIEZO_GAIN, unit="(m/s^2)/V",
        why="1 / the film's sensitivity: below, a film 250 times as sensitive as a free "
            "one; above, the +-10 V input spans 100,000 g; either is a unit slip")
    piezo_offset: float = bounded(0.0, low=-PIEZO_INPUT_V, high=PIEZO_INPUT_V, unit="V",
                                  why="the myRIO's piezo input range")


@dataclasses.dataclass
class TactileCalibration:
    """Both pads, and how many count sequences to average when zeroing (0: never)."""
    left: PadCalibration = dataclasses.field(default_factory=PadCalibration)
    right: PadCalibration = dataclasses.field(default_factory=PadCalibration)
    zero_samples: int = bounded(
        32, low=0, high=MAX_ZERO_SAMPLES, unit="sequences",
        why="one per ~9.2 ms (TACTILE_FRAME.md): 65,000 take 600 s, the longest ready_timeout")
    piezo_volts_per_count: float = bounded(
        PIEZO_VOLTS_PER_COUNT, low=0.0, low_open=True, high=PIEZO_VOLTS_PER_COUNT, unit="V",
        why="the myRIO's widest piezo input, +-10 V over the signed 16-bit count")

    def pads(self) -> tuple[PadCalibration, PadCalibration]:
        """(left, right), in `channels.FINGER_NAMES` order."""
        return self.left, self.right


def LoadTactileCalibration(filename: str) -> TactileCalibration:
    """Reads a TactileCalibration from YAML; otherwise a ConfigError naming the file and field."""
    from tegrasp_drake.rig.typed_yaml import (ConfigError, ForeignTagError, load_typed,
                                              parse_yaml_file, read_yaml_text,
                                              require_known_keys, require_mapping)
    # A field names the file, which may be any file the user can read: what is wrong with
    # one that is no calibration is said without showing its content.
    advice = "give a calibration SaveTactileCalibration wrote, or no file for the defaults"
    text = read_yaml_text(filename, "the tactile calibration")
    try:
        data = parse_yaml_file(text, filename, "the tactile calibration",
                               kind=TactileCalibration)
    except ForeignTagError:
        raise
    except ConfigError as e:  # its words may quote the text (a key, a token); where may not
        where = f" {e.where}:" if e.where else ""
        raise ConfigError(f"{filename}:{where} is not a tactile calibration (its {len(text)} "
                          f"characters are refused as YAML): {advice}") from None
    if data is None:
        raise ConfigError(f"{filename}: the tactile calibration is empty; give the pads' "
                          "gains and offsets (left, right, zero_samples), or no file for "
                          "the defaults")
    require_mapping(data, filename, "the tactile calibration",
                    "fields (left, right, zero_samples, piezo_volts_per_count)", echo=False)
    require_known_keys(data, TactileCalibration, filename, "a tactile calibration", advice)
    calibration = load_typed(data, TactileCalibration, str(filename))
    check_ranges(calibration, str(filename))
    return calibration


# The first line SaveTactileCalibration writes (a YAML comment): how a calibration file, and
# a killed writer's staging file of one, starts (write_atomically's `start`).
CALIBRATION_FILE_START = b"# tactile calibration"


def SaveTactileCalibration(calibration: TactileCalibration, filename: str):
    """Writes a TactileCalibration as YAML, under a first comment line, atomically (an
    earlier file stays whole until the new one is complete)."""
    write_atomically(filename, CALIBRATION_FILE_START.decode() + " (gains N/count, offsets "
                     "counts: LoadTactileCalibration)\n" + yaml_dump_typed(calibration),
                     start=CALIBRATION_FILE_START)


def forces_from_counts(counts, gain, offset) -> np.ndarray:
    """Taxel normal forces [N] from AD7147 counts (negative forces clip to zero)."""
    return np.maximum(np.asarray(gain) * (np.asarray(counts, dtype=float)
                                          - np.asarray(offset)), 0.0)


def counts_from_forces(forces, gain, offset) -> np.ndarray:
    """The inverse, rounded to the u16 counts a CDC would report (for the emulator)."""
    counts = np.asarray(offset) + np.asarray(forces, dtype=float) / np.asarray(gain)
    return np.clip(np.rint(counts), 0, COUNT_MAX).astype(np.int64)


def acceleration_from_piezo(counts, volts_per_count, piezo_gain, piezo_offset):
    """Acceleration-equivalent [m/s^2] of piezo samples [counts]."""
    return piezo_gain * (np.asarray(counts, dtype=float) * volts_per_count - piezo_offset)


def piezo_from_acceleration(acceleration, volts_per_count, piezo_gain, piezo_offset):
    """The inverse, rounded to i16 samples (for the emulator)."""
    volts = np.asarray(acceleration, dtype=float) / piezo_gain + piezo_offset
    return np.clip(np.rint(volts / volts_per_count), -PIEZO_COUNT_LIMIT - 1,
                   PIEZO_COUNT_LIMIT).astype(np.int64)


@dataclasses.dataclass(frozen=True)
class PadZeroing:
    """Running sums for one pad's zeroing (immutable: `add` returns a new one)."""
    count_sum: tuple = (0.0,) * TAXELS_PER_PAD
    count_samples: int = 0
    piezo_sum: float = 0.0
    piezo_samples: int = 0

    def add(self, counts, piezo_volts) -> "PadZeroing":
        """Adds one frame's counts (or None) and piezo sample [V]."""
        count_sum, count_samples = self.count_sum, self.count_samples
        if counts is not None:
            count_sum = tuple(np.add(count_sum, counts))
            count_samples += 1
        return PadZeroing(count_sum, count_samples, self.piezo_sum + piezo_volts,
                          self.piezo_samples + 1)

    def done(self, zero_samples: int) -> bool:
        return self.count_samples >= zero_samples

    def zeroed(self, pad: PadCalibration) -> PadCalibration:
        """The pad's calibration with the offsets replaced by the means seen."""
        return dataclasses.replace(
            pad, offset=list(np.divide(self.count_sum, max(self.count_samples, 1))),
            piezo_offset=self.piezo_sum / max(self.piezo_samples, 1))
