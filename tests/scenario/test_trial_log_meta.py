"""A trial log's metadata holds only the keys its writers store (trial_log_file.META_KEYS),
and its text is bounded before it is decompressed: a 1 MB file of one repeated character
declares hundreds of MB."""


import pytest

from tegrasp_drake.scenario.trial_log_file import MAX_META_CHARS, TrialLogError, load_trial_log
from tests.bad_input.probes import assert_one_line_error, run_cli, trial_log_with
from tests.trial_log_contents import edit_trial_log


def test_a_trial_log_whose_meta_holds_a_key_no_writer_stores_is_refused(tmp_path):
    path = trial_log_with(tmp_path / "trial.npz", {"padding": "x"})
    with pytest.raises(TrialLogError, match="meta holds the key 'padding', which no trial "
                       "log has"):
        load_trial_log(path)


def test_a_trial_log_whose_meta_declares_too_much_text_is_refused_before_reading_it(tmp_path):
    path = trial_log_with(tmp_path / "trial.npz", {"result": {"note": "x" * MAX_META_CHARS}})
    assert path.stat().st_size < 1_000_000
    with pytest.raises(TrialLogError, match="'meta' declares .* characters of text, more than "
                       f"the {MAX_META_CHARS} a trial log holds"):
        load_trial_log(path)


# Rule: every writer of a trial log stores the controller that ran it (runs/trial.py, and the
# ideal grasp's open-loop script), so a log without one is refused naming the file and the
# field, never read as a log of no controller.
def test_a_trial_log_whose_meta_has_no_controller_is_refused_naming_the_field(tmp_path, capfd):
    path = trial_log_with(tmp_path / "trial.npz")
    edit_trial_log(path, path, lambda meta: meta.pop("controller"))
    with pytest.raises(TrialLogError, match="meta lacks the field 'controller'"):
        load_trial_log(path)
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "t.png")], capfd)
    assert_one_line_error(code, text, str(path), "'controller'")
    assert not (tmp_path / "t.png").exists()
