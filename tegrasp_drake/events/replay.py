"""Replay a logged (or synthetic) trial as the station's `channels` signal.

`channels_trajectory(trial)` is a zero-order-hold trajectory of the four channels in
CHANNEL_NAMES order, each logged value held until the next one, as the station's channel
output holds SA at the SA rate and RA at 1 kHz. Feed it through a TrajectorySource to drive
the WindowNormalizer and EventMatcher offline.
"""

import numpy as np
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.events.extraction import TactileTrial

# Each value becomes visible this much before its time stamp, so that a periodic update at
# the stamp's time sees it although k * period and the stamp may differ in the last bit.
TIME_STAMP_ALLOWANCE_S = 1e-9


def _hold(times: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    indices = np.searchsorted(times, at, side="right") - 1
    return values[np.maximum(indices, 0)]


def channels_trajectory(trial: TactileTrial) -> PiecewisePolynomial:
    """Zero-order hold of [sa_left, sa_right, ra_left, ra_right] over the trial's times."""
    breaks = np.union1d(trial.t_sa, trial.t_ra)
    samples = np.hstack([_hold(trial.t_sa, trial.sa, breaks),
                         _hold(trial.t_ra, trial.ra, breaks)])
    return PiecewisePolynomial.ZeroOrderHold(breaks - TIME_STAMP_ALLOWANCE_S, samples.T)
