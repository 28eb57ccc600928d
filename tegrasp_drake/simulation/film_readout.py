"""The film's electronics: the charge amplifier's output swing and the myRIO-1900's 12-bit
analog input (paper, Sec. IV-A), as pure functions. Per RA sample:

  V = clip(S a + n, -swing, +swing)   S [V/(m/s^2)], n Gaussian noise
  code = clip(round((V + offset) / lsb), low, high),   a_read = (code lsb - offset) / S

docs/model.md, "Vibration (RA) model" (Readout)."""

import dataclasses
import math
import typing

ADC_INPUTS = ("msp", "mxp", "ideal")


@dataclasses.dataclass(frozen=True)
class AdcInput:
    """One myRIO analog input range: codes, volts per code, and the shift to mid-range 0 V."""
    low_code: int
    high_code: int
    volts_per_code: float
    offset_v: float

    @property
    def lowest_v(self) -> float:
        return self.low_code * self.volts_per_code - self.offset_v

    @property
    def highest_v(self) -> float:
        return self.high_code * self.volts_per_code - self.offset_v


# NI myRIO-1900 User Guide and Specifications, "Converting Raw Data Values to Voltage": the MSP
# connector's differential +-10 V input, the MXP connectors' single-ended 0-5 V one.
MYRIO_INPUTS = {
    "msp": AdcInput(low_code=-2048, high_code=2047, volts_per_code=20.0 / 4096, offset_v=0.0),
    "mxp": AdcInput(low_code=0, high_code=4095, volts_per_code=5.0 / 4096, offset_v=2.5),
}


def adc_input(name: str) -> AdcInput | None:
    """The myRIO input range called `name` (ADC_INPUTS); None for "ideal" (no converter)."""
    if name == "ideal":
        return None
    return MYRIO_INPUTS[name]


@dataclasses.dataclass(frozen=True)
class Arithmetic:
    """The min, max and floor that `reading_mps2` uses: Python's on floats (FLOATS) or
    pydrake.symbolic's, so one function also writes the compiled readout."""
    min: typing.Callable
    max: typing.Callable
    floor: typing.Callable


FLOATS = Arithmetic(min=min, max=max, floor=math.floor)


def reading_mps2(value_mps2, noise_v, sensitivity_v_per_mps2: float, swing_v: float,
                 adc: AdcInput | None, arithmetic: Arithmetic = FLOATS):
    """What the host reads [m/s^2] for the film's value_mps2 plus noise_v [V] at the
    amplifier (module docstring); without a converter (adc None) the clipped voltage over S."""
    low, high, floor = arithmetic.min, arithmetic.max, arithmetic.floor
    volts = sensitivity_v_per_mps2 * value_mps2 + noise_v
    volts = low(high(volts, -swing_v), swing_v)
    if adc is None:
        return volts / sensitivity_v_per_mps2
    lsb = adc.volts_per_code
    code = floor((volts + adc.offset_v) / lsb + 0.5)
    code = low(high(code, adc.low_code), adc.high_code)
    return (code * lsb - adc.offset_v) / sensitivity_v_per_mps2


def noise_at_amplifier_v(noise_std_mps2: float, adc_noise_lsb: float,
                         sensitivity_v_per_mps2: float, adc: AdcInput | None) -> float:
    """The Gaussian noise [V rms] per sample: amplifier's and converter's, root-sum-square."""
    amplifier = noise_std_mps2 * sensitivity_v_per_mps2
    converter = 0.0 if adc is None else adc_noise_lsb * adc.volts_per_code
    return math.hypot(amplifier, converter)


def reading_noise_std(noise_std_mps2: float, adc_noise_lsb: float,
                      sensitivity_v_per_mps2: float, adc: AdcInput | None) -> float:
    """The reading's noise at rest [m/s^2 rms]: Gaussian noise plus rounding's lsb^2 / 12."""
    gaussian = noise_at_amplifier_v(noise_std_mps2, adc_noise_lsb, sensitivity_v_per_mps2,
                                    adc)
    rounding = 0.0 if adc is None else adc.volts_per_code / math.sqrt(12.0)
    return math.hypot(gaussian, rounding) / sensitivity_v_per_mps2
