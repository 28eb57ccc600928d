"""Cut memorized events out of a recorded ideal grasp (Sec. III-A of the paper): a
`window_s` window of every channel from `pre_transition_s` before each transition's physical
event, divided by its maximum. An RA window whose peak stays below the recording's noise
floor (ra_noise_floor.py) is stored as ones, a quiet template (beyond the paper;
docs/controller.md, "The paper's state machine")."""

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.events.memorized_event import MemorizedEvent, current_package_versions
from tegrasp_drake.tactile.sampling import samples_per_window
from tegrasp_drake.events.transitions import transition_order

DEFAULT_WINDOW_S = 0.5  # the paper's window (Sec. III-A)
# The event mid-window: as much of the state before it as after, so the event describes the
# change, not the state (a plateau-filled window would let a steady grip look like contact).
DEFAULT_PRE_TRANSITION_S = 0.25


@dataclasses.dataclass(frozen=True)
class TactileTrial:
    """The channels logged during one grasp (each value held until the next), and its
    transitions' physical-event times: t_sa (N,) [s], sa (N, 2) [N] [left, right]; t_ra (M,)
    [s], ra (M, 2) [m/s^2]; transition_times: {transition: time [s]}."""
    t_sa: np.ndarray
    sa: np.ndarray
    t_ra: np.ndarray
    ra: np.ndarray
    transition_times: Mapping[str, float]

    def __post_init__(self):
        for times_name, values_name in (("t_sa", "sa"), ("t_ra", "ra")):
            times = np.asarray(getattr(self, times_name), dtype=float)
            values = np.asarray(getattr(self, values_name), dtype=float)
            if times.ndim != 1 or len(times) < 2 or np.any(np.diff(times) <= 0.0):
                raise ValueError(f"{times_name} must be a strictly increasing 1-D array")
            if values.shape != (len(times), 2):
                raise ValueError(f"{values_name} has shape {values.shape}; expected "
                                 f"({len(times)}, 2) for [left, right]")
            if not (np.all(np.isfinite(times)) and np.all(np.isfinite(values))):
                raise ValueError(f"{times_name} and {values_name} must be finite")
            object.__setattr__(self, times_name, times)
            object.__setattr__(self, values_name, values)
        object.__setattr__(self, "transition_times", dict(self.transition_times))


def cut_window(times: np.ndarray, values: np.ndarray, *, start_s: float, rate_hz: float,
               length: int, what: str) -> np.ndarray:
    """Samples a log (times (N,), values (N, channels)) at start_s + k / rate_hz, k < length,
    holding the latest value -> (channels, length); ValueError naming `what` outside the log."""
    grid = start_s + np.arange(length) / rate_hz
    tolerance = 1e-6 / rate_hz  # of a sample period: float noise in the time stamps
    if grid[0] < times[0] - tolerance or grid[-1] > times[-1] + tolerance:
        raise ValueError(
            f"{what} needs the log from {grid[0]:.4f} s to {grid[-1]:.4f} s, but the log "
            f"covers {times[0]:.4f} s to {times[-1]:.4f} s; record a longer trial or move "
            "the window (pre_transition_s)")
    indices = np.searchsorted(times, grid + tolerance, side="right") - 1
    return np.asarray(values)[np.maximum(indices, 0)].T


def extract_memorized_events(
        trial: TactileTrial, *, object_name: str, sa_rate_hz: float, ra_rate_hz: float,
        window_s: float = DEFAULT_WINDOW_S,
        pre_transition_s: float = DEFAULT_PRE_TRANSITION_S, scenario: str = "",
        package_versions: Mapping[str, str] | None = None,
        object_description: Mapping | None = None,
        ra_floor: Sequence[float] | None = None) -> dict[str, MemorizedEvent]:
    """One max-normalised MemorizedEvent per transition of `trial`, in grasp order, at the
    memorized (= live) rates [Hz]; ra_floor: the recording's RA noise floor [m/s^2] or None.
    ValueError for an unknown transition, a window outside the log, or an all-zero channel."""
    versions = current_package_versions() if package_versions is None else package_versions
    events = {}
    for name in sorted(trial.transition_times, key=transition_order):
        time = float(trial.transition_times[name])
        start = time - pre_transition_s
        what = f"transition '{name}' at {time:.4f} s"
        sa = cut_window(trial.t_sa, trial.sa, start_s=start, rate_hz=sa_rate_hz,
                        length=samples_per_window(window_s, sa_rate_hz),
                        what=f"{what} (SA)")
        ra = cut_window(trial.t_ra, trial.ra, start_s=start, rate_hz=ra_rate_hz,
                        length=samples_per_window(window_s, ra_rate_hz),
                        what=f"{what} (RA)")
        if ra_floor is not None:
            ra = quiet_as_flat(ra, ra_floor)
        event = MemorizedEvent(
            object_name=object_name, transition=name, sa=normalize_by_max(sa),
            ra=normalize_by_max(ra), sa_rate_hz=sa_rate_hz, ra_rate_hz=ra_rate_hz,
            window_s=window_s, pre_transition_s=pre_transition_s, transition_time_s=time,
            scenario=scenario, package_versions=versions,
            object_description=object_description or {})
        problem = event.shape_problem()
        if problem:  # what the event files' reader refuses is never cut
            raise ValueError(f"{what}: {problem}")
        events[name] = event
    return events


def recording_ra_floor(trial: TactileTrial, *, quiet_s: float, sigmas: float) -> np.ndarray:
    """[left, right] RA noise floor m + k s [m/s^2] of the raw RA samples of the trial's
    first quiet_s [s] (the approach, pads untouched), k = sigmas (ra_noise_floor.py)."""
    quiet = trial.ra[trial.t_ra < trial.t_ra[0] + quiet_s].T
    if quiet.shape[1] < 2:
        raise ValueError(f"the RA noise floor needs at least 2 samples in the first "
                         f"{number_text(quiet_s)} s of the log")
    return quiet.mean(axis=1) + sigmas * quiet.std(axis=1)


def quiet_as_flat(ra: np.ndarray, floor: Sequence[float]) -> np.ndarray:
    """`ra` (channels, N) with each channel whose peak |value| is not above its `floor`
    replaced by ones: a flat window that expects no change (module doc)."""
    ra = np.array(ra, dtype=float)
    for channel, level in enumerate(floor):
        if np.max(np.abs(ra[channel])) <= level:
            ra[channel] = 1.0
    return ra
