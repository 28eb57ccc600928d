"""A writer removes only its own kind's leftovers: the staging files of the very file it is
about to write (`.NAME.<pid>.staging`, with staged_file's random part or without), left by a
process that has ended, holding what that file holds (or nothing yet). A file of the user's
that only looks like one (another name, other content, a link) stays."""

import os
import struct

from tests.commands.test_run_folder import _ended_process_id
from tests.test_bad_input_probes import _events
from tegrasp_drake.commands.run_folder import staging_file_beside
from tegrasp_drake.events.events_folder import save_memorized_events

LCM_LOG_START = struct.pack(">I", 0xEDA1DA01)  # an LCM log's first event's sync word


def _write_all(files: dict) -> None:
    for path, data in files.items():
        path.write_bytes(data)


# Rule: a hardware run's log staging removes the killed runs' staging logs of that --log
# alone, and only those holding an LCM log (or nothing, or the start of a sync word).
def test_a_log_staging_removes_the_same_logs_leftovers_and_keeps_the_users_files(tmp_path):
    dead = _ended_process_id()
    users = {tmp_path / f".txt.lcmlog.{dead}.staging": b"not a log",
             tmp_path / f".other.lcmlog.{dead}.staging": LCM_LOG_START + b"another log",
             tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging": b"not a log either"}
    left = {tmp_path / f".kill.lcmlog.{dead}.staging": LCM_LOG_START + b"events",
            tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging": b"",
            tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging": LCM_LOG_START[:2]}
    live = tmp_path / f".kill.lcmlog.{os.getppid()}.staging"
    _write_all({**users, **left, live: LCM_LOG_START})
    link = tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging"
    link.symlink_to(tmp_path / f".txt.lcmlog.{dead}.staging")
    staging_file_beside(tmp_path / "kill.lcmlog", LCM_LOG_START)
    assert all(path.read_bytes() == data for path, data in users.items())
    assert link.is_symlink() and live.exists()
    assert not any(path.exists() for path in left)


# Rule: saving events removes the ended writers' staging files of the files it writes (JSON),
# and nothing else of the events folder's.
def test_saving_events_keeps_the_users_files_named_like_staging_files(tmp_path):
    dead = _ended_process_id()
    (tmp_path / "mine").mkdir()
    users = {tmp_path / f".notes.txt.{dead}.staging": b"{my notes}",
             tmp_path / "mine" / f".photo.json.{dead}.staging": b"{\"a\": 1}",
             tmp_path / f".index.json.abcd1234.{dead}.staging": b"not JSON"}
    left = {tmp_path / f".index.json.k2j4h5g6.{dead}.staging": b"{\"format\"",
            tmp_path / "mine" / f".reach_load.json.x_y0z9w8.{dead}.staging": b""}
    _write_all({**users, **left})
    save_memorized_events(tmp_path, _events())
    assert all(path.read_bytes() == data for path, data in users.items())
    assert not any(path.exists() for path in left)
