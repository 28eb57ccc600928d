"""Memorized event files and their index are read whole or refused: a duplicate or unknown
key, a value no float holds, NaN, a negative time or window, a grip force beyond the
gripper, an event listed twice or no event listed, events of one object at different rates,
events of a changed built-in object, each named with its file in one line before any trial
runs. Every committed event file still loads."""

import json
import math
import pathlib
import shutil

import numpy as np
import pytest

import tegrasp_drake
from tegrasp_drake.events.event_file import INDEX_FILE, MemorizedEventError, read_index
from tegrasp_drake.events.events_folder import load_memorized_events, save_memorized_events
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.bad_input.probes import (assert_one_line_error, edit_json, events_copy_with_index,
                                    memorized_events, one_line_of, run_cli)


def _zero_channel(folder):
    edit_json(folder / "box" / "load_lift.json",
          lambda data: data["samples"].update(ra_left=[0.0] * len(data["samples"]["ra_left"])))


def _drop_index_entry(folder):
    edit_json(folder / "index.json", lambda data: data.update(events=[
        e for e in data["events"] if (e["object"], e["transition"]) != ("box", "load_lift")]))


def _as_box(scenario: str) -> str:
    return scenario.replace("name: thick_cylinder", "name: box", 1)


def _copy_other_objects_events(folder):
    """The thick cylinder's well-formed events copied in as the box's (their scenario's object
    renamed too, so that each file is whole)."""
    for file in (folder / "thick_cylinder").glob("*.json"):
        shutil.copy(file, folder / "box" / file.name)
        edit_json(folder / "box" / file.name, lambda data: data.update(
            object="box", scenario=_as_box(data["scenario"])))
    edit_json(folder / "index.json", lambda data: data.update(events=[
        dict(e, object="box", file=e["file"].replace("thick_cylinder", "box"),
             scenario=_as_box(e["scenario"]))
        if e["object"] == "thick_cylinder" else e
        for e in data["events"] if e["object"] != "box"]))


def _turned_over_sa_window(folder):
    """The box's Reach-Load sa_left window negated (its peak -1, no sample +1): max-normalised
    still, but no recording's window."""
    edit_json(folder / "box" / "reach_load.json", lambda data: data["samples"].update(
        sa_left=[-v for v in data["samples"]["sa_left"]]))


def _negative_mass_described(folder):
    """The box's Reach-Load file describes an object of mass -0.15 kg: no object a scenario
    can hold, whether or not the controller lets the events' mass differ."""
    edit_json(folder / "box" / "reach_load.json",
              lambda data: data["object_description"].update(mass=-0.15))


# Rule: an event file's object description holds an object a scenario could hold (shape,
# sizes, mass and friction in ObjectConfig's ranges), also where event_object_may_differ
# lets that field differ from the scenario's object.
@pytest.mark.parametrize("extra", [[], ["--set", "controller.event_object_may_differ=[mass]"]])
def test_an_event_felt_on_an_impossible_object_is_refused(extra, events_copy, capfd):
    _negative_mass_described(events_copy)
    code, text = run_cli(["trial", "--events", str(events_copy), *extra], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "reach_load.json", "'object_description.mass' is -0.15",
                          "must lie in")


def _reversed_reach_load(folder):
    """The box's Reach-Load windows reversed in time: each still max-normalised with its peak
    +1, but the force falls through the first contact."""
    edit_json(folder / "box" / "reach_load.json", lambda data: data["samples"].update(
        {name: values[::-1] for name, values in data["samples"].items()}))


# Rule: a reach_load window's force rises through the first contact; one that peaks before
# it and falls (reversed in time, edited) is refused by the event files' reader and never
# written by a recording.
@pytest.mark.parametrize("spoil, expected", [
    (_reversed_reach_load, "field 'samples.sa_left' peaks before the first contact and falls"),
    (_zero_channel, "channels ['ra_left'] are zero throughout the window"),
    (_turned_over_sa_window, "field 'samples.sa_left' sample 44 is -1, the window's peak"),
    (_drop_index_entry, "lists no load_lift event of object 'box'"),
    (_copy_other_objects_events, "were recorded on another object: shape 'cylinder' "
                                 "(recorded) != 'box' (now)"),
])
def test_unusable_events_are_named_before_the_trial_runs(spoil, expected, events_copy, capfd):
    spoil(events_copy)
    code, text = run_cli(["trial", "--events", str(events_copy)], capfd)
    assert_one_line_error(code, text, str(events_copy), expected)


