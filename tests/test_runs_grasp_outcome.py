"""The judge's lifted test and the grip-force event at a plateau."""

import math
import types

import numpy as np
import pytest

from tegrasp_drake.runs.grasp_outcome import (GRIP_FRACTION, grip_force_time, lifted_mask)
from tegrasp_drake.rig.objects import ObjectConfig

BOX = ObjectConfig(name="box", shape="box", size=[0.045, 0.045, 0.11], mass=0.15,
                   friction=0.8)


def state(z, roll_rad=0.0):
    """An object state row (quaternion w x y z, position, velocities) rolled about x."""
    row = np.zeros(13)
    row[:4] = [math.cos(roll_rad / 2), math.sin(roll_rad / 2), 0.0, 0.0]
    row[6] = z
    return row


def test_a_box_knocked_onto_its_side_is_not_lifted_but_a_raised_one_is():
    toppled = types.SimpleNamespace(object_state=np.array(
        [state(0.0), state(0.0225, math.pi / 2)]))
    raised = types.SimpleNamespace(object_state=np.array([state(0.0), state(0.05)]))
    assert list(lifted_mask(toppled, BOX)) == [False, False]
    assert list(lifted_mask(toppled)) == [False, True]  # by the origin, as before
    assert list(lifted_mask(raised, BOX)) == [False, True]


def squeeze_log(peak_n):
    """Both pads' force rising linearly to peak_n over 1 s, then flat."""
    t = np.arange(0.0, 2.0, 0.01)
    force = peak_n * np.clip(t, 0.0, 1.0)
    taxels = np.repeat(force[:, None] / 12.0, 24, axis=1)
    return types.SimpleNamespace(t_sa=t, true_taxels=taxels)


def test_the_grip_force_is_reached_at_the_command_or_at_the_plateau_below_it():
    assert grip_force_time(squeeze_log(30.0), 25.0) == pytest.approx(
        GRIP_FRACTION * 25.0 / 30.0, abs=0.011)
    # The 22 mm cylinder's case: the taxels never see 90 % of the command.
    assert grip_force_time(squeeze_log(21.4), 25.0) == pytest.approx(GRIP_FRACTION, abs=0.011)
    # A plateau below the command but above its fraction: the command's fraction, as
    # before the plateau rule (the built-in objects' committed events depend on it).
    assert grip_force_time(squeeze_log(24.0), 25.0) == pytest.approx(
        GRIP_FRACTION * 25.0 / 24.0, abs=0.011)
    assert grip_force_time(squeeze_log(0.1), 25.0) is None  # never squeezed
