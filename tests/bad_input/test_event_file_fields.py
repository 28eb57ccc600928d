"""Every field of an event file and of index.json has a declared type
(event_file.EVENT_FIELD_KINDS, INDEX_FIELD_KINDS, INDEX_ENTRY_KINDS): a null where a value is
required, a value of another type or a key that is no field is refused naming the file and
the field, never loaded. The writer writes exactly the declared fields."""

import json

import pytest

from tegrasp_drake.events.event_file import (EVENT_FIELD_KINDS, INDEX_ENTRY_KINDS,
                                             INDEX_FIELD_KINDS, MemorizedEventError,
                                             event_to_json)
from tegrasp_drake.events.events_folder import load_memorized_events, save_memorized_events
from tests.bad_input.probes import edit_json, memorized_events


@pytest.mark.parametrize("field", sorted(set(EVENT_FIELD_KINDS) - {"format", "format_version"}))
def test_a_null_event_file_field_is_refused_naming_file_and_field(field, events_copy):
    path = events_copy / "box" / "reach_load.json"
    edit_json(path, lambda data: data.update({field: None}))
    with pytest.raises(MemorizedEventError) as refused:
        load_memorized_events(events_copy, "box")
    message = str(refused.value)
    assert message.startswith(f"{path}: field '{field}' is null, where the file must hold "
                              f"{'an' if EVENT_FIELD_KINDS[field][0] in 'aeiou' else 'a'} "
                              f"{EVENT_FIELD_KINDS[field]}"), message
    assert "\n" not in message and "record-events --object box" in message, message


@pytest.mark.parametrize("field, value, kind", [
    ("physical_event", 3, "a text"), ("channels", ["sa_left", 2, "ra_left", "ra_right"],
                                      "a list of texts"),
    ("package_versions", {"drake": 1.51}, "an object of texts")])
def test_an_event_file_field_of_another_type_is_refused(field, value, kind, events_copy):
    path = events_copy / "box" / "reach_load.json"
    edit_json(path, lambda data: data.update({field: value}))
    with pytest.raises(MemorizedEventError, match=f"reach_load.json: field '{field}' is not "
                                                  f"{kind}"):
        load_memorized_events(events_copy, "box")


@pytest.mark.parametrize("change, words", [
    (lambda data: data.update(notes="mine"),
     "field 'notes' is not a field of an index (FORMAT.md lists them)"),
    (lambda data: data.update(remake_command=None),
     "field 'remake_command' is null, where the file must hold a text"),
    (lambda data: data.update(events=None), "field 'events' is null, where the file must hold "
                                            "a list"),
    (lambda data: data["events"][0].update(notes="mine"),
     "field 'events[0].notes' is not a field of an index entry"),
    (lambda data: data["events"][1].update(scenario=None),
     "field 'events[1].scenario' is null, where the file must hold a text"),
    (lambda data: data["events"][0].update(window_s="0.5"),
     "field 'events[0].window_s' is not a number"),
], ids=["unknown-key", "null-remake-command", "null-events", "unknown-entry-key",
        "null-entry-field", "entry-field-type"])
def test_an_index_with_an_unknown_null_or_mistyped_field_is_refused(change, words,
                                                                    events_copy):
    index = events_copy / "index.json"
    edit_json(index, change)
    with pytest.raises(MemorizedEventError) as refused:
        load_memorized_events(events_copy, "box")
    message = str(refused.value)
    assert message.startswith(f"{index}: {words}"), message


def test_the_writer_writes_exactly_the_declared_fields(tmp_path):
    events = memorized_events()
    save_memorized_events(tmp_path, events)
    index = json.loads((tmp_path / "index.json").read_text())
    assert set(index) == set(INDEX_FIELD_KINDS)
    assert all(set(entry) == set(INDEX_ENTRY_KINDS) for entry in index["events"])
    assert all(set(event_to_json(event)) == set(EVENT_FIELD_KINDS) for event in events)
    assert set(load_memorized_events(tmp_path, "mine")) == {e.transition for e in events}
