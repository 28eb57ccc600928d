"""Writing the user's files (rig/files.py): an interrupted or failed write leaves the old
file whole and no temporary behind; a claimed folder is never claimed twice."""

import os
import signal
import subprocess
import sys

import pytest

from tests.killed_runs import environment, killed_before_rename
from tegrasp_drake.rig.files import (claim_folder, folder_problem, interruptions_deferred,
                                     temporary_sibling, write_atomically)


def test_write_atomically_replaces_the_file_and_leaves_nothing_else(tmp_path):
    target = tmp_path / "events.yaml"
    target.write_text("old")
    write_atomically(target, "new ü", start=b"new")
    write_atomically(tmp_path / "data.bin", b"\x00\x01", start=b"\x00")
    assert target.read_bytes() == "new ü".encode("utf-8")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["data.bin", "events.yaml"]


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "events.yaml"
    target.write_text("old")
    with pytest.raises(TypeError):
        write_atomically(target, 12345, start=b"")  # neither text nor bytes: fails mid-write
    with pytest.raises(OSError):
        write_atomically(tmp_path / "missing" / "x.yaml", "data", start=b"data")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["events.yaml"]


def test_write_atomically_needs_the_kind_of_file_it_writes(tmp_path):
    with pytest.raises(TypeError, match="start"):  # no write without its clean-up
        write_atomically(tmp_path / "result.json", "{}")
    assert list(tmp_path.iterdir()) == []


# Each atomic writer of the package: the file it writes, and the statements that write it
# (TARGET: that file's path; a page it rewrites already holds `_PAGE`).
_PAGE = "# A page\n\n<!-- a table -->\nold\n<!-- end of a table -->\n"
_ATOMIC_WRITERS = {
    "a run's result": (
        "result.json", "from tegrasp_drake.commands.run_folder import write_result\n"
        "write_result(TARGET, {'ok': True})"),
    "a sweep record": (
        "trials/c.o.m.a1.json", "import pathlib\n"
        "from tegrasp_drake.sweep.records import write_record\n"
        "write_record(pathlib.Path(TARGET).parents[1], {'trial_id': 'c/o/m/a1'})"),
    "the emulators' station config": (
        "station.yaml", "from tegrasp_drake.emulators.launcher import Emulators\n"
        "Emulators(lcm_url='memq://').write_hardware_config(TARGET)"),
    "a generated docs table": (
        "page.md", "from tegrasp_drake.rig.generated_table import GeneratedTable\n"
        "GeneratedTable(name='a table', marker='a table', markdown=lambda: 'new\\n')"
        ".main(['--write', TARGET])"),
}


# Rule: every atomic write of the package removes what a write of that same file killed past
# its handlers (SIGKILL, the OOM killer, a power cut) left beside it.
@pytest.mark.parametrize("writer", sorted(_ATOMIC_WRITERS))
def test_each_atomic_writer_removes_what_a_killed_write_of_its_file_left(tmp_path, writer):
    name, statements = _ATOMIC_WRITERS[writer]
    target = tmp_path / name
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(_PAGE)
    statements = statements.replace("TARGET", repr(str(target)))
    killed_before_rename(statements)
    left = sorted(path.name for path in target.parent.iterdir())
    assert len(left) == 2 and target.read_text() == _PAGE, left  # the killed write's file
    subprocess.run([sys.executable, "-c", statements], env=environment(), check=True,
                   stdout=subprocess.DEVNULL, timeout=120)  # a bound on a hang
    assert sorted(target.parent.iterdir()) == [target]
    assert target.read_text() != _PAGE


def test_temporary_sibling_renames_on_success_and_removes_on_error(tmp_path):
    target = tmp_path / "trial.npz"
    with temporary_sibling(target, start=b"PK") as temporary:
        assert temporary.parent == tmp_path and temporary.name.startswith(".trial.npz.")
        temporary.write_text("done")
    assert target.read_text() == "done"
    with pytest.raises(RuntimeError):
        with temporary_sibling(target, start=b"PK") as temporary:
            temporary.write_text("half")
            raise RuntimeError("the writer failed")
    assert target.read_text() == "done"
    assert [p.name for p in tmp_path.iterdir()] == ["trial.npz"]


def test_ctrl_c_inside_the_block_is_acted_on_after_it():
    # Python's own Ctrl-C handler, whatever an earlier test left installed (restored after).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        finished = []
        with pytest.raises(KeyboardInterrupt):
            with interruptions_deferred():
                os.kill(os.getpid(), signal.SIGINT)
                finished.append(True)  # the block runs to its end first
        assert finished == [True]
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    finally:
        signal.signal(signal.SIGINT, previous)


def test_claim_folder_is_true_once(tmp_path):
    folder = tmp_path / "runs" / "run-1"
    assert claim_folder(folder) is True
    assert claim_folder(folder) is False
    assert folder.is_dir()


def test_folder_problem_names_a_file_in_the_way(tmp_path):
    blocker = tmp_path / "out"
    blocker.write_text("a file")
    assert folder_problem(blocker / "sweep") == f"{blocker} is not a folder"
    assert folder_problem(tmp_path / "new" / "deeper") is None