# Rule: an event file or index that names no format_version (absent or null) is said to be
# none `tegrasp record-events` wrote, with how to remake it, never "format_version None".
@pytest.mark.parametrize("name", ["box/load_lift.json", INDEX_FILE])
@pytest.mark.parametrize("remove", [lambda data: data.pop("format_version"),
                                    lambda data: data.update(format_version=None)])
def test_an_event_file_without_a_format_version_says_who_writes_one(name, remove, events_copy,
                                                                   capfd):
    edit_json(events_copy / name, remove)
    code, text = run_cli(["trial", "--events", str(events_copy)], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, name.split("/")[-1], "has no format_version, so "
                          "`tegrasp record-events` did not write it", "Remake it with")
    assert "None" not in text, text


# Rule: an event file or index saved with a UTF-8 byte-order mark (as some Windows editors
# save) is said to start with one, with what to do, never as JSON "perhaps truncated".
@pytest.mark.parametrize("name", ["box/load_lift.json", INDEX_FILE])
def test_an_event_file_with_a_byte_order_mark_says_so(name, events_copy, capfd):
    path = events_copy / name
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    code, text = run_cli(["trial", "--events", str(events_copy)], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, name.split("/")[-1], "starts with a UTF-8 byte-order "
                          "mark, which JSON does not take; save it without one",
                          "Remake it with `tegrasp record-events")
    assert "truncated" not in text, text


def test_events_of_a_changed_builtin_object_are_refused_unless_accepted(capfd):
    code, text = run_cli(["trial", "--set", "object.mass=0.3"], capfd)
    assert_one_line_error(code, text, "mass 0.15 (recorded) != 0.3 (now)",
                          "controller.event_object_may_differ=[mass]")


def test_events_of_one_object_with_different_rates_are_refused(tmp_path):
    from tegrasp_drake.events.event_file import event_json_text, event_to_json
    from tegrasp_drake.events.events_folder import UnreadableEventsError
    mixed = memorized_events(sa_rate_hz=108.0)[:2] + memorized_events(sa_rate_hz=1000.0)[2:]
    with pytest.raises(UnreadableEventsError, match="different windows or rates"):
        save_memorized_events(tmp_path, mixed)
    assert not (tmp_path / INDEX_FILE).exists()
    save_memorized_events(tmp_path, mixed[:2] + memorized_events(sa_rate_hz=108.0)[2:])
    for event in mixed[2:]:  # the other rate's files written in by hand
        (tmp_path / event.relative_path()).write_text(event_json_text(event_to_json(event)))
    edit_json(tmp_path / INDEX_FILE, lambda data: [
        entry.update(sa_rate_hz=1000.0) for entry in data["events"]
        if entry["transition"] in {e.transition for e in mixed[2:]}])
    with pytest.raises(MemorizedEventError, match="different windows or rates"):
        load_memorized_events(tmp_path, "mine")


def test_a_deeply_nested_index_is_one_line(tmp_path, capfd):
    events = tmp_path / "events"
    events.mkdir()
    (events / "index.json").write_text("[" * 100_000 + "]" * 100_000)
    code, text = run_cli(["trial", "--events", str(events)], capfd)
    assert_one_line_error(code, text, "index.json")


def test_an_unreadable_event_file_is_one_line(tmp_path, capfd):
    import shutil
    from tegrasp_drake.rig import paths
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events,
                    ignore=shutil.ignore_patterns("__init__.py", "__pycache__"))
    (events / "box" / "load_lift.json").unlink()
    (events / "box" / "load_lift.json").mkdir()  # a folder where the file should be
    code, text = run_cli(["trial", "--events", str(events)], capfd)
    assert_one_line_error(code, text, "load_lift.json")


