"""Bad inputs the eleventh review found, one test per rule: each stops with one line that
names the input and what to do, a non-zero exit, and nothing lost."""

import pytest

from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tests.test_bad_input import assert_one_line_error, run_probe
from tests.test_bad_input_round2 import _trial_log_with


_BOX = scenario_to_yaml(LoadScenario(name="box"))


# Rule: every metadata field of a trial log that a reader uses has one declared form
# (trial_log_file.META_FIELDS), checked when the log is read: a number where names belong,
# a map of times that holds text, a result that is not one, is refused naming the file and
# the field; a log without the scenario the figures need is refused as such.
@pytest.mark.parametrize("meta, words", [
    ({"phases": [1, 2, 3]}, "meta 'phases' must be a non-empty list of names"),
    ({"controller": 5}, "meta 'controller' must be a controller name, got 5"),
    ({"scenario": 5}, "meta 'scenario' must be the scenario's YAML text"),
    ({"campaign_run": ["a"]}, "meta 'campaign_run' must be"),
    ({"events": 5}, "meta 'events' must map event names to times [s]"),
    ({"events": {"reach_load": "soon"}}, "meta 'events' must map event names to times [s]"),
    ({"result": [1]}, "meta 'result' must be a trial result's JSON form"),
    ({"result": {"final_mode": 3}, "scenario": _BOX}, "'result' is not a trial result's JSON form"),
    ({}, "its metadata has no 'scenario'"),
])
def test_a_trial_log_metadata_field_of_the_wrong_form_is_refused_naming_it(
        meta, words, tmp_path, monkeypatch, capfd):
    make = lambda folder: _trial_log_with(folder / "t.npz", meta)  # noqa: E731
    before, _, code, text = run_probe(make, ["plot", "trial", "t.npz", "--out", "x.png"],
                                      tmp_path, monkeypatch, capfd)
    assert_one_line_error(code, text, "trial log 't.npz'", words)
    assert not (tmp_path / "x.png").exists()
