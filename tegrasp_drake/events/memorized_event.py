"""A memorized tactile event: one object's four max-normalised channel windows around one
grasp transition, checked on construction. Files: event_file.py, events_folder.py, FORMAT.md."""

import dataclasses
import importlib.metadata
from collections.abc import Mapping

import numpy as np

import tegrasp_drake
from tegrasp_drake.rig.api_boundary import array_problem, check_field_values, public_dataclass
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import EVENT_WINDOW, SAMPLE_RATE, bounded, within
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS
from tegrasp_drake.rig.objects import (DESCRIPTION_FIELDS, description_problem,
                                       object_name_problem)
from tegrasp_drake.tactile.sampling import samples_per_window
from tegrasp_drake.events.transitions import transition_order

NORMALIZATION = "max"
_NORMALIZATION_TOLERANCE = 1e-9
# A reach_load SA window's mean fall through the transition, as a fraction of its peak, that
# no first contact shows (MemorizedEvent.falling_first_contact).
_FALL_OF_PEAK = 0.15


@public_dataclass
@dataclasses.dataclass(frozen=True, eq=False)
class MemorizedEvent:
    """The four channels of one object's tactile event around one grasp transition: sa, ra
    (2, window_s * rate) windows [left, right], each divided by its max |value|, starting
    `pre_transition_s` [s] before the physical event (at `transition_time_s` [s] in its trial)."""
    object_name: str
    transition: str
    sa: np.ndarray
    ra: np.ndarray
    sa_rate_hz: float = within(dataclasses.MISSING, SAMPLE_RATE)
    ra_rate_hz: float = within(dataclasses.MISSING, SAMPLE_RATE)
    window_s: float = within(0.5, EVENT_WINDOW)
    # [s] from the window's start to the transition, within the window
    pre_transition_s: float = bounded(0.25, low=0.0, unit="s")
    transition_time_s: float = bounded(0.0, low=0.0, unit="s",
                                       why="a time in its trial, which starts at 0")
    scenario: str = ""  # name or text of the scenario that produced the trial
    package_versions: Mapping[str, str] = dataclasses.field(default_factory=dict)
    # The object the event was felt on: {shape, size, mass, friction, file}
    # (rig/objects.object_description); {} when unknown (synthetic events in tests).
    object_description: Mapping = dataclasses.field(default_factory=dict)
    normalization: str = NORMALIZATION
    channel_names: tuple[str, ...] = CHANNEL_NAMES

    def __post_init__(self):
        check_field_values(self)  # types of the text fields, ranges of the numbers
        problem = object_name_problem(self.object_name)
        if problem:
            raise ValueError(f"MemorizedEvent: field 'object_name' {problem}")
        transition_order(self.transition)
        if tuple(self.channel_names) != CHANNEL_NAMES:
            raise ValueError(f"channels {list(self.channel_names)} must be "
                             f"{list(CHANNEL_NAMES)}")
        if self.normalization != NORMALIZATION:
            raise ValueError(f"normalisation '{self.normalization}' is not "
                             f"'{NORMALIZATION}'")
        if not 0.0 <= self.pre_transition_s <= self.window_s:
            raise ValueError(f"pre_transition_s {number_text(self.pre_transition_s)} must lie "
                             f"within the {number_text(self.window_s)} s window")
        for name, rate in (("sa", self.sa_rate_hz), ("ra", self.ra_rate_hz)):
            expected = (2, samples_per_window(self.window_s, rate))
            # Its shape before it is converted: a huge array is refused without a copy.
            problem = array_problem(getattr(self, name), expected)
            if problem:
                raise ValueError(f"'{name}' {problem}; "
                                 f"{number_text(self.window_s)} s at {number_text(rate)} Hz "
                                 f"for two fingers needs {expected}")
            window = np.array(getattr(self, name), dtype=float)
            if not np.all(np.isfinite(window)):
                raise ValueError(f"'{name}' holds non-finite values")
            peaks = np.max(np.abs(window), axis=1)
            if np.any((peaks != 0.0) & (np.abs(peaks - 1.0) > _NORMALIZATION_TOLERANCE)):
                raise ValueError(f"'{name}' is not normalised by its maximum "
                                 f"(max |value| per finger: {peaks.tolist()})")
            if name == "ra":
                _check_magnitudes(window)
            window.setflags(write=False)
            object.__setattr__(self, name, window)
        versions = dict(self.package_versions)
        if not all(isinstance(k, str) and isinstance(v, str) for k, v in versions.items()):
            raise ValueError("package_versions must map package names to version text")
        object.__setattr__(self, "package_versions", versions)
        object.__setattr__(self, "channel_names", tuple(self.channel_names))
        description = dict(self.object_description)
        if description and sorted(description) != sorted(DESCRIPTION_FIELDS):
            raise ValueError(f"object_description has fields {sorted(description)}; "
                             f"expected {sorted(DESCRIPTION_FIELDS)}")
        problem = description and description_problem(description)
        if problem:
            raise ValueError(problem)
        object.__setattr__(self, "object_description", description)

    def channel(self, name: str) -> np.ndarray:
        """The window of channel `name` (one of CHANNEL_NAMES)."""
        index = CHANNEL_NAMES.index(name)
        return self.sa[index] if index < 2 else self.ra[index - 2]

    def channel_rate_hz(self, name: str) -> float:
        return self.sa_rate_hz if CHANNEL_NAMES.index(name) < 2 else self.ra_rate_hz

    def sample_times(self, name: str) -> np.ndarray:
        """Times [s] of channel `name`'s samples relative to the transition."""
        rate = self.channel_rate_hz(name)
        return np.arange(len(self.channel(name))) / rate - self.pre_transition_s

    def zero_channels(self) -> list[str]:
        """Names of the channels that are zero throughout the window."""
        return [name for name in CHANNEL_NAMES if not np.any(self.channel(name))]

    def negative_peak(self) -> tuple[str, int, float] | None:
        """(channel, sample index, value) of the first channel whose peak (largest |value|,
        1 once normalised) is a negative sample, else None. Max-normalising divides by the
        peak's magnitude, so a window's peak is +1 when it is the force (SA) or vibration (RA)
        the pad felt at its transition, as in every recorded event (the committed events' 160
        windows); -1 with no +1 is a window turned over (an edited file), which Eq. 3 would
        score as the opposite of the touch it memorized."""
        for name in CHANNEL_NAMES:
            window = self.channel(name)
            if np.any(window) and window.max() < 1.0 - _NORMALIZATION_TOLERANCE:
                index = int(np.argmin(window))
                return name, index, float(window[index])
        return None

    def falling_first_contact(self) -> tuple[str, float, float] | None:
        """(SA channel, mean before, mean after the transition) of the first channel of a
        reach_load event whose force falls through the first contact, else None. At first
        contact the pad's force rises from its untouched noise: every committed reach_load
        window peaks at or after the transition (0 to 26 samples after) and its mean after
        exceeds its mean before by 0.18 to 0.88 of the peak. A window that peaks before it
        and whose mean falls by more than _FALL_OF_PEAK (a window reversed in time) is no
        first contact; a window of noise alone does both in 3 % of draws (white noise,
        54 samples), and such a window already fails negative_peak half the time."""
        if self.transition != "reach_load":
            return None
        before = int(round(self.pre_transition_s * self.sa_rate_hz))
        for name, window in zip(CHANNEL_NAMES[:2], self.sa):
            if not 0 < before < len(window):
                return None
            mean_before = float(window[:before].mean())
            mean_after = float(window[before:].mean())
            if int(np.argmax(window)) < before and mean_after < mean_before - _FALL_OF_PEAK:
                return name, mean_before, mean_after
        return None

    def shape_problem(self) -> str | None:
        """Why these windows are no recording's, in words naming the channel, else None: a
        channel zero throughout (zero_channels), a negative peak (negative_peak), a first
        contact whose force falls (falling_first_contact). What the event files' reader
        refuses, and what extraction never cuts."""
        zero = self.zero_channels()
        if zero:
            return (f"channels {zero} are zero throughout the window: Eq. 3 could never "
                    "match them")
        turned = self.negative_peak()
        if turned:
            channel, index, value = turned
            return (f"field 'samples.{channel}' sample {index} is {number_text(value)}, the "
                    "window's peak, but no sample is +1: max-normalising divides by the "
                    "peak's magnitude, so a recorded window's peak is the force or vibration "
                    "the pad felt, +1, and a negative peak is no window a recording gives "
                    "(turned over or edited)")
        falling = self.falling_first_contact()
        if falling:
            channel, before, after = falling
            return (f"field 'samples.{channel}' peaks before the first contact and falls "
                    f"through it (mean {number_text(before)} before, {number_text(after)} "
                    "after): at first contact a pad's force rises, so this window is no "
                    "recording's (reversed in time or edited)")
        return None

    def relative_path(self) -> str:
        """Path of the event's file inside the events folder."""
        return f"{self.object_name}/{self.transition}.json"