def _events_copy(tmp_path) -> pathlib.Path:
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("prismatic", "ensemble", "corrective"))
    return folder


def test_an_event_file_with_a_duplicate_key_is_refused(tmp_path):
    folder = _events_copy(tmp_path)
    path = folder / "box" / "reach_load.json"
    path.write_text(path.read_text().replace('"format":', '"format_version": 2,\n "format":', 1))
    with pytest.raises(MemorizedEventError, match="reach_load.json: key 'format_version' appears"):
        tegrasp_drake.load_memorized_events(folder, "box")


def test_an_index_listing_an_event_twice_is_refused(tmp_path):
    folder = _events_copy(tmp_path)
    index = json.loads((folder / "index.json").read_text())
    index["events"].append(dict(index["events"][0]))
    (folder / "index.json").write_text(json.dumps(index))
    with pytest.raises(MemorizedEventError, match="both list the box reach_load event"):
        read_index(folder)


def test_events_given_as_a_list_are_named():
    with pytest.raises(TypeError) as refused:
        tegrasp_drake.EventMatcher(events=[1, 2])
    assert "EventMatcher: argument 'events' must be Mapping" in one_line_of(refused.value)


@pytest.mark.parametrize("fields, field", [
    (dict(sa_rate_hz=math.inf), "sa_rate_hz"),
    (dict(window_s=-0.5), "window_s"),
    (dict(object_name=5), "object_name"),
])
def test_a_memorized_event_names_its_wrong_field(fields, field):
    arguments = dict(object_name="box", transition="reach_load", sa=np.ones((2, 54)),
                     ra=np.ones((2, 500)), sa_rate_hz=108.0, ra_rate_hz=1000.0)
    with pytest.raises((ConfigError, TypeError)) as refused:
        tegrasp_drake.MemorizedEvent(**{**arguments, **fields})
    assert f"field '{field}'" in one_line_of(refused.value)


def test_an_event_sample_no_float_holds_is_refused_naming_the_file(tmp_path):
    folder = _events_copy(tmp_path)
    path = folder / "box" / "load_lift.json"
    data = json.loads(path.read_text())
    text = json.dumps(data).replace(json.dumps(data["samples"]["sa_left"][0]), "9" * 5000, 1)
    path.write_text(text)
    with pytest.raises(MemorizedEventError) as refused:
        tegrasp_drake.load_memorized_events(folder, "box")
    assert "load_lift.json" in one_line_of(refused.value) and "5000 digits" in str(refused.value)


def test_an_index_holding_nan_is_refused(tmp_path):
    folder = _events_copy(tmp_path)
    index = folder / "index.json"
    index.write_text(index.read_text().replace("{", '{"x_nan": NaN, ', 1))
    with pytest.raises(MemorizedEventError) as refused:
        tegrasp_drake.load_memorized_events(folder, "box")
    assert "index.json" in one_line_of(refused.value) and "NaN" in str(refused.value)


# Rule: an event file holds its fields and nothing else: an unknown key in it or in its
# `samples` (a forged extra channel) is refused naming the key, as a duplicate channel or a
# window of the wrong length is, rather than ignored.
@pytest.mark.parametrize("where, key, words", [
    ("samples", "extra", "field 'samples.extra' is not a channel"),
    ("file", "sa_rate", "field 'sa_rate' is not a field of an event file"),
])
def test_an_event_file_with_an_unknown_key_is_refused_naming_it(tmp_path, where, key, words):
    import json
    import shutil
    from tegrasp_drake.events.event_file import MemorizedEventError, read_memorized_event
    path = tmp_path / "reach_load.json"
    shutil.copy("events/box/reach_load.json", path)
    data = json.loads(path.read_text())
    (data["samples"] if where == "samples" else data)[key] = [0.0, 0.0, 0.0]
    path.write_text(json.dumps(data))
    with pytest.raises(MemorizedEventError) as refused:
        read_memorized_event(path)
    message = str(refused.value)
    assert "\n" not in message and str(path) in message and words in message, message


