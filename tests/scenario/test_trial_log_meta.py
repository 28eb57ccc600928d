"""A trial log's metadata holds only the keys its writers store (trial_log_file.META_KEYS),
and its text is bounded before it is decompressed: a 1 MB file of one repeated character
declares hundreds of MB."""

import pytest

from tegrasp_drake.scenario.trial_log_file import MAX_META_CHARS, TrialLogError, load_trial_log
from tests.test_bad_input_round2 import _trial_log_with


def test_a_trial_log_whose_meta_holds_a_key_no_writer_stores_is_refused(tmp_path):
    path = _trial_log_with(tmp_path / "trial.npz", {"padding": "x"})
    with pytest.raises(TrialLogError, match="meta holds the key 'padding', which no trial "
                       "log has"):
        load_trial_log(path)


def test_a_trial_log_whose_meta_declares_too_much_text_is_refused_before_reading_it(tmp_path):
    path = _trial_log_with(tmp_path / "trial.npz", {"result": {"note": "x" * MAX_META_CHARS}})
    assert path.stat().st_size < 1_000_000
    with pytest.raises(TrialLogError, match="'meta' declares .* characters of text, more than "
                       f"the {MAX_META_CHARS} a trial log holds"):
        load_trial_log(path)
