"""Trial logs made or edited by hand, written as TrialLog.save writes them: with the checksum
of what they hold (trial_log_file.trial_log_checksum), so that a test of a check on a log's
contents meets that check and not the checksum's. The one helper every test that writes a
trial log's file itself uses (no tests here)."""

import json

import numpy as np

from tegrasp_drake.scenario.trial_log_file import (ARRAY_FIELDS, CHECKSUM_FIELD,
                                                   trial_log_checksum)


def read_trial_log_contents(path) -> dict:
    """{member name: array} of a trial log's .npz (its 'meta' the array of its JSON text)."""
    with np.load(path) as data:
        return {name: data[name] for name in data.files}


def write_trial_log_contents(path, contents: dict, *, compressed: bool = True):
    """Writes `contents` ({member: array}; 'meta' a dict or the array of its JSON text) to
    `path` (a file name or a binary file) as an .npz, with meta 'checksum' that of the rest
    when the metadata is a JSON object and every array of a trial log is there (else as given:
    the log is refused for what it lacks first). Returns `path`."""
    contents = dict(contents)
    meta = contents.get("meta")
    if isinstance(meta, dict):
        meta = json.dumps(meta)
    if meta is not None:
        try:
            parsed = json.loads(str(meta))
        except ValueError:
            parsed = None
        if isinstance(parsed, dict) and all(name in contents for name in ARRAY_FIELDS):
            arrays = {name: np.asanyarray(contents[name]) for name in ARRAY_FIELDS}
            try:
                parsed[CHECKSUM_FIELD] = trial_log_checksum(parsed, arrays)
                meta = json.dumps(parsed)
            except (TypeError, ValueError):  # a probe's array of no bytes (objects)
                pass
        contents["meta"] = np.array(meta)
    (np.savez_compressed if compressed else np.savez)(path, **contents)
    return path


def edit_trial_log(source, path, change_meta=None, **arrays):
    """`source`'s log with change_meta(meta) applied to its metadata (a dict, changed in place)
    and `arrays` replacing its arrays, written to `path` with its checksum (a log that reads
    as written so: what the reader's other checks make of the edit is what a test sees)."""
    contents = read_trial_log_contents(source)
    meta = json.loads(str(contents["meta"]))
    if change_meta is not None:
        change_meta(meta)
    contents.update(arrays, meta=meta)
    return write_trial_log_contents(path, contents)