def test_every_committed_event_file_still_loads():
    import pathlib
    from tegrasp_drake.events.event_file import read_memorized_event
    files = [path for path in pathlib.Path("events").glob("**/*.json")
             if path.name != "index.json"]
    assert len(files) >= 40
    for path in files:
        assert read_memorized_event(path).object_name == path.parent.name


# Rule: an events index that lists no events is a damaged events folder, refused where the
# index is read (so every reader of it, the plot, a trial, a sweep, names it alike) in one
# line naming the index and how to remake it; not an internal error of the figure.
def test_an_index_listing_no_events_is_refused_naming_it(tmp_path, capfd):
    from tegrasp_drake.events import MemorizedEventError, read_index
    folder = events_copy_with_index(tmp_path, entries=lambda entries: [])
    with pytest.raises(MemorizedEventError, match="lists no events"):
        read_index(folder)
    code, error = run_cli(["plot", "events", "--events", str(folder),
                           "--out", str(tmp_path / "events.png")], capfd)
    assert code == 1, error
    assert_one_line_error(code, error, "index.json", "lists no events")
    assert not (tmp_path / "events.png").exists()


# Rule: an RA window is a normalised vibration magnitude (Eq. 2), so no sample is negative;
# a memorized event holding one is refused naming its file and channel. (SA windows may dip
# below zero: the committed events' reach SA windows reach -0.67 of their peak.)
def test_a_memorized_event_with_a_negative_ra_window_is_refused(tmp_path, capfd):
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events,
                    ignore=shutil.ignore_patterns("__init__.py", "__pycache__"))
    path = events / "box" / "load_lift.json"
    data = json.loads(path.read_text())
    data["samples"]["ra_left"] = [-1.0] * len(data["samples"]["ra_left"])
    path.write_text(json.dumps(data))
    with pytest.raises(MemorizedEventError, match=r"load_lift\.json.*'ra_left'.*negative"):
        load_memorized_events(events, "box")
    code, text = run_cli(["plot", "events", "--events", str(events), "--out",
                          str(tmp_path / "p.png")], capfd)
    assert_one_line_error(code, text, "load_lift.json", "'ra_left'")