def _check_magnitudes(ra: np.ndarray) -> None:
    """ValueError naming the channel if an RA window holds a negative sample. RA is a pad's
    vibration magnitude (Eq. 2), and max-normalising divides by a positive peak, so every
    sample is >= 0 exactly (the committed events' least RA sample is 0.0; the RA envelope, a
    first-order low-pass, keeps a non-negative window non-negative). SA windows get no such
    rule: a measured taxel is its offset plus unclipped noise, so a window before contact dips
    below zero, and max-normalised against a small first-contact peak far below (the committed
    events' least SA sample, events/prismatic/ensemble/box/reach_load.json, is -0.67)."""
    for index, window in zip(RA_CHANNELS, ra):
        if np.any(window < 0.0):
            least = int(np.argmin(window))
            raise ValueError(f"'{CHANNEL_NAMES[index]}' holds negative samples (the least, "
                             f"sample {least}, is {number_text(float(window[least]))}); an RA "
                             "window is a vibration magnitude, 0 to 1 once normalised")


def current_package_versions() -> dict[str, str]:
    """Versions of the packages that shape a recording, for the files' provenance."""
    versions = {"tegrasp-drake": tegrasp_drake.__version__}
    for package in ("drake", "numpy"):
        try:
            versions[package] = importlib.metadata.version(package)
        except importlib.metadata.PackageNotFoundError:
            versions[package] = "unknown"
    return versions
