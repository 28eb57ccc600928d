"""`tegrasp record-events`: which objects it records, with which settings, and that its help
says so (the recorder is replaced: nothing is simulated)."""

import argparse

import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands import record_events
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS


@pytest.fixture
def recorded(monkeypatch):
    """The (object name, scenario) of each recording the command asks for, in order."""
    from tegrasp_drake import events
    from tegrasp_drake.recording import ensemble_events, paper_events
    calls = []

    def record(object_name, scenario=None, **kwargs):
        calls.append((object_name, scenario))
        return {}

    def record_ensemble(object_name, scenario, runs, **kwargs):
        calls.append((f"{object_name} ensemble of {runs}", scenario))
        return {}
    monkeypatch.setattr(paper_events, "record_events", record)
    monkeypatch.setattr(ensemble_events, "record_object_ensemble", record_ensemble)
    monkeypatch.setattr(events, "save_memorized_events", lambda folder, saved: [])
    return calls


def test_set_without_object_records_all_three_builtin_objects_with_the_setting(
        recorded, tmp_path):
    assert cli.main(["record-events", "--set", "random_seed=603", "--events",
                     str(tmp_path / "events"), "-q"]) == 0
    assert [name for name, _ in recorded] == sorted(BUILTIN_OBJECTS)  # no ensembles: theirs ship
    for name, scenario in recorded:
        assert scenario.object.name == name and scenario.random_seed == 603


def test_set_naming_an_object_records_that_object_alone(recorded, tmp_path):
    assert cli.main(["record-events", "--set", "object.name=thin_cylinder", "--set",
                     "random_seed=603", "--events", str(tmp_path / "events"), "-q"]) == 0
    (name, scenario), (ensemble, _) = recorded
    assert name == "thin_cylinder" and scenario.random_seed == 603
    assert ensemble == f"thin_cylinder ensemble of {record_events.TEMPLATE_RUNS}"


def test_no_option_records_all_three_builtin_objects_from_their_own_scenarios(recorded,
                                                                            tmp_path):
    assert cli.main(["record-events", "--events", str(tmp_path / "events"), "-q"]) == 0
    assert recorded == [(name, None) for name in sorted(BUILTIN_OBJECTS)]


def test_object_help_says_that_a_set_alone_records_all_three():
    parser = cli.build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    option = next(a for a in commands.choices["record-events"]._actions
                  if "--object" in a.option_strings)
    assert "all three, each with the --set options" in option.help
    assert "--set object.name=... names" in option.help
