"""Calibration of the tactile pads: AD7147 counts to newtons, piezo samples to m/s^2.

Capacitive taxels (SA): a pressed pad brings the fabric closer to the electrodes, so
Delta C = eps A (1/d1 - 1/d0) grows and the AD7147 count moves from its baseline. Over the
working range we use a per-taxel line,

    F_k = max(0, gain_k * (counts_k - offset_k))        [N]

with `gain` [N/count] from a bench calibration (weights on each taxel) and `offset`
[counts] the no-contact baseline, which drifts with temperature and mounting and is
therefore re-estimated at start ("zeroing": the mean of the first `zero_samples` count
sequences per finger, taken with nothing touching the pads).

Piezo film (RA): the charge amplifier gives V = -Q / C_f, proportional to the film's
strain rate, a high-pass image of the pad's vibration. It is scaled into an
acceleration-equivalent so that Eq. 2 and the memorized events see the units they were
recorded in:

    a = piezo_gain * (counts * volts_per_count - piezo_offset)   [m/s^2]

with `piezo_offset` [V] zeroed at start like the taxels. The film has one axis: the
receiver puts `a` in x of the pad's 3-vector and zeros in y, z, so Eq. 2 gives |a|.

The default gains are placeholders of the right order (1 mN per count, 30000-count
baseline); a real pad's numbers go in a YAML file loaded with `LoadTactileCalibration`. The
default piezo gain is the simulated film's, 1 / S = 253 (m/s^2)/V with S = G_Q / (w^2 C_f)
its mid-band sensitivity to base acceleration (simulation/pad_vibration_sensor.py,
docs/model.md "Vibration (RA) model"), so that a recorded simulation replays through the emulated myRIO
within the +-10 V input range. For a real pad, S is measured: shake the finger at a known
acceleration between the amplifier's high-pass and the fingertip's mode (e.g. 10-100 Hz)
and read the voltage.
"""

import dataclasses

import numpy as np
from pydrake.common.yaml import yaml_dump_typed

from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.hardware.myrio.tactile_frame import PIEZO_VOLTS_PER_COUNT

COUNT_MAX = 65535
PIEZO_COUNT_LIMIT = 32767


@dataclasses.dataclass
class PadCalibration:
    """One finger's pad."""
    gain: list[float] = dataclasses.field(
        default_factory=lambda: [1e-3] * TAXELS_PER_PAD)          # [N/count]
    offset: list[float] = dataclasses.field(
        default_factory=lambda: [30000.0] * TAXELS_PER_PAD)       # [counts]
    piezo_gain: float = 253.0   # [(m/s^2)/V], 1 / S of the simulated film
    piezo_offset: float = 0.0   # [V]


@dataclasses.dataclass
class TactileCalibration:
    """Both pads, and how many count sequences to average when zeroing (0: never)."""
    left: PadCalibration = dataclasses.field(default_factory=PadCalibration)
    right: PadCalibration = dataclasses.field(default_factory=PadCalibration)
    zero_samples: int = 32
    piezo_volts_per_count: float = PIEZO_VOLTS_PER_COUNT

    def pads(self) -> tuple[PadCalibration, PadCalibration]:
        """(left, right), in `channels.FINGER_NAMES` order."""
        return self.left, self.right


def LoadTactileCalibration(filename: str) -> TactileCalibration:
    """Reads a TactileCalibration from YAML (fields as in the dataclasses). ConfigError, one
    line naming the file and the field, for anything that is not one: a missing or empty
    file, a FIFO or device (refused before a byte is read), a file too large, bad YAML, an
    unknown or non-finite field."""
    from tegrasp_drake.rig.typed_yaml import ConfigError, load_typed, read_yaml_file
    data = read_yaml_file(filename, "the tactile calibration")
    if data is None:
        raise ConfigError(f"{filename}: the tactile calibration is empty; give the pads' "
                          "gains and offsets (left, right, zero_samples), or no file for "
                          "the defaults")
    if not isinstance(data, dict):
        raise ConfigError(f"{filename}: the tactile calibration must be a mapping of "
                          "fields (left, right, zero_samples, piezo_volts_per_count), got "
                          f"a {type(data).__name__}")
    data.pop("_tag", None)
    return load_typed(data, TactileCalibration, str(filename))


def SaveTactileCalibration(calibration: TactileCalibration, filename: str):
    """Writes a TactileCalibration as YAML."""
    with open(filename, "w", encoding="utf-8") as file:
        file.write(yaml_dump_typed(calibration))


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
