"""A trial log's stored result is what the judge makes of the log's own data: every reader
judges it again (trial_judge.stored_verdict_problem) and refuses an edited verdict in one
line naming the file, the field, the stored and the judged value, and to run the trial
again."""


import pytest

from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.trial_log_contents import edit_trial_log


@pytest.fixture(scope="module")
def real_log(tmp_path_factory):
    """A real trial's log: the shortest the tests write (test_plot's: 1 s of the default)."""
    path = tmp_path_factory.mktemp("verdict") / "trial.npz"
    return run_trial(LoadScenario(), max_time=1.0).log.save(path)


def _edited(source, path, **changes):
    """`source` with its meta 'result' fields changed to `changes`, written to `path`."""
    return edit_trial_log(source, path, lambda meta: meta["result"].update(changes))


def test_an_unedited_trial_log_is_read_with_its_result(real_log):
    result = load_trial_log(real_log).meta["result"]
    assert result["hold_success"] is False and result["hold_time_s"] == 0.0


@pytest.mark.parametrize("changes, field, stored, judged", [
    ({"hold_time_s": 0.5}, "'hold_time_s'", "0.5 s", "0 s"),
    ({"false_triggers": 3}, "'false_triggers'", "3", "0"),
    ({"lift_height_m": 0.05}, "'lift_height_m'", "0.05", ""),
], ids=["hold-time", "false-triggers", "lift-height"])
def test_a_trial_log_whose_result_was_edited_is_refused(real_log, tmp_path, changes, field,
                                                         stored, judged):
    path = _edited(real_log, tmp_path / "edited.npz", **changes)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert "\n" not in message and str(path) in message, message
    assert f"meta 'result' field {field} is {stored}, but the log's data judge it {judged}" \
        in message, message
    assert message.endswith("run the trial again to remake it"), message
    # the re-judging reader (analysis/rejudge_from_logs.py) still reads it
    assert load_trial_log(path, rejudge=False).meta["result"][field.strip("'")] == \
        changes[field.strip("'")]


def test_a_hold_time_within_one_sample_period_of_the_judges_is_read(real_log, tmp_path):
    """The hold is read off 10 ms samples: a stored time off by less than one is the same."""
    path = _edited(real_log, tmp_path / "rounded.npz", hold_time_s=0.009)
    assert load_trial_log(path).meta["result"]["hold_time_s"] == 0.009
