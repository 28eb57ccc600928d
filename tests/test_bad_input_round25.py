"""Bad inputs the fourteenth hostile pass found (round 25), one test per rule."""

import numpy as np
import pytest

from tegrasp_drake.hardware.jaco import jaco_lcm
from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_STATUS_CHANNEL, jaco_status_boundary, make_jaco_status)
from tests.test_bad_input_round21 import jaco_driver_on_memq

Q = [3.3, 4.5, 1.1, 2.5, 2.3, 3.9]  # [rad] inside every joint's range
ZERO = [0.0] * 6


# Rule: a status from the far future (utime 2^62 us, 146,000 years ahead) does not become a
# clock the arm's genuine statuses must beat: it is one sample, and the genuine stream after
# it is taken (the order of utime is not checked: jaco_lcm.jaco_status_boundary says why).
def test_an_arm_status_from_the_far_future_does_not_lock_out_the_genuine_stream():
    lcm, driver, simulator, context = jaco_driver_on_memq(Q)

    def publish(utime):
        lcm.Publish(JACO_STATUS_CHANNEL, make_jaco_status(utime, Q, ZERO, ZERO).encode())
        simulator.AdvanceTo(simulator.get_context().get_time() + 0.01)
        return driver.status_receiver.GetOutputPort("time_measured").Eval(context)[0]

    assert publish(6_580_000) == pytest.approx(6.58)
    assert publish(6_590_000) == pytest.approx(6.59)
    assert publish(2**62) == pytest.approx(2**62 * 1e-6)
    for utime in (6_600_000, 6_610_000, 6_620_000):
        assert publish(utime) == pytest.approx(utime * 1e-6)
    counters = driver.status_boundary.counters()
    assert counters.accepted == 6 and counters.rejected == {}


# Rule: an arm status whose joint positions, velocities or torques lie beyond the JACO2's
# physical ranges (modelgen/jaco2_dh.py) is counted and skipped, as a non-finite one is;
# one at the published limits is the arm's and is accepted.
@pytest.mark.parametrize("field, joint, value", [
    ("joint_position", 0, 1e300),   # finite, but no angle of a continuous joint
    ("joint_position", 1, np.radians(30.0)),   # joint 2 stops at 47 deg
    ("joint_position", 2, np.radians(350.0)),  # joint 3 stops at 341 deg
    ("joint_velocity", 3, -1e300),
    ("joint_velocity", 0, np.radians(90.0)),   # joint 1 turns at most 36 deg/s
    ("joint_torque", 1, 1e300),
    ("joint_torque", 5, -100.0),               # joint 6 makes at most 20 N m
])
def test_an_arm_status_beyond_the_jaco2s_ranges_is_skipped(field, joint, value):
    boundary = jaco_status_boundary()
    values = {"joint_position": list(Q), "joint_velocity": list(ZERO),
              "joint_torque": list(ZERO)}
    values[field][joint] = value
    bad = make_jaco_status(1_000_000, values["joint_position"], values["joint_velocity"],
                           values["joint_torque"])
    assert boundary.accept(bad.encode()) is None
    assert boundary.counters().rejected == {jaco_lcm.OUT_OF_RANGE: 1}
    (rejection,) = boundary.new_rejections()
    assert f"{field}[{joint}]" in rejection.detail
    assert "\n" not in boundary.describe(rejection)
    at_limits = make_jaco_status(
        1_010_000, [0.0, np.radians(47.0), np.radians(341.0), 0.0, 0.0, 0.0],
        np.radians([36.0, -36.0, 36.0, 48.0, -48.0, 48.0]),
        [40.0, -80.0, 40.0, 20.0, -20.0, 20.0])
    assert boundary.accept(at_limits.encode()) is not None
    assert boundary.counters().rejected == {jaco_lcm.OUT_OF_RANGE: 1}