# Rule: a max-normalised window's peak is the force or vibration the pad felt, +1; a window
# whose peak is -1 (an SA window turned over: each sample in [-1, 1], its magnitude still 1)
# is no recording's and is refused by the event files' one reader, naming the file, channel,
# sample and value, with the command that records the events again.
def test_an_event_window_whose_peak_is_negative_is_refused_naming_the_sample(tmp_path, capfd):
    events = _events_copy(tmp_path)
    _turned_over_sa_window(events)
    code, text = run_cli(["plot", "events", "--events", str(events), "--out",
                          str(tmp_path / "p.png")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, str(events / "box" / "reach_load.json"),
                          "field 'samples.sa_left' sample 44 is -1",
                          "tegrasp record-events --object box")
    assert not (tmp_path / "p.png").exists()
    with pytest.raises(MemorizedEventError, match="'samples.sa_left' sample 44 is -1"):
        load_memorized_events(events, "box")


def test_recording_never_writes_a_window_whose_peak_is_negative():
    from tegrasp_drake.events.extraction import TactileTrial, extract_memorized_events
    t = np.arange(0, 1.0, 0.001)
    sa = np.column_stack([-0.02 - 0.01 * (t > 0.5), 0.02 + 5.0 * (t > 0.5)])  # left: no touch
    ra = np.column_stack([0.1 + (t > 0.5), 0.1 + (t > 0.5)])
    trial = TactileTrial(t_sa=t, sa=sa, t_ra=t, ra=ra, transition_times={"reach_load": 0.5})
    with pytest.raises(ValueError, match="'samples.sa_left' sample 26 is -1, the window's peak"):
        extract_memorized_events(trial, object_name="box", sa_rate_hz=100.0, ra_rate_hz=1000.0)


# Rule: a JSON text that escapes a lone surrogate ("\\ud800") is valid JSON syntax but no
# Unicode text; every JSON file the package reads refuses it (rig/files.load_json), naming the
# file and the field, here an event file's 'physical_event' for `tegrasp plot events`.
def test_an_event_file_with_a_lone_surrogate_is_refused_naming_the_field(tmp_path, capfd):
    events = _events_copy(tmp_path)
    path = events / "box" / "reach_load.json"
    path.write_text(path.read_text().replace(
        '"physical_event": "first contact', '"physical_event": "first \\ud800 contact', 1))
    code, text = run_cli(["plot", "events", "--events", str(events), "--out",
                          str(tmp_path / "p.png")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, f"{path}: field 'physical_event' holds \\ud800",
                          "lone UTF-16 surrogate", "tegrasp record-events --object box")
    assert not (tmp_path / "p.png").exists()


# Rule: an event file's numbers are in their ranges when read: the transition's time in its
# trial is not before the trial started.
def test_an_event_whose_transition_time_is_negative_is_refused(tmp_path):
    import json
    import shutil
    from tegrasp_drake.events import MemorizedEventError, load_memorized_events
    from tegrasp_drake.rig import paths
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events)
    path = events / "box" / "reach_load.json"
    data = json.loads(path.read_text())
    data["transition_time_s"] = -50.0
    path.write_text(json.dumps(data))
    with pytest.raises(MemorizedEventError, match="transition_time_s"):
        load_memorized_events(events, "box")


# Rule: a transition's numbers are in their ranges when built: a Lift-Load's grip force is
# one the 2F-85 can give.
def test_a_transition_with_a_grip_force_beyond_the_gripper_is_refused():
    import tegrasp_drake as T
    with pytest.raises(ValueError, match="grip_force_n"):
        T.Transition(t=1.0, from_mode=T.Mode.LIFT, to_mode=T.Mode.LOAD,
                     trigger=list(T.Trigger)[0], reason="x", grip_force_n=1e9)


def test_recording_never_writes_a_first_contact_whose_force_falls():
    from tegrasp_drake.events.extraction import TactileTrial, extract_memorized_events
    t = np.arange(0, 1.0, 0.001)
    falling = 0.02 + 5.0 * (t < 0.5)  # a force that lets go at the "first contact"
    sa = np.column_stack([falling, falling])
    ra = np.column_stack([0.1 + (t > 0.5), 0.1 + (t > 0.5)])
    trial = TactileTrial(t_sa=t, sa=sa, t_ra=t, ra=ra, transition_times={"reach_load": 0.5})
    with pytest.raises(ValueError, match="'samples.sa_left' peaks before the first contact"):
        extract_memorized_events(trial, object_name="box", sa_rate_hz=100.0, ra_rate_hz=1000.0)


# Rule: an event's window was cut from the run its `scenario` field records, so it lies within
# that run: it ends by that scenario's time limit (a note's event, e.g. an ensemble's, by the
# longest run any scenario allows). A transition time past it is refused naming the file and
# the field, by a trial before it runs and by `tegrasp plot events`.
@pytest.mark.parametrize("folder, time, words", [
    ("box", 22.7, "ends after the time limit of the scenario it was recorded in"),
    ("box", 1e6, "ends after the time limit of the scenario it was recorded in"),
    ("ensemble/box", 1e6, "ends after the longest run any scenario allows"),
])
def test_an_event_whose_transition_lies_past_its_recorded_run_is_refused(
        folder, time, words, events_copy, no_simulation, capfd):
    path = events_copy / folder / "place_unload.json"  # the last: in grasp order still
    edit_json(path, lambda data: data.update(transition_time_s=time))
    argv = (["trial", "--events", str(events_copy)] if folder == "box" else
            ["trial", "--controller", "taxel_aware", "--events", str(events_copy)])
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, str(path), "field 'transition_time_s'", words,
                          "Remake it with")
    if folder == "box":
        code, text = run_cli(["plot", "events", "--events", str(events_copy), "--out",
                              str(events_copy / "p.png")], capfd)
        assert_one_line_error(code, text, str(path), "field 'transition_time_s'", words)
        assert not (events_copy / "p.png").exists()


