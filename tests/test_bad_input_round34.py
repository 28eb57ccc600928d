"""Trial logs whose time bases do not cover one run, or whose stored result disagrees with the
log: each reader refuses them in one line."""

import numpy as np
import pytest

from tests.test_bad_input import _trial_log
from tests.test_bad_input_round2 import _trial_log_with
from tests.test_bad_input_round28 import _refused

# A stored scenario as runs/trial.py logs it (the defaults: SA at 108 Hz, RA at 1 kHz).
SCENARIO = "random_seed: 600\nobject:\n  name: box\n"


def _with_times(tmp_path, scenario, name, change):
    """The small trial log storing `scenario` (None: none) with time base `name` changed."""
    with np.load(_trial_log(tmp_path / "base.npz")) as base:
        times = change(base[name].copy())
    meta = {"scenario": scenario} if scenario is not None else {}
    return _trial_log_with(tmp_path / "trial.npz", meta, **{name: times})


# Rule: each time base is sampled at the period its logger writes at in the log's scenario
# (a 1e-9-scaled RA base drew a raster-overflowing plot, exit 70).
@pytest.mark.parametrize("name, change, expected", [
    ("t_ra", lambda t: t * 1e-9, "'t_ra' is sampled every 1e-12 s, but its scenario's logger "
                                 "writes it every 0.001 s"),
    ("t_slow", lambda t: t * 2.0, "'t_slow' is sampled every 0.02 s, but its scenario's logger "
                                  "writes it every 0.01 s"),
    ("t_sa", lambda t: np.arange(len(t)) / 100.0, "'t_sa' is sampled every 0.01 s, but its "
                                                  "scenario's logger writes it every 0.00925926 s"),
], ids=["ra-scaled", "slow-doubled", "sa-at-100-hz"])
def test_a_time_base_not_at_its_loggers_period_is_refused(tmp_path, name, change, expected):
    _refused(_with_times(tmp_path, SCENARIO, name, change), expected)


# Rule: the three time bases cover one run: they start and end together, within the slower
# period (a log storing no scenario, or a bare recording, included).
@pytest.mark.parametrize("scenario", [SCENARIO, None], ids=["scenario", "none"])
@pytest.mark.parametrize("name, change, expected", [
    ("t_ra", lambda t: t - 100.0, "'t_sa' starts at 0 s but 't_ra' at -100 s; a trial's time "
                                  "bases cover one run"),
    ("t_slow", lambda t: t + 0.05, "'t_sa' starts at 0 s but 't_slow' at 0.05 s"),
    ("t_sa", lambda t: t + 0.0925926 * 2, "'t_sa' starts at 0.185185 s but 't_ra' at 0 s"),
], ids=["ra-100-s-early", "slow-late", "sa-late"])
def test_time_bases_that_do_not_cover_one_run_are_refused(tmp_path, scenario, name, change,
                                                         expected):
    _refused(_with_times(tmp_path, scenario, name, change), expected)


def test_a_scaled_time_base_ends_apart_from_the_others_without_a_scenario(tmp_path):
    _refused(_with_times(tmp_path, None, "t_ra", lambda t: t * 1e-9),
             "'t_sa' ends at 0.0925926 s but 't_ra' at 1e-10 s")
