"""A trial log's metadata names its format version as a whole number: JSON's true, which
Python reads as 1 (the version this package writes), is refused."""

import json

import pytest

from tegrasp_drake.rig.ranges import is_integer
from tegrasp_drake.scenario.trial_log_file import (FORMAT_VERSION, TrialLogError,
                                                   load_trial_log)
from tests.fake_trials import small_trial_log
from tests.trial_log_contents import edit_trial_log, read_trial_log_contents


def test_a_trial_log_whose_format_version_is_true_is_refused(tmp_path):
    saved = small_trial_log().save(tmp_path / "saved.npz")
    meta = json.loads(str(read_trial_log_contents(saved)["meta"]))
    assert meta["format_version"] == FORMAT_VERSION == True  # noqa: E712: the trap itself
    path = edit_trial_log(saved, tmp_path / "trial.npz",
                          lambda meta: meta.update(format_version=True))
    with pytest.raises(TrialLogError, match="has format version True"):
        load_trial_log(path)


@pytest.mark.parametrize("value, expected", [(1, True), (0, True), (True, False),
                                             (False, False), (1.0, False), ("1", False)])
def test_is_integer_takes_ints_and_not_bools(value, expected):
    assert is_integer(value) is expected
