"""Trial logs holding sensor readings or an object position no sensor or workspace of the
trial could give, one test per channel: each reader refuses them in one line."""

import numpy as np
import pytest

from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.test_bad_input_round2 import _trial_log_with
from tests.test_bad_input_round28 import _refused

# A stored scenario as runs/trial.py logs it (the defaults: capacitive taxels, the PVDF film).
SCENARIO = "random_seed: 600\nobject:\n  name: box\n"
FORCE_TAXELS = SCENARIO + "tactile:\n  transducer: force\n  noise_std_n: 0.005\n"


def _log(tmp_path, scenario, name, row, values):
    """_trial_log_with's log storing `scenario` (None: none), its array `name` (ones but for
    taxels' rest readings) with `values` written into sample `row`."""
    from tests.test_bad_input import _trial_log
    with np.load(_trial_log(tmp_path / "base.npz")) as base:
        array = base[name].copy()
    array[row, ...] = values
    meta = {"scenario": scenario} if scenario is not None else {}
    return _trial_log_with(tmp_path / "trial.npz", meta, **{name: array})


# Rule: a taxel reads what its transducer's model gives: the capacitive taxel's calibrated
# newtons are clipped at zero; the force transducer's reading dips below zero by its noise (to
# 10 sigma), and neither reads past its full scale.
@pytest.mark.parametrize("scenario, value, expected", [
    (SCENARIO, -1e6, "holds -1000000 N, outside 0 to"),
    (SCENARIO, -0.5, "holds -0.5 N, outside 0 to"),
    (FORCE_TAXELS, -1e6, "holds -1000000 N, outside -0.0505 to 235.05 N"),
    (FORCE_TAXELS, 1e4, "holds 10000 N, outside -0.0505 to 235.05 N"),
    (None, -1e6, "holds -1000000 N or counts, outside -32768 to"),
], ids=["capacitive-huge", "capacitive-negative", "force-huge", "force-past-grip", "any"])
def test_taxel_readings_no_transducer_of_the_trial_gives_are_refused(tmp_path, scenario, value,
                                                                    expected):
    _refused(_log(tmp_path, scenario, "taxels", 5, value),
             f"'taxels' sample 5 column 0 {expected}")


@pytest.mark.parametrize("scenario, value", [(SCENARIO, 0.0), (FORCE_TAXELS, -0.03)],
                         ids=["capacitive-rest", "force-noise"])
def test_taxel_readings_a_transducer_gives_at_rest_are_read(tmp_path, scenario, value):
    log = load_trial_log(_log(tmp_path, scenario, "taxels", 5, value))
    assert log.taxels[5, 0] == value


# Rule: a pad's RA reading lies within its transducer's full scale (the film's readout clips
# at the amplifier's swing or the converter's last code).
@pytest.mark.parametrize("scenario, value, expected", [
    (SCENARIO, 1e300, "holds 1e+300 m/s^2, outside -2526.62 to 2526.62 m/s^2"),
    (SCENARIO, -3000.0, "holds -3000 m/s^2, outside -2526.62 to 2526.62 m/s^2"),
    (None, 1e300, "holds 1e+300 m/s^2, outside"),
], ids=["huge", "past-full-scale", "any"])
def test_pad_accelerations_past_the_transducers_full_scale_are_refused(tmp_path, scenario, value,
                                                                      expected):
    _refused(_log(tmp_path, scenario, "pad_acceleration", 50, value),
             f"'pad_acceleration' sample 50 column 0 {expected}")


def test_pad_accelerations_within_the_films_full_scale_are_read(tmp_path):
    log = load_trial_log(_log(tmp_path, SCENARIO, "pad_acceleration", 50, -2500.0))
    assert log.pad_acceleration[50, 0] == -2500.0


# Rule: the object starts on the table and moves no faster than the hand or a hit can drive it
# (or falls): 100 m away after 0.1 s is not where an object can be.
@pytest.mark.parametrize("column, value, expected", [
    (4, 100.0, "column 4 (x) holds 100 m, outside"),
    (6, 100.0, "column 6 (z) holds 100 m, outside"),
    (6, -100.0, "column 6 (z) holds -100 m, outside"),
], ids=["x", "z-up", "z-down"])
def test_an_object_position_beyond_where_it_can_be_is_refused(tmp_path, column, value, expected):
    path = _log(tmp_path, SCENARIO, "object_state", 5, 0.0)
    with np.load(path) as data:
        state = data["object_state"].copy()
    state[:, 0] = 1.0
    state[5, column] = value
    path = _trial_log_with(tmp_path / "moved.npz", {"scenario": SCENARIO}, object_state=state)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert (f"'object_state' sample 5 {expected}" in message and str(path) in message
            and "\n" not in message), message


def test_an_object_carried_within_the_reach_is_read(tmp_path):
    state = np.zeros((11, 13))
    state[:, 0] = 1.0
    state[:, 4:7] = [0.72, 0.0, 0.4]  # lifted 40 cm above its marker
    path = _trial_log_with(tmp_path / "trial.npz", {"scenario": SCENARIO}, object_state=state)
    assert load_trial_log(path).object_state[3, 6] == 0.4


# Rule: the scenario a log stores is one the package can run (its sensors set the ranges above);
# a stored number outside its declared range is named, as a scenario file's would be.
def test_a_trial_log_storing_a_scenario_out_of_its_ranges_is_refused(tmp_path):
    path = _trial_log_with(tmp_path / "trial.npz",
                           {"scenario": SCENARIO + "tactile:\n  noise_std_n: 7.0\n"})
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert (str(path) in message and "meta 'scenario'" in message
            and "tactile.noise_std_n" in message and "\n" not in message), message


# Rule: Eq. 1's SA is a pad's 12 taxels' sum and Eq. 2's RA the size of its 3 axes' vector, so
# each lies within 12 times, or sqrt(3) times, what the scenario's sensors read.
@pytest.mark.parametrize("column, value, expected", [
    (0, -1e6, "column 0 (sa_left) holds -1000000 N, outside 0 to 8136.93 N"),
    (3, 1e300, "column 3 (ra_right) holds 1e+300 m/s^2, outside 0 to 4376.23 m/s^2"),
], ids=["sa", "ra"])
def test_sa_and_ra_beyond_what_the_sensors_give_are_refused(tmp_path, column, value, expected):
    _refused(_log(tmp_path, SCENARIO, "channels", 50, [1.0] * column + [value]
                  + [1.0] * (3 - column)), f"'channels' sample 50 {expected}")


# Rule: the accelerometer transducer (no electronics) reads at most twice (its high-pass) the
# pad's largest acceleration: its top speed reversed within one plant step, and gravity.
def test_an_accelerometer_reading_no_pad_motion_gives_is_refused(tmp_path):
    scenario = SCENARIO + "vibration:\n  transducer: accelerometer\n"
    assert load_trial_log(_log(tmp_path, scenario, "pad_acceleration", 50, 3000.0)) is not None
    _refused(_log(tmp_path, scenario, "pad_acceleration", 50, 1e6),
             "'pad_acceleration' sample 50 column 0 holds 1000000 m/s^2, outside")
