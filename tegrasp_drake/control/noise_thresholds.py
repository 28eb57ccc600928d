"""The RA and SA thresholds raised to the channels' noise: each threshold in force is max(number,
sigmas x sigma), sigma the channel's noise at rest in closed form, the sigmas chosen so that noise
alone crosses it in at most FALSE_ALARM_PER_TRIAL of trials. Reasoning and values: docs/model.md,
"Thresholds in noise sigmas" and "SA thresholds against the taxels' noise"."""

import dataclasses

import numpy as np
from scipy import signal
from scipy.stats import chi2, norm

from tegrasp_drake.events.ra_noise_floor import FALSE_ALARM_PER_TRIAL, TRIAL_HORIZON_S
from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.simulation.taxel_rest_noise import loaded_noise, rest_reading
from tegrasp_drake.tactile.slip_vibration_band import highpass_biquad

PADS = 2


def magnitude_sigmas(false_alarm_per_trial: float, samples_per_trial: int) -> float:
    """k such that |Gaussian noise| crosses k sigma with probability at most
    false_alarm_per_trial over samples_per_trial samples (union bound, both tails)."""
    return float(norm.isf(false_alarm_per_trial / (2.0 * samples_per_trial)))


def window_rms_sigmas(false_alarm_per_trial: float, windows_per_trial: int,
                      window_samples: int) -> float:
    """k such that the RMS of window_samples independent Gaussian samples crosses k sigma
    with probability at most false_alarm_per_trial over windows_per_trial windows."""
    quantile = chi2.isf(false_alarm_per_trial / windows_per_trial, window_samples)
    return float(np.sqrt(quantile / window_samples))


def slip_band_noise_std(ra_noise_std_mps2: float, band_hz: float, rate_hz: float) -> float:
    """The slip band's noise per sample [m/s^2 rms] for white RA noise of ra_noise_std_mps2:
    times the high-pass's white-noise gain sqrt(sum h_k^2)."""
    c = highpass_biquad(band_hz, rate_hz)
    impulse = np.zeros(max(64, int(rate_hz)))  # 1 s: the response has long died out
    impulse[0] = 1.0
    h = signal.lfilter(c[:3], [1.0, c[3], c[4]], impulse)
    return float(ra_noise_std_mps2 * np.sqrt(np.sum(h * h)))


def default_rule_sigmas(ra_rate_hz: float = 1000.0, window_samples: int = 10):
    """(magnitude k, band RMS k) of the module docstring's rule at ra_rate_hz [Hz]."""
    samples = int(TRIAL_HORIZON_S * ra_rate_hz) * PADS
    return (magnitude_sigmas(FALSE_ALARM_PER_TRIAL, samples),
            window_rms_sigmas(FALSE_ALARM_PER_TRIAL, samples, window_samples))


@dataclasses.dataclass(frozen=True)
class SaNoiseFloors:
    """The forces noise alone exceeds by the rule [N, or counts for a counts output]."""
    pad_sum: float        # Eq. 1's sum of one pad at rest
    taxel: float          # one taxel's reading at rest
    pad_asymmetry: float  # |difference of the two pads' SA gains|, both pads loaded
    held_margin: float    # how far above contact_force_n a pad must read to lift (held_margin)


def sa_noise_floors(tactile_config, sa_rate_hz: float) -> SaNoiseFloors:
    """SaNoiseFloors of a TactileSensorConfig read at sa_rate_hz [Hz] (module docstring)."""
    samples = int(TRIAL_HORIZON_S * sa_rate_hz)
    reading = rest_reading(tactile_config)
    asymmetry_std = np.sqrt(4 * TAXELS_PER_PAD) * loaded_noise(tactile_config).std()
    return SaNoiseFloors(
        pad_sum=reading.sum_of(TAXELS_PER_PAD).exceeded_with(
            FALSE_ALARM_PER_TRIAL / (samples * PADS)),
        taxel=reading.exceeded_with(FALSE_ALARM_PER_TRIAL / (samples * PADS * TAXELS_PER_PAD)),
        pad_asymmetry=float(norm.isf(FALSE_ALARM_PER_TRIAL / 2.0) * asymmetry_std),
        held_margin=held_margin(tactile_config, samples))


