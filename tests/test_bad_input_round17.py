"""Bad inputs the seventeenth review found, one test per rule."""

import json
import pathlib
import shutil

import pytest

from tegrasp_drake import cli
from tegrasp_drake.rig.paths import package_events_dir
from tests.test_bad_input import assert_one_line_error, run_cli


def _events_copy(tmp_path, entries=None) -> pathlib.Path:
    """A copy of the package's events folder; `entries` (a function of the index's entries)
    rewrites the index."""
    folder = tmp_path / "events"
    shutil.copytree(package_events_dir(), folder)
    if entries is not None:
        index = json.loads((folder / "index.json").read_text())
        index["events"] = entries(index["events"])
        (folder / "index.json").write_text(json.dumps(index))
    return folder


# Rule: an events index that lists no events is a damaged events folder, refused where the
# index is read (so every reader of it, the plot, a trial, a sweep, names it alike) in one
# line naming the index and how to remake it; not an internal error of the figure.
def test_an_index_listing_no_events_is_refused_naming_it(tmp_path, capfd):
    from tegrasp_drake.events import MemorizedEventError, read_index
    folder = _events_copy(tmp_path, entries=lambda entries: [])
    with pytest.raises(MemorizedEventError, match="lists no events"):
        read_index(folder)
    code, error = run_cli(["plot", "events", "--events", str(folder),
                           "--out", str(tmp_path / "events.png")], capfd)
    assert code == 1, error
    assert_one_line_error(code, error, "index.json", "lists no events")
    assert not (tmp_path / "events.png").exists()
