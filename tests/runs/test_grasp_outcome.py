"""The judge's lifted test, the grip-force event at a plateau, the grip fraction and the
scripted lift start."""

import math
import types

import numpy as np
import pytest

from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
from tegrasp_drake.scenario.grasp_outcome import (GRIP_FRACTION, first_contact_time,
                                                  grip_force_time, grip_fraction_at,
                                                  lifted_mask, release_height_m,
                                                  scripted_lift_start)
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.scenario.trial_judge import lift_grip_fraction

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


def test_the_release_height_is_the_lowest_point_above_the_start_when_unload_began():
    """A box lifted 60 mm and tilted 20 deg about x: its lowest corner hangs below its base's
    centre by half its depth times sin(20 deg)."""
    tilt = math.radians(20.0)
    log = types.SimpleNamespace(t_slow=np.array([0.0, 1.0, 2.0]), object_state=np.array(
        [state(0.0), state(0.06, tilt), state(0.0)]))
    hanging_m = 0.06 - 0.045 / 2 * math.sin(tilt)
    assert release_height_m(log, 1.0, BOX) == pytest.approx(hanging_m, abs=1e-9)
    assert release_height_m(log, 1.5, BOX) == pytest.approx(hanging_m, abs=1e-9)  # last state
    assert release_height_m(log, 2.0, BOX) == pytest.approx(0.0, abs=1e-9)


def gripper_at(t, opening_m):
    """t_slow and gripper_status of fingers standing opening_m apart throughout."""
    status = np.zeros((len(t), ru.STATUS_SIZE))
    status[:, ru.STATUS_PO] = ru.position_byte_from_opening(opening_m)
    return dict(t_slow=t, gripper_status=status)


def squeeze_log(peak_n, opening_m=0.045):
    """Both pads' force rising linearly to peak_n over 1 s, then flat, the fingers opening_m
    apart (by default on a 45 mm box)."""
    t = np.arange(0.0, 2.0, 0.01)
    force = peak_n * np.clip(t, 0.0, 1.0)
    taxels = np.repeat(force[:, None] / 12.0, 24, axis=1)
    return types.SimpleNamespace(t_sa=t, true_taxels=taxels, **gripper_at(t, opening_m))


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


def overshoot_log(peak_n, held_n):
    """Both pads' force jumping to peak_n at 0.5 s and relaxing to held_n within 60 ms
    (the drive's overshoot, then the object settling under the locked screw)."""
    t = np.arange(0.0, 2.0, 0.01)
    force = np.where(t < 0.5, 0.0, held_n + (peak_n - held_n) * np.exp(-(t - 0.5) / 0.02))
    taxels = np.repeat(force[:, None] / 12.0, 24, axis=1)
    return types.SimpleNamespace(t_sa=t, true_taxels=taxels, **gripper_at(t, 0.045))


def test_the_grip_fraction_is_the_weaker_pads_force_over_the_held_grip():
    # The held grip is the median over the 0.2 s after the grip force is reached (0.75 s):
    # the ramp's 22.5-28.5 N, 25.5 N.
    log = squeeze_log(30.0)
    assert grip_fraction_at(log, 0.5, 25.0) == pytest.approx(15.0 / 25.5, abs=0.01)
    assert grip_fraction_at(log, -0.1, 25.0) is None  # before the first frame
    # A peak past the setting that relaxes: the held 20 N is the grip, not the command.
    relaxed = overshoot_log(29.0, 20.0)
    assert grip_fraction_at(relaxed, 1.5, 25.0) == pytest.approx(1.0, abs=0.01)
    assert grip_fraction_at(relaxed, 1.5, 25.0) > 20.0 / 25.0 + 0.1
    # Taxels that never see 90 % of the command: the plateau is the grip.
    assert grip_fraction_at(squeeze_log(21.4), 0.5, 25.0) == pytest.approx(0.5, abs=0.02)
    assert grip_fraction_at(squeeze_log(0.1), 1.5, 25.0) is None  # never squeezed


def test_pads_pressed_on_each_other_are_no_contact_and_no_grip():
    """Fingers that closed on nothing (the 2F-85 at its closed byte) press their pads on each
    other: the taxels read it (6.3 N a pad, as an open-loop close past a box pushed out of
    reach did), but no object was touched or gripped. Between the pads of a 5 mm object the
    same forces are its grip."""
    empty = squeeze_log(6.3, opening_m=0.0)
    assert first_contact_time(empty) is None
    assert grip_force_time(empty, 25.0) is None
    assert grip_fraction_at(empty, 1.5, 25.0) is None
    thinnest = squeeze_log(6.3, opening_m=0.005)
    assert first_contact_time(thinnest) == pytest.approx(0.04, abs=0.011)
    assert grip_fraction_at(thinnest, 1.5, 25.0) == pytest.approx(1.0, abs=0.01)


def test_the_lift_start_is_the_scripts_and_a_closed_loop_log_has_none():
    scripted = types.SimpleNamespace(meta={"phase_starts": {"load": 2.8, "lift": 4.6}})
    closed_loop = types.SimpleNamespace(meta={"phase_starts": {"Load": 3.8, "Lift": 4.2}})
    assert scripted_lift_start(scripted) == 4.6
    assert scripted_lift_start(closed_loop) is None


def re_reached_log():
    """A grasp that re-centred: the first close pinches the object for 40 ms at 0.5 s (28 N),
    then only rubs it (0.4 N) while the gripper opens, until 1.0 s; after the Reach again at
    1.5 s the second close rises to 25 N by 2.5 s and holds it."""
    t = np.arange(0.0, 4.0, 0.01)
    force = np.where((t >= 0.5) & (t < 0.54), 28.0, np.where((t >= 0.54) & (t < 1.0), 0.4, 0.0))
    force = np.where(t >= 2.0, 25.0 * np.clip((t - 2.0) / 0.5, 0.0, 1.0), force)
    taxels = np.repeat(force[:, None] / 12.0, 24, axis=1)
    return types.SimpleNamespace(t_sa=t, true_taxels=taxels, **gripper_at(t, 0.045))


def test_the_lift_grip_fraction_is_of_the_grip_settled_after_the_last_reach():
    """The settled grip of a trial that re-centred is the second close's, the one it lifts
    with, not the first close's rub as the gripper opened (which made the fraction 62)."""
    transitions = [Transition(0.8, Mode.REACH, Mode.RE_REACH, Trigger.CORRECTIVE, "one finger"),
                   Transition(1.5, Mode.RE_REACH, Mode.REACH, Trigger.CORRECTIVE, "re-centred"),
                   Transition(2.2, Mode.REACH, Mode.LOAD, Trigger.MEMORIZED_EVENT, "event"),
                   Transition(3.0, Mode.LOAD, Mode.LIFT, Trigger.MEMORIZED_EVENT, "event")]
    assert lift_grip_fraction(re_reached_log(), transitions, 25.0) == pytest.approx(1.0,
                                                                                    abs=0.01)
    # Without the Re-Reach, the first close's settled grip is the trial's: its rub.
    assert lift_grip_fraction(re_reached_log(), transitions[2:], 25.0) > 10.0