def held_margin(tactile_config, samples_per_trial: int) -> float:
    """How far above the drop check's pad sum [N] one reading of each pad must lie to lift.

    The drop check calls the object lost at the first sample both pads read at or below it; a
    held pad reads its force plus the loaded noise, sigma = sqrt(12) x a taxel's (1.06 N on
    the capacitive pad), the pads independent. A grip whose force lies z_hold sigma above it
    leaves both pads below it in at most FALSE_ALARM_PER_TRIAL of trials of samples_per_trial
    samples: Phi(-z_hold)^2 samples <= FALSE_ALARM_PER_TRIAL. The lift decides on one reading
    per pad: a grip weaker than that reads z_read sigma more, either pad, in at most
    FALSE_ALARM_PER_TRIAL of lifts. The margin is (z_hold + z_read) sigma."""
    sigma = np.sqrt(TAXELS_PER_PAD) * loaded_noise(tactile_config).std()
    z_hold = norm.isf(np.sqrt(FALSE_ALARM_PER_TRIAL / samples_per_trial))
    z_read = norm.isf(FALSE_ALARM_PER_TRIAL / PADS)
    return float((z_hold + z_read) * sigma)


def _sa_changes(config, floors: SaNoiseFloors) -> dict:
    contact_force_n = max(config.contact_force_n, floors.pad_sum)
    changes = {"contact_force_n": contact_force_n,
               "taxel_contact_n": max(config.taxel_contact_n, floors.taxel),
               "avoid": dataclasses.replace(config.avoid, sa_asymmetry_n=max(
                   config.avoid.sa_asymmetry_n, floors.pad_asymmetry))}
    heuristic = getattr(config, "heuristic", None)
    if heuristic is not None:
        changes["heuristic"] = dataclasses.replace(
            heuristic, contact_force_n=max(heuristic.contact_force_n, floors.pad_sum))
    taxel_aware = getattr(config, "taxel_aware", None)
    if taxel_aware is not None:
        changes["taxel_aware"] = dataclasses.replace(taxel_aware, lift_pad_sum_n=max(
            taxel_aware.lift_pad_sum_n, contact_force_n + floors.held_margin))
    return changes


def resolve_noise_thresholds(config, *, ra_noise_std_mps2: float, ra_rate_hz: float,
                             tactile=None, sa_rate_hz: float | None = None):
    """A copy of `config`, its RA thresholds raised for RA noise ra_noise_std_mps2 [m/s^2 rms] at
    ra_rate_hz [Hz] and, given `tactile` and config.sa_noise_floor, SA ones to sa_noise_floors."""
    avoid, lift_load = config.avoid, config.lift_load
    band = slip_band_noise_std(ra_noise_std_mps2, lift_load.slip_band_hz, ra_rate_hz)
    changes = {
        "avoid": dataclasses.replace(avoid, hit_ra_mps2=max(
            avoid.hit_ra_mps2, avoid.hit_ra_sigmas * ra_noise_std_mps2)),
        "lift_load": dataclasses.replace(lift_load, slip_vibration_mps2=max(
            lift_load.slip_vibration_mps2, lift_load.slip_vibration_sigmas * band))}
    heuristic = getattr(config, "heuristic", None)
    if heuristic is not None:
        changes["heuristic"] = dataclasses.replace(heuristic, place_ra_mps2=max(
            heuristic.place_ra_mps2, heuristic.place_ra_sigmas * ra_noise_std_mps2))
    taxel_aware = getattr(config, "taxel_aware", None)
    if taxel_aware is not None and taxel_aware.ra_onset_mps2 > 0.0:
        changes["taxel_aware"] = dataclasses.replace(taxel_aware, ra_onset_mps2=max(
            taxel_aware.ra_onset_mps2, taxel_aware.ra_onset_sigmas * ra_noise_std_mps2))
    resolved = dataclasses.replace(config, **changes)
    if tactile is None or not config.sa_noise_floor:
        return resolved
    return dataclasses.replace(resolved, **_sa_changes(resolved,
                                                       sa_noise_floors(tactile, sa_rate_hz)))
