"""The thresholds in units of the channels' noise, so that they follow the electronics.

RA, in sigmas of the film's noise:

Three triggers compare the film's reading with a number: the hit that starts Avoid
(`avoid.hit_ra_mps2`, raw RA magnitude), the heuristic controller's Place-Unload
(`heuristic.place_ra_mps2`, raw RA magnitude) and the slip that starts Lift-Load
(`lift_load.slip_vibration_mps2`, the slip band's RMS over
`lift_load.slip_window_s`). Each also has a setting in
sigmas of the noise it reads, and the threshold in force is the larger of the two:

    threshold = max(number, sigmas x sigma)

The number is what the signals need (the table touch, the hit, a normal lift's own band
reading); the sigmas keep noise alone from crossing it when the electronics are noisier
than those numbers allow.

sigma. The RA channel's noise at rest, sigma_RA, in closed form from the electronics
(simulation/pad_vibration_sensor.ra_noise_std_mps2: the amplifier's and the converter's
Gaussian noise and the converter's rounding, lsb^2 / 12); the slip band's, per sample,
sigma_RA times the band's white-noise gain sqrt(sum h_k^2), h the high-pass's impulse
response (`slip_band_noise_std`). Closed form rather than measured on the stream's first
seconds: what the pads read during the approach is the electronics' noise plus the arm's
motion and drive vibration (docs/model.md, "Drive vibration"), whose level depends on the
motion, not on the electronics; and the closed form is exact for the white part.

sigmas, by the rule of the RA noise floor (events/ra_noise_floor.py): noise alone crosses
the threshold in at most `FALSE_ALARM_PER_TRIAL` (1e-3) of trials, union-bounded over the
trial's horizon at the RA rate, both pads:

  - the raw magnitude |a| (hit, place): P(|n| > k sigma) = 2 Q(k) over N = 14 s x 1000 Hz
    x 2 samples: k = Q^-1(alpha / 2N) = 5.51 (`magnitude_sigmas`);
  - the band's RMS over W samples: W RMS^2 / sigma_band^2 is chi-square with W degrees of
    freedom (the band's samples taken as independent: its impulse response lasts about 3
    samples at 80 Hz and 1 kHz), so k = sqrt(chi2^-1(1 - alpha / N; W) / W) = 2.34 for
    W = 10 (`window_rms_sigmas`); the rule also asks the band to stay above for
    lift_load.slip_s, which only lowers the false alarms further.

SA, by the same rule on the exact distribution of the taxels' noise
(simulation/taxel_rest_noise.py; `sa_noise_floor` switches it off). Four settings compare
taxel readings with a force; each is raised to the force that noise alone exceeds with the
rule's probability:

  - a pad touches (`contact_force_n`, and the heuristic's Reach-Load
    `heuristic.contact_force_n`): Eq. 1's sum of a pad's 12 readings at rest, over the
    trial's SA samples of both pads. The capacitive pad's calibration clips each reading at
    zero, so its sum at rest has a mean of 1.46 N and noise alone reaches 5.5 N once a
    trial of a thousand, against 0.3 N asked;
  - a taxel counts toward a contact's shape (`taxel_contact_n`): one reading at rest, over
    the trial's samples of all 24 taxels;
  - the Avoid move's side (`avoid.sa_asymmetry_n`): the difference of the two pads' SA
    gains, each a loaded pad's sum now less its sum before the hit (48 loaded readings'
    noise, unclipped: Gaussian to within the lattice), once per Avoid: both tails,
    probability FALSE_ALARM_PER_TRIAL.
"""

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


def sa_noise_floors(tactile_config, sa_rate_hz: float) -> SaNoiseFloors:
    """SaNoiseFloors of a TactileSensorConfig read at sa_rate_hz [Hz] (module docstring)."""
    samples = int(TRIAL_HORIZON_S * sa_rate_hz)
    reading = rest_reading(tactile_config)
    asymmetry_std = np.sqrt(4 * TAXELS_PER_PAD) * loaded_noise(tactile_config).std()
    return SaNoiseFloors(
        pad_sum=reading.sum_of(TAXELS_PER_PAD).exceeded_with(
            FALSE_ALARM_PER_TRIAL / (samples * PADS)),
        taxel=reading.exceeded_with(FALSE_ALARM_PER_TRIAL / (samples * PADS * TAXELS_PER_PAD)),
        pad_asymmetry=float(norm.isf(FALSE_ALARM_PER_TRIAL / 2.0) * asymmetry_std))


def _sa_changes(config, floors: SaNoiseFloors) -> dict:
    changes = {"contact_force_n": max(config.contact_force_n, floors.pad_sum),
               "taxel_contact_n": max(config.taxel_contact_n, floors.taxel),
               "avoid": dataclasses.replace(config.avoid, sa_asymmetry_n=max(
                   config.avoid.sa_asymmetry_n, floors.pad_asymmetry))}
    heuristic = getattr(config, "heuristic", None)
    if heuristic is not None:
        changes["heuristic"] = dataclasses.replace(
            heuristic, contact_force_n=max(heuristic.contact_force_n, floors.pad_sum))
    return changes


def resolve_noise_thresholds(config, *, ra_noise_std_mps2: float, ra_rate_hz: float,
                             tactile=None, sa_rate_hz: float | None = None):
    """`config` (a GraspControllerConfig, perhaps with a `heuristic` section) with its RA
    thresholds raised to max(number, sigmas x sigma) for RA noise ra_noise_std_mps2
    [m/s^2 rms] at ra_rate_hz [Hz], and, given the taxels' TactileSensorConfig `tactile`
    read at sa_rate_hz [Hz] and config.sa_noise_floor, its SA thresholds raised to the
    noise's (sa_noise_floors); a new config, the caller's untouched."""
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
    resolved = dataclasses.replace(config, **changes)
    if tactile is None or not config.sa_noise_floor:
        return resolved
    return dataclasses.replace(resolved, **_sa_changes(resolved,
                                                       sa_noise_floors(tactile, sa_rate_hz)))