def test_replace_problem_names_a_folder_in_a_files_place_and_a_file_on_its_path(tmp_path):
    from tegrasp_drake.rig.files import replace_problem
    (tmp_path / "record.json").mkdir()
    assert "is a folder" in replace_problem(tmp_path / "record.json")
    (tmp_path / "plain").write_text("")
    assert f"{tmp_path / 'plain'} is not a folder" in replace_problem(tmp_path / "plain" / "x")
    os.mkfifo(tmp_path / "fifo")  # an atomic rename replaces a FIFO as it does a file
    assert replace_problem(tmp_path / "fifo") is None
    assert replace_problem(tmp_path / "new" / "deeper" / "x.json") is None


def test_a_json_integer_beyond_a_float_is_refused_without_converting_it():
    from tegrasp_drake.rig.files import JsonValueError, load_json
    with pytest.raises(JsonValueError, match="5000 digits"):
        load_json('{"a": ' + "9" * 5000 + "}")


@pytest.mark.skipif(not os.path.isdir("/dev/shm"), reason="no /dev/shm on this machine")
def test_an_output_file_may_go_to_a_ram_folder_in_dev_but_not_beside_the_device_nodes():
    from tegrasp_drake.rig.files import _filesystem_type, output_file_problem
    assert "is in /dev, not a place for files" in output_file_problem("/dev/x.html")
    assert "is a device" in output_file_problem("/dev/null")
    if _filesystem_type("/dev/shm") != "tmpfs":
        pytest.skip("/dev/shm is not a tmpfs mount here")
    assert output_file_problem("/dev/shm/x.html") is None
    assert "is in /proc" in output_file_problem("/proc/x.html")


def _is_object(data):
    return None if isinstance(data, dict) else "is not a JSON object"


JSON_DAMAGES = {  # name: (what is put at the path, the fact the error states)
    "missing": (lambda path: None, "file is missing"),
    "too large": (lambda path: path.write_bytes(b" " * 300_001), "is larger than 300000 bytes"),
    "not UTF-8": (lambda path: path.write_bytes(b'{"a": "\xff"}'), "is not UTF-8 text (byte 7)"),
    "truncated": (lambda path: path.write_text('{"a": [1,'), "is not valid JSON, perhaps trunc"),
    "duplicate key": (lambda path: path.write_text('{"a": 1, "a": 2}'), "appears twice"),
    "NaN": (lambda path: path.write_text('{"a": NaN}'), "holds NaN"),
    # Valid JSON syntax, but no Unicode text: the field is named.
    "lone surrogate": (lambda path: path.write_text('{"a": [{"b": "x\\ud800"}]}'),
                       "field 'a[0].b' holds \\ud800 at character 1, a lone UTF-16 surrogate"),
    "lone surrogate key": (lambda path: path.write_text('{"a": {"\\udc00": 1}}'),
                           "a key of field 'a' holds \\udc00"),
    "wrong top-level type": (lambda path: path.write_text("[1]"), "is not a JSON object"),
    "deep nesting": (lambda path: path.write_text("[" * 100_000 + "]" * 100_000),
                     "nests too deeply to be a test file"),
    "folder": (lambda path: path.mkdir(), "is a folder, not a file"),
    "FIFO": (os.mkfifo, "is a named pipe (FIFO), not a file"),
    "device": (lambda path: path.symlink_to("/dev/null"), "is a device, not a file"),
}


@pytest.mark.parametrize("damage", JSON_DAMAGES)
def test_a_json_file_that_cannot_be_read_is_one_error_naming_it_and_the_remedy(tmp_path,
                                                                                damage):
    from tegrasp_drake.rig.files import JsonFileError, UserPathError, read_json_file
    make, fact = JSON_DAMAGES[damage]
    path = tmp_path / "state.json"
    make(path)
    with pytest.raises(JsonFileError) as refused:
        read_json_file(path, limit=300_000, kind="a test file", check=_is_object,
                       remedy="remake it")
    message = str(refused.value)
    assert message.startswith(f"{path}: ") and message.endswith("; remake it"), message
    assert fact in refused.value.problem and "\n" not in message
    assert isinstance(refused.value, UserPathError)  # the commands say it in one line


def test_json_text_with_a_surrogate_pair_is_the_character_it_spells():
    from tegrasp_drake.rig.files import load_json
    assert load_json('{"a": "\\ud83d\\ude00"}') == {"a": "\U0001f600"}
    assert load_json(b'{"a": "\\u00e9"}') == {"a": "\u00e9"}


def test_a_sound_json_file_is_read_and_checked(tmp_path):
    from tegrasp_drake.rig.files import read_json_file
    (tmp_path / "state.json").write_text('{"a": [1, 2.5, "x"]}')
    assert read_json_file(tmp_path / "state.json", limit=1000, kind="a test file",
                          check=_is_object) == {"a": [1, 2.5, "x"]}
