"""Fig. 10's hit trigger: each film's level in Hold plus the threshold, as the controller's
Avoid rule computes it (control/corrective_actions.py, is_hit with ra_level)."""

import numpy as np
import pytest

from tegrasp_drake.control.corrective_actions import ra_history, ra_level
from tegrasp_drake.figures.avoid import HitRule, hit_trigger_lines

RULE = HitRule(threshold_mps2=3.93, level_s=0.02, period_s=0.005)  # a level of 4 ticks


def _film(t, left, right):
    return np.column_stack([np.broadcast_to(left, t.shape), np.broadcast_to(right, t.shape)])


def test_a_steady_film_raises_its_trigger_by_its_level():
    t = np.arange(0.0, 2.0, 0.001)
    t_tick, trigger = hit_trigger_lines(t, _film(t, 6.0, 0.5), [(1.0, 1.5)], RULE)
    assert t_tick[0] == pytest.approx(1.005)  # the tick after the transition's
    assert trigger[0] == pytest.approx([3.93, 3.93])  # no tick before it in Hold
    assert trigger[5:] == pytest.approx(np.tile([6.0 + 3.93, 0.5 + 3.93], (len(t_tick) - 5, 1)))


def test_the_trigger_is_the_controllers_level_tick_by_tick():
    rng = np.random.default_rng(982)
    t = np.arange(0.0, 1.0, 0.001)
    ra = rng.normal(2.0, 1.0, size=(len(t), 2))
    t_tick, trigger = hit_trigger_lines(t, ra, [(0.3, 0.6)], RULE)
    history = ()
    for k, tick in enumerate(t_tick):
        read = ra[np.searchsorted(t, tick, side="right") - 1]
        assert trigger[k] == pytest.approx(np.asarray(ra_level(history)) + RULE.threshold_mps2)
        history = ra_history(history, read, RULE.level_s, RULE.period_s)


def test_the_level_starts_again_with_each_hold():
    t = np.arange(0.0, 3.0, 0.001)
    ra = _film(t, np.where(t < 1.5, 8.0, 1.0), 0.0)
    t_tick, trigger = hit_trigger_lines(t, ra, [(1.0, 1.2), (2.0, 2.2)], RULE)
    second = trigger[t_tick > 2.0]
    assert second[0] == pytest.approx([3.93, 3.93])
    assert second[5:, 0] == pytest.approx(1.0 + 3.93)


def test_without_a_level_the_trigger_is_the_threshold():
    t = np.arange(0.0, 1.0, 0.001)
    _, trigger = hit_trigger_lines(t, _film(t, 6.0, 9.0), [(0.2, 0.4)],
                                   HitRule(threshold_mps2=3.93))
    assert np.all(trigger == 3.93)
