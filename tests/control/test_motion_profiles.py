"""Minimum-jerk timing and pose interpolation (control/motion_profiles.py)."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix

from tegrasp_drake.control.motion_profiles import (MINIMUM_JERK_PEAK_SPEED, MotionSegment,
                                                   interpolate_pose, minimum_jerk,
                                                   minimum_jerk_slope)


def test_minimum_jerk_starts_and_ends_at_rest():
    # s = 10 t^3 - 15 t^4 + 6 t^5: s' = 30 t^2 (1 - t)^2 and s'' = 60 t (1 - t)(1 - 2 t)
    # vanish at both ends; central differences see it.
    h = 1e-4
    for tau in (0.0, 1.0):
        velocity = (minimum_jerk(tau + h) - minimum_jerk(tau - h)) / (2 * h)
        assert velocity == pytest.approx(0.0, abs=1e-6)
    assert minimum_jerk(0.0) == 0.0 and minimum_jerk(1.0) == 1.0
    assert minimum_jerk(0.5) == pytest.approx(0.5, abs=1e-15)  # odd about the midpoint
    # The peak speed, 30/16 = 1.875 times the mean, at tau = 1/2.
    assert (minimum_jerk(0.5 + h) - minimum_jerk(0.5 - h)) / (2 * h) == pytest.approx(
        1.875, rel=1e-6)


def test_minimum_jerk_clips_tau_outside_the_segment():
    np.testing.assert_array_equal(minimum_jerk(np.array([-3.0, -1e-9, 1.0 + 1e-9, 7.0])),
                                  [0.0, 0.0, 1.0, 1.0])
    assert [minimum_jerk(tau) for tau in (-3.0, -1e-9, 1.0 + 1e-9, 7.0)] == [0.0, 0.0, 1.0, 1.0]


def test_minimum_jerk_of_a_float_is_the_polynomial_on_the_clipped_numpy_scalar_to_the_bit():
    for tau in np.linspace(-0.1, 1.1, 1201).tolist():
        clipped = np.clip(tau, 0.0, 1.0)  # a numpy scalar: its own arithmetic
        assert minimum_jerk(tau) == clipped ** 3 * (10.0 + clipped * (-15.0 + 6.0 * clipped))


def test_interpolate_pose_moves_straight_and_turns_about_the_fixed_axis():
    X0 = RigidTransform(RotationMatrix.MakeXRotation(0.2), [0.1, 0.2, 0.3])
    X1 = RigidTransform(RotationMatrix.MakeXRotation(1.4), [0.5, -0.2, 0.3])
    for s in (0.0, 0.25, 0.5, 1.0):
        X = interpolate_pose(X0, X1, s)
        np.testing.assert_allclose(X.translation(), [0.1 + 0.4 * s, 0.2 - 0.4 * s, 0.3],
                                   rtol=0, atol=1e-15)
        np.testing.assert_allclose(X.rotation().matrix(),
                                   RotationMatrix.MakeXRotation(0.2 + 1.2 * s).matrix(),
                                   rtol=0, atol=1e-12)


def test_motion_segment_holds_its_ends_outside_its_time_and_is_done_at_its_end():
    segment = MotionSegment(t_start=1.0, duration=2.0, p_start=(0.0, 0.0, 0.1),
                            p_end=(0.2, 0.0, 0.1))
    np.testing.assert_array_equal(segment.position(0.0), [0.0, 0.0, 0.1])
    np.testing.assert_allclose(segment.position(2.0), [0.1, 0.0, 0.1], rtol=0, atol=1e-15)
    # tau = 0.25: s = 10/64 - 15/256 + 6/1024 = 0.103515625
    np.testing.assert_allclose(segment.position(1.5), [0.2 * 0.103515625, 0.0, 0.1],
                               rtol=0, atol=1e-15)
    np.testing.assert_array_equal(segment.position(9.0), [0.2, 0.0, 0.1])
    assert not segment.done(2.999) and segment.done(3.0)


def test_a_hold_stands_still_from_its_start():
    hold = MotionSegment.hold(4.0, [0.3, 0.1, 0.2])
    assert hold.done(4.0)
    for t in (0.0, 4.0, math.inf):
        np.testing.assert_array_equal(hold.position(t), [0.3, 0.1, 0.2])


def test_the_minimum_jerk_slope_is_its_derivative_and_peaks_at_fifteen_eighths():
    tau = np.linspace(0.0, 1.0, 101)
    np.testing.assert_allclose(minimum_jerk_slope(tau), np.gradient(minimum_jerk(tau), tau),
                               atol=2e-3)
    assert minimum_jerk_slope(0.5) == MINIMUM_JERK_PEAK_SPEED
    assert minimum_jerk_slope(0.0) == minimum_jerk_slope(1.0) == minimum_jerk_slope(1.5) == 0.0