# Rule: a recording cuts its windows at its scenario's sample rates, so an event whose rates
# (and windows, consistently) are not those of the scenario its `scenario` field records is
# refused naming the file and the rate's field.
def test_an_event_at_rates_its_recorded_scenario_does_not_sample_at_is_refused(events_copy):
    from tegrasp_drake.scenario.scenario import LoadScenario
    from tegrasp_drake.scenario.scenario_events import load_controller_events

    def at_100_hz(data):
        data["sa_rate_hz"] = 100.0
        for name in ("sa_left", "sa_right"):
            window = np.array(data["samples"][name][:50])
            data["samples"][name] = (window / np.abs(window).max()).tolist()
    for path in (events_copy / "box").glob("*.json"):
        edit_json(path, at_100_hz)
    edit_json(events_copy / INDEX_FILE, lambda data: [
        entry.update(sa_rate_hz=100.0) for entry in data["events"] if entry["object"] == "box"])
    assert load_memorized_events(events_copy, "box")["reach_load"].sa_rate_hz == 100.0
    with pytest.raises(MemorizedEventError) as refused:
        load_controller_events(LoadScenario(name="box"), events_copy)
    message = one_line_of(refused.value)
    for words in ("box/reach_load.json", "field 'sa_rate_hz' is 100 Hz",
                  "samples at 108 Hz (tactile.sample_rate_hz)"):
        assert words in message, message


# Rule: a window of ones is a quiet RA window, which only format_version 3 stores; a version-2
# file (windows as cut) holding one is refused naming the file and the channel.
def test_a_version_2_event_with_a_quiet_ra_window_is_refused(events_copy):
    path = events_copy / "prismatic" / "box" / "load_lift.json"

    def quiet(data):
        data["samples"]["ra_right"] = [1.0] * len(data["samples"]["ra_right"])
    edit_json(path, quiet)
    with pytest.raises(MemorizedEventError) as refused:
        load_memorized_events(events_copy / "prismatic", "box")
    message = one_line_of(refused.value)
    for words in (str(path), "field 'samples.ra_right' is a window of ones",
                  "format_version 2"):
        assert words in message, message


def test_every_committed_event_lies_within_its_recorded_run():
    from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
    from tegrasp_drake.scenario.scenario_events import recorded_run_problem
    root = pathlib.Path(tegrasp_drake.__file__).parent.parent
    checked = 0
    for index in sorted([*root.glob("events/**/index.json"),
                         *root.glob("analysis/**/events/**/index.json"),
                         *root.glob("analysis/*_events/**/index.json")]):
        folder = index.parent
        required = CORRECTIVE_TRANSITIONS if folder.name == "corrective" else ()
        for name in sorted({entry["object"] for entry in read_index(folder)}):
            for event in load_memorized_events(folder, name, required=required).values():
                assert recorded_run_problem(event) is None, (folder, name, event.transition)
                checked += 1
    assert checked >= 100


# Rule: an event file's scenario text that no scenario reader accepts (a Python object tag)
# makes the file damaged: refused by its reader naming the file and field, with how to
# remake it; a sweep says so as any unusable events folder (exit 1), as a trial does.
def test_an_event_whose_scenario_text_holds_a_python_tag_is_a_damaged_file(events_copy, capfd):
    path = events_copy / "box" / "reach_load.json"
    edit_json(path, lambda data: data.update(scenario="!!python/object/apply:os.system [ls]"))
    for argv in (["trial", "--events", str(events_copy)],
                 ["sweep", "--dry-run", "--events", str(events_copy), "--objects", "box",
                  "--controllers", "memorized", "--attempts", "1", "--out",
                  str(events_copy.parent / "sweep")]):
        code, text = run_cli(argv, capfd)
        assert code == 1, text
        assert_one_line_error(code, text, f"{path}: field 'scenario': line 1, column 1",
                              "Python object tag", "tegrasp record-events --object box")


