"""Two processes saving memorized events into one folder: the save holds the folder (the hold
`tegrasp record-events` takes), so one cannot read the index while the other is between
reading and writing it, and drop the other's entries."""

import subprocess
import sys

import pytest

from tegrasp_drake.events.event_file import INDEX_FILE, read_index
from tegrasp_drake.events.events_folder import (EventsDestinationError,
                                                load_all_memorized_events,
                                                save_memorized_events)
from tests import killed_runs
from tests.events.test_format import make_events

# A child that saves "cup" and stops at its first staged file (after it has read the index,
# before it writes any file), says so, and goes on when told to.
_PAUSED_SAVER = """
import sys
from tegrasp_drake.events import events_folder
from tests.events.test_format import make_events
staged_file = events_folder.staged_file
def paused_staged_file(*arguments, **options):
    if not paused_staged_file.paused:
        paused_staged_file.paused = True
        print("paused", flush=True)
        sys.stdin.readline()
    return staged_file(*arguments, **options)
paused_staged_file.paused = False
events_folder.staged_file = paused_staged_file
events_folder.save_memorized_events(sys.argv[1], make_events("cup").values())
"""


def _listed_objects(folder) -> set[str]:
    return {entry["object"] for entry in read_index(folder)}


@pytest.fixture
def folder(tmp_path):
    """An events folder whose index lists one object already."""
    save_memorized_events(tmp_path, make_events("box").values())
    return tmp_path


def test_a_save_during_another_processs_save_leaves_both_objects_in_the_index(folder):
    child = subprocess.Popen([sys.executable, "-c", _PAUSED_SAVER, str(folder)],
                             env=killed_runs.environment(), stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "paused", child.stderr.read()
        try:  # the child has read the index and not yet written it
            save_memorized_events(folder, make_events("mug").values())
            refused = False
        except EventsDestinationError:
            refused = True
        _, err = child.communicate("go\n", timeout=300)  # a bound on a hang, not a measure
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert child.returncode == 0, err
    if refused:  # as a script would, once the other save has ended
        save_memorized_events(folder, make_events("mug").values())
    assert _listed_objects(folder) == {"box", "cup", "mug"}
    assert sorted(load_all_memorized_events(folder)) == ["box", "cup", "mug"]


def test_a_save_while_another_process_holds_the_folder_is_refused_in_one_line(folder):
    before = (folder / INDEX_FILE).read_bytes()
    child = subprocess.Popen(
        [sys.executable, "-c", "import sys\nfrom tegrasp_drake.rig.files import held_folder\n"
         "with held_folder(sys.argv[1]):\n    print('held', flush=True)\n"
         "    sys.stdin.readline()\n", str(folder)],
        env=killed_runs.environment(), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "held", child.stderr.read()
        with pytest.raises(EventsDestinationError) as raised:
            save_memorized_events(folder, make_events("mug").values())
    finally:
        child.communicate("go\n", timeout=300)
    assert str(raised.value) == (f"{folder}: another process is saving or recording events "
                                 "there now; wait for it to end, or give another folder")
    assert (folder / INDEX_FILE).read_bytes() == before
    assert not (folder / "mug").exists()


def test_a_save_inside_this_processs_hold_of_the_folder_shares_it(folder):
    from tegrasp_drake.events.events_folder import held_events_folder
    with held_events_folder(folder):  # as record-events holds it for its whole recording
        save_memorized_events(folder, make_events("mug").values())
    assert _listed_objects(folder) == {"box", "mug"}
