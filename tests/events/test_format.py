"""Memorized event files: exact round trip, deterministic bytes, and loading errors."""

import dataclasses
import json
import pathlib
import re
import shlex

import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.events.extraction import extract_memorized_events
from tegrasp_drake.events.event_file import (
    INDEX_FILE, MemorizedEventError, read_index, read_memorized_event)
from tegrasp_drake.events.events_folder import (
    load_all_memorized_events, load_memorized_events, save_memorized_events)
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.synthetic import (SyntheticGraspConfig, SyntheticSignalsConfig,
                                             synthetic_grasp)

VERSIONS = {"drake": "1.51.1", "numpy": "2.4.6", "tegrasp-drake": "0.1.0"}


def make_events(object_name="box", **config):
    trial = synthetic_grasp(SyntheticGraspConfig(**config))
    return extract_memorized_events(trial, object_name=object_name, sa_rate_hz=100.0,
                                    ra_rate_hz=1000.0, scenario="synthetic grasp",
                                    package_versions=VERSIONS)


@pytest.fixture
def saved(tmp_path):
    events = make_events()
    save_memorized_events(tmp_path, events.values())
    return tmp_path, events


def edit_json(path, edit):
    data = json.loads(path.read_text())
    edit(data)
    path.write_text(json.dumps(data))


def assert_names_file_and_command(error, path, command):
    message = str(error.value)
    assert str(path) in message
    assert f"`{command}`" in message


def test_loading_returns_every_value_exactly(saved):
    events_dir, events = saved
    loaded = load_memorized_events(events_dir, "box")
    assert list(loaded) == list(events)
    for transition, event in events.items():
        again = loaded[transition]
        assert np.array_equal(again.sa, event.sa) and np.array_equal(again.ra, event.ra)
        for field in dataclasses.fields(MemorizedEvent):
            if field.name not in ("sa", "ra"):
                assert getattr(again, field.name) == getattr(event, field.name), field.name


def test_saving_again_writes_identical_bytes(saved, tmp_path_factory):
    events_dir, _ = saved
    other_dir = tmp_path_factory.mktemp("again")
    save_memorized_events(other_dir, load_memorized_events(events_dir, "box").values())
    files = sorted(p.relative_to(events_dir) for p in events_dir.rglob("*.json"))
    assert files == sorted(p.relative_to(other_dir) for p in other_dir.rglob("*.json"))
    for file in files:
        assert (events_dir / file).read_bytes() == (other_dir / file).read_bytes(), file


def test_index_lists_each_event_with_its_metadata(saved):
    events_dir, events = saved
    entries = read_index(events_dir)
    assert [(e["object"], e["transition"]) for e in entries] == [
        ("box", t) for t in events]
    entry = entries[0]
    assert entry["file"] == "box/reach_load.json"
    assert entry["channels"] == ["sa_left", "sa_right", "ra_left", "ra_right"]
    assert (entry["sa_rate_hz"], entry["ra_rate_hz"], entry["window_s"]) == (100.0, 1000.0,
                                                                            0.5)
    assert entry["normalization"] == "max"
    assert entry["scenario"] == "synthetic grasp"
    assert entry["package_versions"] == VERSIONS


def test_recording_one_object_keeps_the_others(saved):
    events_dir, _ = saved
    save_memorized_events(events_dir, make_events("thin_cylinder").values())
    louder = make_events(signals=SyntheticSignalsConfig(grip_force_n=6.0), contact_rise_s=0.2)
    save_memorized_events(events_dir, louder.values())
    everything = load_all_memorized_events(events_dir)
    assert sorted(everything) == ["box", "thin_cylinder"]
    assert np.array_equal(everything["box"]["reach_load"].sa, louder["reach_load"].sa)


def test_saving_removes_an_objects_stale_files(saved):
    events_dir, events = saved
    without_lift_hold = [e for t, e in events.items() if t != "lift_hold"]
    save_memorized_events(events_dir, without_lift_hold)
    assert not (events_dir / "box" / "lift_hold.json").exists()
    assert "lift_hold" not in load_memorized_events(events_dir, "box")


def test_saving_requires_the_paper_transitions(tmp_path):
    events = make_events()
    with pytest.raises(ValueError, match="save_memorized_events: object 'box' lacks the "
                       "transitions 'place_unload' .each object needs reach_load, .*nothing"):
        save_memorized_events(tmp_path, [e for t, e in events.items() if t != "place_unload"])


@pytest.mark.parametrize("changed", [False, True], ids=["same-event", "another-window"])
def test_saving_two_events_of_one_object_and_transition_is_refused_naming_them(
        saved, changed):
    """Neither is kept silently: one file holds each object's transition."""
    events_dir, events = saved
    before = {path: path.read_bytes() for path in events_dir.rglob("*") if path.is_file()}
    again = events["load_lift"]
    if changed:
        again = dataclasses.replace(again, transition_time_s=again.transition_time_s + 0.1)
    given = [*events.values(), again]
    with pytest.raises(ValueError) as refused:
        save_memorized_events(events_dir, given)
    message = str(refused.value)
    assert ("events[1] and events[4] are both object 'box', transition 'load_lift' (one file, "
            "box/load_lift.json, holds it)") in message, message
    assert "nothing was saved" in message and "\n" not in message, message
    assert {path: path.read_bytes() for path in events_dir.rglob("*") if path.is_file()} == before