# Rule: the public loader names an unknown transition in its argument `required` as the
# argument's fault, not the events folder's (which would send the user to record again).
def test_a_required_transition_that_does_not_exist_is_the_arguments_fault():
    with pytest.raises(ValueError, match="argument 'required' names 'bogus', no transition; "
                                         "the transitions are reach_load, "):
        load_memorized_events(paths.package_events_dir(), "box", required=["bogus"])


# Rule: an object's grasp events in one folder are cut from one ideal grasp: their
# transition_time_s increase in grasp order, and they carry that grasp's scenario text, whose
# object is the one each file names (object, object_description). A folder that breaks this
# is refused naming the file and the field, by a trial before it runs and by
# `tegrasp plot events`, exit 1.
def _set_in_box_file(transition: str, edit):
    """A spoil that applies `edit` to the box's `transition` file and its index entry."""
    def spoil(folder):
        edit_json(folder / "box" / f"{transition}.json", edit)
        edit_json(folder / INDEX_FILE, lambda data: [
            edit(entry) for entry in data["events"]
            if (entry["object"], entry["transition"]) == ("box", transition)])
    return spoil


def _in_scenario(old: str, new: str):
    def edit(data):
        assert old in data["scenario"]
        data["scenario"] = data["scenario"].replace(old, new, 1)
    return edit


def _in_every_box_scenario(old: str, new: str):
    def spoil(folder):
        for transition in ("reach_load", "load_lift", "place_unload"):
            _set_in_box_file(transition, _in_scenario(old, new))(folder)
    return spoil


def _file_time(seconds: float):
    return lambda data: data.update(transition_time_s=seconds) if "samples" in data else None


@pytest.mark.parametrize("spoil, file, expected", [
    (_set_in_box_file("place_unload", _file_time(1.0)), "place_unload.json",
     "field 'transition_time_s' is 1 s, not after load_lift's"),
    (_set_in_box_file("load_lift", _file_time(2.0)), "load_lift.json",
     "field 'transition_time_s' is 2 s, not after reach_load's"),
    (_in_every_box_scenario("mass: 0.15", "mass: 0.5"), "reach_load.json",
     "mass 0.5 (field 'scenario') != 0.15 (field 'object_description')"),
    (_in_every_box_scenario("  name: box", "  name: thin_cylinder"), "reach_load.json",
     "field 'scenario' grasps object 'thin_cylinder', but field 'object' is 'box'"),
    (_set_in_box_file("load_lift", _in_scenario("random_seed: 0", "random_seed: 5")),
     "load_lift.json", "field 'scenario' differs from reach_load's (line 1: 'random_seed: 5'"),
    (_set_in_box_file("load_lift", _in_scenario("hit_time_s: -1.0", "hit_time_s: 4.0")),
     "load_lift.json", "'  hit_time_s: 4.0' here, '  hit_time_s: -1.0' there"),
])
def test_an_objects_events_that_no_one_grasp_gives_are_refused(spoil, file, expected,
                                                               events_copy, no_simulation,
                                                               capfd):
    spoil(events_copy)
    path = events_copy / "box" / file
    code, text = run_cli(["trial", "--events", str(events_copy)], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, str(path), expected, "Remake it with")
    code, text = run_cli(["plot", "events", "--events", str(events_copy), "--out",
                          str(events_copy / "p.png")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, str(path), expected)
    assert not (events_copy / "p.png").exists()


# Rule: corrective events come from runs of their own, one per situation: an object's
# corrective events keep their own scenario text and times, which the one-grasp rule leaves
# alone; they still share the object's description, window and rates.
def test_an_objects_corrective_events_need_not_share_a_grasp_but_an_object(events_copy):
    corrective = events_copy / "corrective"
    events = load_memorized_events(corrective, "box", required=("lift_load", "hold_avoid"))
    assert events["lift_load"].scenario != events["hold_avoid"].scenario
    _set_in_box_file("hold_avoid", lambda data: data["object_description"].update(
        mass=0.2))(corrective)
    with pytest.raises(MemorizedEventError,
                       match=r"hold_avoid.json: field 'object_description' differs from "
                             r"lift_load's: mass 0.2 \(here\) != 0.15"):
        load_memorized_events(corrective, "box", required=("lift_load", "hold_avoid"))
