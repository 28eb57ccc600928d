"""Reads are bounded and refuse what is not a regular file before reading: an endless or
oversized file stops at its limit, a named pipe is refused without blocking, a device is
refused by every reader, and a trial log declaring huge arrays is refused from its header."""

import json
import os
import subprocess
import sys
import zipfile

import numpy as np
import numpy.lib.format as npy_format
import pytest

from tegrasp_drake.rig import files
from tegrasp_drake.scenario.trial_log_file import ARRAY_FIELDS, FORMAT_VERSION
from tests.bad_input.probes import assert_one_line_error, one_error_line, run_cli


# --- bounded reads ------------------------------------------------------------------------

# Rule: every file input refuses a device, /dev/zero and /dev/null as /dev/urandom, in the same
# words, from fstat before a byte is read.
@pytest.mark.parametrize("argv", [
    ["trial", "--scenario", "DEVICE", "--scenario-name", "x"],
    ["record-events", "--scenario", "DEVICE", "--scenario-name", "x"],
    ["hardware", "--config", "DEVICE"],
    ["sweep", "--spec", "DEVICE", "--out", "sw"],
    ["transfer", "DEVICE", "--out", "tr"],
    ["sensitivity", "DEVICE", "--out", "se"],
])
@pytest.mark.parametrize("device", ["/dev/zero", "/dev/null", "/dev/urandom"])
def test_a_configuration_that_is_a_device_is_refused_as_one(argv, device, tmp_path,
                                                            monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli([device if a == "DEVICE" else a for a in argv], capfd)
    assert_one_line_error(code, text, device, "is a device, not a file; give a regular file")


def test_a_calibration_file_that_is_a_device_is_refused_as_one(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    for device in ("/dev/zero", "/dev/urandom"):
        (tmp_path / "hw.yaml").write_text(f"tactile: {{calibration_file: {device}}}\n")
        code, text = run_cli(["hardware", "--config", "hw.yaml"], capfd)
        assert_one_line_error(code, text, device, "is a device, not a file; give a regular file")


def test_read_bounded_stops_at_its_limit_on_a_file_that_grows():
    with pytest.raises(files.InputTooLargeError):
        files.read_bounded("/proc/self/status", 16)  # a regular file fstat sizes as 0 bytes


def _log_declaring(path, declared_shape, stored_bytes: int):
    """A small .npz with every trial-log array, whose 't_sa' header declares
    `declared_shape` float64 values over `stored_bytes` bytes of zeros."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in ("meta", *ARRAY_FIELDS):
            with archive.open(name + ".npy", "w", force_zip64=True) as member:
                if name == "meta":
                    npy_format.write_array(member, np.array(json.dumps(
                        {"format_version": FORMAT_VERSION})))
                    continue
                shape = declared_shape if name == "t_sa" else (2,)
                npy_format.write_array_header_1_0(
                    member, {"descr": "<f8", "fortran_order": False, "shape": shape})
                member.write(bytes(stored_bytes if name == "t_sa" else 16))
    return path


@pytest.mark.parametrize("argv", [["plot", "trial", "LOG", "--out", "x.png"],
                                  ["emulate", "myrio", "--trial", "LOG"]])
def test_a_trial_log_declaring_a_huge_array_is_refused_from_its_header(
        argv, tmp_path, monkeypatch, capfd, no_array_is_read):
    """A 4 GiB array declared over 40 kB of data: np.load would allocate 4 GiB first."""
    monkeypatch.chdir(tmp_path)
    log = _log_declaring(tmp_path / "trial.npz", (2**29,), 40_000)
    code, text = run_cli([str(log) if a == "LOG" else a for a in argv], capfd)
    assert_one_line_error(code, text, "trial.npz", "'t_sa' declares (536870912,) float64")


def test_arrays_over_the_limit_are_refused_before_they_are_read(tmp_path, no_array_is_read):
    from tegrasp_drake.rig.npz_headers import NpzHeaderError, checked_npz_arrays
    log = _log_declaring(tmp_path / "trial.npz", (5_000,), 40_000)
    with pytest.raises(NpzHeaderError, match="more than the 1000 this reads"):
        checked_npz_arrays(log, ("t_sa",), max_bytes=1000)


def test_a_fifo_is_refused_without_blocking(tmp_path):
    """In a child process with a time limit: a regression blocks in open(), not the suite."""
    fifo = tmp_path / "f.yaml"
    os.mkfifo(fifo)
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake", "trial", "--scenario",
                           str(fifo), "--scenario-name", "x"], capture_output=True, text=True,
                          timeout=600, cwd=tmp_path)
    assert done.returncode == 1
    assert "named pipe (FIFO)" in done.stderr


def test_read_bounded_refuses_what_is_not_a_file_before_reading(tmp_path):
    os.mkfifo(tmp_path / "fifo")
    for path, words in ((tmp_path / "fifo", "named pipe"), (tmp_path, "folder")):
        with pytest.raises(files.NotAFileError, match=words):
            files.read_bounded(path, 4096)
    for device in ("/dev/zero", "/dev/null"):
        with pytest.raises(files.NotAFileError, match="is a device, not a file"):
            files.read_bounded(device, 4096)
    assert files.file_problem(tmp_path / "none") == "does not exist"
    assert files.file_problem(tmp_path / "fifo").startswith("is a named pipe")


@pytest.mark.parametrize("trial", ["/dev/zero", "fifo"])
def test_emulate_myrio_refuses_a_trial_that_is_not_a_file_before_reading(tmp_path, trial,
                                                                         capfd):
    if trial == "fifo":
        trial = str(tmp_path / "t.npz")
        os.mkfifo(trial)
    code, text = run_cli(["emulate", "--scheduling", "normal", "myrio", "--trial", trial,
                          "--lcm-url", "udpm://239.255.76.67:8716?ttl=0"], capfd)
    assert code == 1
    errors = one_error_line(text)
    assert len(errors) == 1 and trial in errors[0] and "not a file" in errors[0], text


# Rule: a log given as a device is told what to give, whichever device it is: /dev/zero
# and /dev/null as /dev/urandom is.
@pytest.mark.parametrize("argv", [["replay"], ["plot", "trial", "--out", "x.png"]])
@pytest.mark.parametrize("device", ["/dev/zero", "/dev/null", "/dev/urandom"])
def test_a_log_given_as_a_device_is_told_to_give_a_regular_file(tmp_path, monkeypatch, capfd,
                                                                argv, device):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli([*argv[:2], device, *argv[2:]], capfd)
    assert code == 1
    assert_one_line_error(code, text, f"'{device}' is a device, not a file; give a regular file")


def test_every_npz_reader_refuses_a_device_before_reading():
    from tegrasp_drake.rig.npz_headers import NpzHeaderError, checked_npz_arrays
    with pytest.raises(NpzHeaderError, match="not a regular file"):
        checked_npz_arrays("/dev/zero", ("t",), max_bytes=10)


def _archive_of_empty_members(path, count):
    """A zip of `count` empty members: a few hundred kB whose central directory zipfile would
    read whole (a ZipInfo a member) before any header could be checked."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_STORED) as archive:
        for k in range(count):
            archive.writestr(f"a{k}.npy", b"")
    return path


@pytest.mark.parametrize("zip64", [False, True], ids=["zip", "zip64-end-record"])
def test_an_npz_of_too_many_members_is_refused_before_its_directory_is_read(
        zip64, tmp_path, monkeypatch, no_array_is_read):
    from tegrasp_drake.rig import npz_headers
    if zip64:  # zipfile writes the zip64 end records past this many members
        monkeypatch.setattr(zipfile, "ZIP_FILECOUNT_LIMIT", 1)
    log = _archive_of_empty_members(tmp_path / "trial.npz", 2_000)
    monkeypatch.undo()

    def no_directory_read(*args, **kwargs):
        raise AssertionError("the zip directory was read before its size was checked")
    monkeypatch.setattr(npz_headers.zipfile, "ZipFile", no_directory_read)
    monkeypatch.setattr(npy_format, "read_array", no_directory_read)
    with pytest.raises(npz_headers.NpzHeaderError,
                       match="its zip directory declares .* bytes of members, more than"):
        npz_headers.checked_npz_arrays(log, ("t_sa",), max_bytes=1000)


def test_a_trial_log_with_zip64_end_records_is_read(tmp_path, monkeypatch):
    """The directory's size is taken where zipfile takes it: the zip64 end record's."""
    from tegrasp_drake.rig.npz_headers import central_directory_bytes, checked_npz_arrays
    plain = tmp_path / "plain.npz"
    np.savez_compressed(plain, t=np.arange(3.0), x=np.ones(2))
    monkeypatch.setattr(zipfile, "ZIP_FILECOUNT_LIMIT", 1)
    zip64 = tmp_path / "zip64.npz"
    np.savez_compressed(zip64, t=np.arange(3.0), x=np.ones(2))
    monkeypatch.undo()
    assert zip64.read_bytes().count(b"PK\x06\x06") == 1
    assert central_directory_bytes(zip64) == central_directory_bytes(plain) > 0
    arrays = checked_npz_arrays(zip64, ("t", "x"), max_bytes=1000)
    assert arrays["t"].tolist() == [0.0, 1.0, 2.0]


@pytest.fixture
def nothing_is_read(monkeypatch):
    """Fails the test if a file opened by read_bounded is read (os.fdopen wraps its descriptor
    into the stream it reads)."""
    def refuse(*args, **kwargs):
        raise AssertionError("the file was read before its size was checked")
    monkeypatch.setattr(files.os, "fdopen", refuse)


def _sparse(path, size: int):
    with open(path, "wb") as stream:
        stream.truncate(size)  # sparse: no disk space used
    return path


# Rule: a regular file larger than its reader's limit is refused from its size (fstat of the
# file opened), before a byte of it is read: a 3 GB log cost a 1 GB read (1.24 GB RSS) to
# refuse. A device or pipe, which fstat cannot size, is still held to the limit by the read.
def test_a_regular_file_over_the_limit_is_refused_from_its_size_before_reading(
        tmp_path, nothing_is_read):
    big = _sparse(tmp_path / "big.bin", 4097)
    with pytest.raises(files.InputTooLargeError):
        files.read_bounded(big, 4096)


def test_a_regular_file_at_the_limit_is_read_whole(tmp_path):
    exact = tmp_path / "exact.bin"
    exact.write_bytes(b"x" * 4096)
    assert files.read_bounded(exact, 4096) == b"x" * 4096


def test_the_bounded_readers_refuse_an_oversized_file_without_reading_it(
        tmp_path, nothing_is_read):
    from tegrasp_drake.rig.typed_yaml import MAX_YAML_BYTES, ConfigError, read_yaml_text
    big = _sparse(tmp_path / "big.yaml", MAX_YAML_BYTES + 1)
    with pytest.raises(ConfigError, match=f"more than {MAX_YAML_BYTES} bytes of YAML"):
        read_yaml_text(big, "a scenario")
    with pytest.raises(files.JsonFileError, match="is larger than 1000 bytes"):
        files.read_json_file(big, limit=1000, kind="a record")


def test_replay_refuses_a_log_over_its_limit_from_its_size_saying_what_to_do(
        tmp_path, monkeypatch, capfd, nothing_is_read):
    from tegrasp_drake.runs.hardware_log_reader import MAX_RUN_LOG_BYTES
    monkeypatch.chdir(tmp_path)
    log = _sparse(tmp_path / "sparse.lcmlog", 3 * 2**30)
    assert log.stat().st_size > MAX_RUN_LOG_BYTES
    code, text = run_cli(["replay", "sparse.lcmlog"], capfd)
    assert code == 1
    assert_one_line_error(code, text, "run log 'sparse.lcmlog' is 3221225472 bytes",
                          f"more than the {MAX_RUN_LOG_BYTES} bytes", "lcm-logfilter",
                          "a shorter run")


def test_replay_refuses_a_log_larger_than_it_can_replay_in_about_a_gigabyte(
        tmp_path, monkeypatch, capfd, nothing_is_read):
    """A 300 MB log is refused from its size: the matcher's re-run holds about 4 times a
    log's tactile bytes (MAX_RUN_LOG_BYTES, 256 MiB; a 10-minute run logs about 230 MB)."""
    monkeypatch.chdir(tmp_path)
    _sparse(tmp_path / "long.lcmlog", 300_000_000)
    code, text = run_cli(["replay", "long.lcmlog"], capfd)
    assert_one_line_error(code, text, "run log 'long.lcmlog' is 300000000 bytes",
                          "more than the 268435456 bytes (256 MiB)", "lcm-logfilter")


def test_a_file_that_grows_after_its_size_is_taken_is_read_to_its_bound(tmp_path, monkeypatch):
    """read_bounded reads a regular file with a buffer of the size fstat gave; one that grew
    since is read on, and still refused past the limit."""
    real_fstat = os.fstat

    def fstat_of_a_smaller_file(descriptor):
        status = list(real_fstat(descriptor))
        status[6] = 10  # st_size: the file as it was before it grew
        return os.stat_result(status)
    monkeypatch.setattr(files.os, "fstat", fstat_of_a_smaller_file)
    grown = tmp_path / "grown.bin"
    grown.write_bytes(b"y" * 3000)
    assert files.read_bounded(grown, 4096) == b"y" * 3000
    grown.write_bytes(b"y" * 5000)
    with pytest.raises(files.InputTooLargeError):
        files.read_bounded(grown, 4096)