def truncate(path):
    text = path.read_text()
    path.write_text(text[:len(text) // 2])


def edit(change):
    return lambda path: edit_json(path, change)


DAMAGES = {  # name: (file, damage, what the message says)
    "missing file": ("load_lift", lambda path: path.unlink(), "file is missing"),
    "truncated file": ("reach_load", truncate, "not valid JSON"),
    "wrong format_version": ("place_unload", edit(lambda data: data.update(format_version=99)),
                             "has format_version 99"),
    # JSON's true is no version, though Python's True equals 1 (a version this reads)
    "format_version true": ("place_unload", edit(lambda data: data.update(format_version=True)),
                            "has format_version True"),
    "missing field": ("reach_load", edit(lambda data: data.pop("sa_rate_hz")),
                      "field 'sa_rate_hz' is missing"),
    "window too short": ("load_lift", edit(lambda data: data["samples"]["ra_left"].pop()),
                         "field 'samples.ra_left' has 499 samples"),
}


@pytest.mark.parametrize("damage", DAMAGES)
def test_a_damaged_event_file_is_named_with_the_command_that_remakes_it(saved, damage):
    events_dir, _ = saved
    transition, spoil, problem = DAMAGES[damage]
    path = events_dir / "box" / f"{transition}.json"
    spoil(path)
    with pytest.raises(MemorizedEventError) as error:
        load_memorized_events(events_dir, "box")
    assert problem in str(error.value)
    assert_names_file_and_command(error, path, "tegrasp record-events --object box")


def test_index_that_disagrees_with_a_file_is_refused(saved):
    events_dir, _ = saved
    edit_json(events_dir / INDEX_FILE,
              lambda data: data["events"][0].update(sa_rate_hz=1000.0))
    with pytest.raises(MemorizedEventError, match="sa_rate_hz") as error:
        load_memorized_events(events_dir, "box")
    assert_names_file_and_command(error, events_dir / INDEX_FILE,
                                  "tegrasp record-events --object box")


def test_missing_index_names_the_index_and_the_command(tmp_path):
    with pytest.raises(MemorizedEventError, match="missing") as error:
        load_memorized_events(tmp_path, "box")
    assert_names_file_and_command(error, tmp_path / INDEX_FILE, "tegrasp record-events")


def test_unknown_object_names_the_index_and_the_command_for_it(saved):
    events_dir, _ = saved
    with pytest.raises(MemorizedEventError, match="no memorized events for object 'cup'") as (
            error):
        load_memorized_events(events_dir, "cup")
    assert_names_file_and_command(error, events_dir / INDEX_FILE, "--set object.name=cup")
    with pytest.raises(MemorizedEventError) as error:
        load_memorized_events(events_dir, "thin_cylinder")
    assert_names_file_and_command(error, events_dir / INDEX_FILE,
                                  "tegrasp record-events --object thin_cylinder")


def record_events_arguments(message: str) -> list[list[str]]:
    """The record-events arguments of each command the message quotes."""
    quoted = [shlex.split(text) for text in re.findall(r"`([^`]+)`", message)]
    return [words[2:] if words[:2] == ["tegrasp", "record-events"] else words
            for words in quoted if words[:2] == ["tegrasp", "record-events"]
            or words[0].startswith("--")]


@pytest.mark.parametrize("name", ["thin_cylinder", "cup", "../../etc", "my/box", "-x"])
def test_the_advice_for_an_object_suggests_only_what_record_events_accepts(saved, name):
    events_dir, _ = saved
    with pytest.raises(MemorizedEventError) as error:
        load_memorized_events(events_dir, name)
    message = str(error.value)
    parser = cli.build_parser()
    for arguments in record_events_arguments(message):
        parser.parse_args(["record-events", *arguments])  # argparse exits on what it refuses
    if name in ("../../etc", "my/box", "-x"):
        assert f"No events are recorded under this name: object.name '{name}' must be" in message
        assert record_events_arguments(message) == []


def test_an_event_must_be_normalised_by_its_maximum():
    event = make_events()["reach_load"]
    with pytest.raises(ValueError, match="not normalised"):
        dataclasses.replace(event, sa=2.0 * event.sa)


DESCRIPTION = {"shape": "box", "size": [0.045, 0.045, 0.11], "mass": 0.15, "friction": 0.5,
               "file": ""}


def test_the_object_description_is_written_and_read_back(tmp_path):
    events = {name: dataclasses.replace(event, object_description=DESCRIPTION)
              for name, event in make_events().items()}
    save_memorized_events(tmp_path, events.values())
    loaded = load_memorized_events(tmp_path, "box")
    assert all(event.object_description == DESCRIPTION for event in loaded.values())
    index = json.loads((tmp_path / "index.json").read_text())
    assert all(entry["object_description"] == DESCRIPTION for entry in index["events"])


def _as_version_1(path, scenario_text):
    def change(data):
        data.pop("object_description", None)
        data.update(format_version=1, scenario=scenario_text)
    edit_json(path, change)


def test_a_version_1_file_is_migrated_from_its_scenario_text(tmp_path):
    save_memorized_events(tmp_path, make_events().values())
    scenario = ("object:\n  name: box\n  shape: box\n  size: [0.045, 0.045, 0.11]\n"
                "  mass: 0.15\n  friction: 0.5\n  file: ''\n")
    for path in (tmp_path / "box").glob("*.json"):
        _as_version_1(path, scenario)
    edit_json(tmp_path / "index.json", lambda data: [
        (entry.pop("object_description"), entry.update(scenario=scenario))
        for entry in data["events"]])
    loaded = load_memorized_events(tmp_path, "box")
    assert all(event.object_description == DESCRIPTION for event in loaded.values())


def test_a_version_1_file_that_does_not_describe_its_object_is_refused(tmp_path):
    save_memorized_events(tmp_path, make_events().values())
    path = tmp_path / "box" / "reach_load.json"
    _as_version_1(path, "box")
    with pytest.raises(MemorizedEventError, match="format_version 1 file whose scenario text "
                                                   "does not describe the object"):
        read_memorized_event(path)


def test_the_format_page_states_the_version_record_events_writes():
    """FORMAT.md's title, its field tables and its Versions section name the version the
    code writes (FORMAT_VERSION), and no other as the one written."""
    from tegrasp_drake.events.event_file import FORMAT_VERSION
    import tegrasp_drake.events
    page = (pathlib.Path(tegrasp_drake.events.__file__).parent / "FORMAT.md").read_text(
        encoding="utf-8")
    assert page.splitlines()[0].endswith(f"version {FORMAT_VERSION}")
    written = re.findall(r"record-events` writes version (\d+)", page)
    assert written == [str(FORMAT_VERSION)], written
    listed = re.findall(r"^- (\d+)[: ]", page.split("## Versions", 1)[1], flags=re.M)
    assert listed and int(listed[0]) == FORMAT_VERSION, listed


# Rule: save_memorized_events writes only what load_memorized_events reads back: it asks the
# reader's own checks of the events it is given (each file's, and each object's events as one
# grasp) and refuses before anything in the folder is replaced.
def _package_events(object_name):
    from tegrasp_drake.events.events_folder import load_memorized_events
    from tegrasp_drake.rig import paths
    return load_memorized_events(paths.package_events_dir(), object_name)


@pytest.mark.parametrize("mix, expected", [
    (lambda box, thin: [box["reach_load"], dataclasses.replace(thin["load_lift"],
                                                                object_name="box"),
                        box["place_unload"]],
     "load_lift.json: field 'scenario' grasps object 'thin_cylinder', but field 'object' is "
     "'box'"),
    (lambda box, thin: [dataclasses.replace(box["reach_load"], transition_time_s=9.0),
                        box["load_lift"], box["place_unload"]],
     "load_lift.json: field 'transition_time_s' is 4.6 s, not after reach_load's 9 s"),
    (lambda box, thin: [box["reach_load"], box["load_lift"], dataclasses.replace(
        box["place_unload"], scenario=box["place_unload"].scenario.replace(
            "random_seed: 0", "random_seed: 5", 1))],
     "place_unload.json: field 'scenario' differs from reach_load's"),
])
def test_saving_refuses_events_the_reader_refuses_and_keeps_the_folder(tmp_path, mix,
                                                                       expected):
    from tegrasp_drake.events.events_folder import UnreadableEventsError
    box, thin = _package_events("box"), _package_events("thin_cylinder")
    save_memorized_events(tmp_path, box.values())
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    with pytest.raises(UnreadableEventsError, match=re.escape(expected)) as error:
        save_memorized_events(tmp_path, mix(box, thin))
    assert str(tmp_path / "box") in str(error.value) and "nothing was saved" in str(error.value)
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


# Rule: an event's windows are checked for their shape and type before they are converted: a
# huge array (100 million rows) is refused from its shape, with no copy of it made.
@pytest.mark.parametrize("window, words", [
    (np.broadcast_to(np.zeros(1), (100_000_000, 2)), "'sa' has shape (100000000, 2)"),
    (np.zeros((2, 100), dtype=complex), "'sa' holds complex128 values, not real numbers"),
])
def test_an_events_window_is_refused_from_its_shape_before_it_is_converted(window, words,
                                                                          monkeypatch):
    convert = np.array

    def no_large_copy(value, *args, **kwargs):
        assert np.size(value) < 1_000_000, "a huge window was copied before its shape was checked"
        return convert(value, *args, **kwargs)
    monkeypatch.setattr(np, "array", no_large_copy)
    with pytest.raises(ValueError) as refused:
        MemorizedEvent(object_name="box", transition="reach_load", sa=window,
                       ra=np.zeros((2, 100)), sa_rate_hz=200.0, ra_rate_hz=200.0)
    assert str(refused.value).startswith(words), refused.value
