"""Hostile files and names, each refused in one line that says what the file is: a trial log
declaring a huge array over a few kB is refused from its .npy headers, before any array is
decompressed; a file that is no zip archive is no trial log (never numpy's pickle advice); a
cut-short or damaged log is told apart from an earlier version's; a symbolic-link loop is
said to be one, never the disk's fault; a misspelt object field is no field, never one "set
per trial"; a world's settings file is read to a bound and its difference told in a line."""

import io
import json
import struct
import textwrap
import zipfile
import zlib

import numpy as np
import numpy.lib.format as npy_format
import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.bad_input.probes import assert_one_line_error, run_cli, trial_log


def _raw_deflate(data: bytes) -> bytes:
    compressor = zlib.compressobj(9, zlib.DEFLATED, -15)
    return compressor.compress(data) + compressor.flush()


def _zip_of(path, members):
    """Writes the zip archive of `members` [(name, deflated bytes, CRC-32, size)] to `path`, by
    hand (PKWARE APPNOTE 4.3): what it declares is what the test says, not what zipfile would
    compute."""
    body, directory = b"", b""
    for name, data, crc, size in members:
        name = name.encode()
        offset = len(body)
        body += struct.pack("<4s5H3L2H", b"PK\x03\x04", 20, 0, 8, 0, 0, crc, len(data), size,
                            len(name), 0) + name + data
        directory += struct.pack("<4s6H3L5H2L", b"PK\x01\x02", 20, 20, 0, 8, 0, 0, crc,
                                 len(data), size, len(name), 0, 0, 0, 0, 0, offset) + name
    end = struct.pack("<4s4H2LH", b"PK\x05\x06", 0, 0, len(members), len(members),
                      len(directory), len(body), 0)
    with open(path, "wb") as file:
        file.write(body + directory + end)
    return path


def _log_with_huge_taxels(path, rows: int):
    """A small well-formed trial log whose 'taxels' member declares (rows, 24) float64 in its
    .npy header, followed by 64 kB of its zeros and then not by the rest of that data but by
    bytes that are no deflate stream: reading the array would fail (and numpy would allocate
    rows * 192 bytes first)."""
    trial_log(path)
    with zipfile.ZipFile(path) as archive:
        members = [(info.filename, archive.read(info)) for info in archive.infolist()]
    header = io.BytesIO()
    npy_format.write_array_header_1_0(header, {"descr": "<f8", "fortran_order": False,
                                               "shape": (rows, 24)})
    # Stored (level 0) deflate blocks: 64 kB of valid stream, more than zipfile reads ahead
    # for the header, then bytes that are no deflate block.
    compressor = zlib.compressobj(0, zlib.DEFLATED, -15)
    declared = (compressor.compress(header.getvalue() + bytes(65_536))
                + compressor.flush(zlib.Z_FULL_FLUSH))
    garbage = b"\xff" * 4096  # block type 3: invalid, were it ever decompressed
    entries = []
    for name, data in members:
        if name == "taxels.npy":
            entries.append((name, declared + garbage, 0, len(header.getvalue()) + rows * 192))
        else:
            entries.append((name, _raw_deflate(data), zlib.crc32(data), len(data)))
    return _zip_of(path, entries)


# Rule: a trial log whose .npy headers declare arrays of other shapes than its time bases give
# (a 500 MB 'taxels' over 11 samples of 't_sa', in a 10 kB file) is refused from the headers,
# before any array is decompressed, in the words a log read whole gets.
@pytest.mark.parametrize("argv", [["plot", "trial", "LOG", "--out", "x.png"],
                                  ["emulate", "myrio", "--trial", "LOG"]])
def test_a_trial_log_declaring_a_huge_array_is_refused_before_decompressing(
        argv, tmp_path, monkeypatch, capfd, no_array_is_read):
    monkeypatch.chdir(tmp_path)
    rows = 500 * 2**20 // 192
    log = _log_with_huge_taxels(tmp_path / "trial.npz", rows)
    assert log.stat().st_size < 100_000
    code, text = run_cli([str(log) if a == "LOG" else a for a in argv], capfd)
    assert_one_line_error(code, text, "trial.npz", f"'taxels' has shape ({rows}, 24), but 11 "
                          "samples of 't_sa' need (11, 24) (from its .npy headers)")


def test_the_python_api_refuses_a_huge_declared_array_from_the_headers(tmp_path,
                                                                      no_array_is_read):
    from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
    log = _log_with_huge_taxels(tmp_path / "trial.npz", 10**6)
    with pytest.raises(TrialLogError, match=r"'taxels' has shape \(1000000, 24\)"):
        load_trial_log(log)


def _zip_after_bytes(path):
    good = trial_log(path.with_name("good.npz"))
    path.write_bytes(b"my own notes\n" + good.read_bytes())  # zipfile reads it; numpy unpickles
    return path


def _npy(path):
    with open(path, "wb") as file:  # np.save would add .npy to the name
        np.save(file, np.ones(3))
    return path


# Rule: a file that does not start as a zip archive is no trial log, said so naming it; never
# numpy's advice to load pickled data, never a traceback (an .npy read as an array).
@pytest.mark.parametrize("make, start", [
    (lambda p: p.write_bytes(bytes(range(200))) and p, "the bytes 00 01 02 03"),
    (_npy, "an .npy array's magic"),
    (_zip_after_bytes, "the bytes 6d 79 20 6f"),
], ids=["raw", "npy", "zip-after-bytes"])
@pytest.mark.parametrize("argv", [["plot", "trial", "LOG", "--out", "x.png"],
                                  ["emulate", "myrio", "--trial", "LOG"]])
def test_a_file_that_is_no_zip_archive_is_no_trial_log(make, start, argv, tmp_path,
                                                       monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "given.npz"
    make(path)
    code, text = run_cli([str(path) if a == "LOG" else a for a in argv], capfd)
    assert_one_line_error(code, text, f"'{path}' is not a trial log (an .npz zip archive "
                          f"written by tegrasp): it starts with {start}")
    assert "pickle" not in text and "internal error" not in text, text


def _without_member(path, member):
    trial_log(path)
    with zipfile.ZipFile(path) as archive:
        members = [(info.filename, archive.read(info)) for info in archive.infolist()]
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in members:
            if name != member:
                archive.writestr(name, data)
    return path


def _cut_short(path):
    data = trial_log(path).read_bytes()
    path.write_bytes(data[:len(data) * 2 // 3])


def _member_changed(path):
    """A byte of 't_ra's compressed data changed: its CRC-32 no longer matches."""
    trial_log(path)
    with zipfile.ZipFile(path) as archive:
        info = archive.getinfo("t_ra.npy")
    data = bytearray(path.read_bytes())
    start = info.header_offset + 30 + len(info.filename) + len(info.extra)
    data[start + info.compress_size // 2] ^= 0x01
    path.write_bytes(bytes(data))


def _directory_past_the_end(path):
    """The end record's offset of the zip directory points past the end of the file: the
    system refuses the seek (EINVAL), which is the file's fault, not the disk's."""
    data = bytearray(trial_log(path).read_bytes())
    end = data.rfind(b"PK\x05\x06")
    data[end + 16:end + 20] = struct.pack("<I", 0xFFFFFFF0)
    path.write_bytes(bytes(data))


# Rule: a log of this package's that is cut short, whose bytes fail their CRC-32, or that lacks
# an array its metadata's format version holds is incomplete or damaged, and said to be not an
# earlier version's log.
@pytest.mark.parametrize("make, words", [
    (_cut_short, "is incomplete or damaged, not one an earlier version wrote: it starts as a "
                 "zip archive but has no zip directory at its end"),
    (_member_changed, "is incomplete or damaged, not one an earlier version wrote"),
    (lambda p: _without_member(p, "taxels.npy"), "is incomplete, not one an earlier version "
     "wrote: it lacks the arrays ['taxels'], which every log of its format version 1 holds"),
    (_directory_past_the_end, "is incomplete or damaged"),
], ids=["cut-short", "crc", "member-missing", "directory-past-the-end"])
@pytest.mark.parametrize("argv", [["plot", "trial", "LOG", "--out", "x.png"],
                                  ["emulate", "myrio", "--trial", "LOG"]])
def test_an_incomplete_or_damaged_log_is_not_called_an_earlier_versions(make, words, argv,
                                                                        tmp_path, monkeypatch,
                                                                        capfd):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "t.npz"
    make(path)
    code, text = run_cli([str(path) if a == "LOG" else a for a in argv], capfd)
    assert_one_line_error(code, text, f"trial log '{path}' {words}", "run the trial again")


def _loop(folder, name):
    """`name` in `folder`: a symbolic link to a link back to it (ELOOP on any open)."""
    (folder / f"other-{name}").symlink_to(folder / name)
    (folder / name).symlink_to(folder / f"other-{name}")
    return folder / name


# Rule: a symbolic-link loop given as an input or output is said to be one, naming the path,
# with what to do about the link; never the disk's or file system's fault.
@pytest.mark.parametrize("argv", [
    ["trial", "--scenario", "LOOP.yaml", "--scenario-name", "x"],
    ["sweep", "--spec", "LOOP.yaml", "--out", "sw"],
    ["plot", "trial", "LOOP.npz", "--out", "x.png"],
    ["plot", "trial", "LOG", "--out", "LOOP.png"],
    ["trial", "--out", "LOOP"],
])
def test_a_symbolic_link_loop_is_said_to_be_one(argv, tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    log = trial_log(tmp_path / "trial.npz")
    argv = [str(_loop(tmp_path, "loop" + a.removeprefix("LOOP"))) if a.startswith("LOOP")
            else str(log) if a == "LOG" else a for a in argv]
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, "loop", "symbolic-link loop")
    assert "disk" not in text and "Too many levels" not in text, text


def _override_refusal(tmp_path, override):
    from tegrasp_drake.sweep.spec_file import LoadSweepSpec
    spec = tmp_path / "s.yaml"
    spec.write_text("objects: [box]\ncontrollers: [memorized]\ngrid: [[0.0, 0.0]]\n"
                    f"attempts: 1\nbase_seed: 640\nscenario_overrides: ['{override}']\n")
    with pytest.raises(ConfigError) as refused:
        LoadSweepSpec(spec)
    return str(refused.value)


# Rule: an override naming no field of the object section (a misspelt `object.mas`, or a
# mapping `object={mas: 0.2}`) is said to be no field, with the nearest names; only a real field
# of a section the sweep sets per trial is called one set per trial.
@pytest.mark.parametrize("override", ["object.mas=0.2", "object={mas: 0.2}"])
def test_a_misspelt_object_field_is_no_field_not_one_set_per_trial(tmp_path, override):
    text = _override_refusal(tmp_path, override)
    assert "'object.mas' is not a field of the object section (nearest: mass" in text, text
    assert "per trial" not in text, text


def test_a_real_object_field_is_still_one_the_sweep_sets_per_trial(tmp_path):
    assert "'object.mass' is set per trial by the sweep" in _override_refusal(tmp_path,
                                                                             "object.mass=0.2")


def test_a_transfer_worlds_misspelt_object_field_is_no_field(tmp_path):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "transfer.yaml"
    spec.write_text(textwrap.dedent("""\
        worlds:
          ideal: {scenario: memorizing_world, overrides: ['object.mas=0.2']}
          faithful: {scenario: faithful_world}
        cells: [[ideal, faithful]]
        sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], attempts: 1,
                base_seed: 600}
        """))
    with pytest.raises(ConfigError, match=r"'object.mas' is not a field of the object section "
                                          r"\(nearest: mass") as refused:
        LoadTransferSpec(spec)
    assert "per trial" not in str(refused.value)


def _transfer_spec(tmp_path):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    path = tmp_path / "transfer.yaml"
    path.write_text(textwrap.dedent("""\
        worlds:
          ideal: {scenario: memorizing_world}
          faithful: {scenario: faithful_world}
        cells: [[ideal, faithful]]
        sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], attempts: 1,
                base_seed: 600}
        """))
    return LoadTransferSpec(path)


# Rule: a world's settings file (world.json) is read to 4 times what this package writes there
# and 64 kB, refused from its size past that (a 2 MB list is never parsed), and settings that
# differ are told by the first differing one in a short line, never the file echoed.
def test_a_world_file_larger_than_a_worlds_settings_is_refused_from_its_size(tmp_path,
                                                                            monkeypatch):
    from tegrasp_drake.rig import files
    from tegrasp_drake.transfer.matrix import record_world_events
    folder = tmp_path / "events" / "ideal"
    folder.mkdir(parents=True)
    (folder / "world.json").write_text(json.dumps(["gripper.model=1"] * 100_000))
    monkeypatch.setattr(files, "load_json", lambda *a: pytest.fail("the file was parsed"))
    with pytest.raises(files.JsonFileError, match="is larger than .* bytes, more than this "
                                                  "world's settings file holds"):
        record_world_events(_transfer_spec(tmp_path), "ideal", folder)


def test_a_world_file_of_other_settings_is_told_by_its_first_difference(tmp_path):
    from tegrasp_drake.sweep.runner import SweepError
    from tegrasp_drake.transfer.matrix import record_world_events
    folder = tmp_path / "events" / "ideal"
    folder.mkdir(parents=True)
    (folder / "world.json").write_text(json.dumps(["gripper.model=" + "x" * 5000, "a=1"]))
    with pytest.raises(SweepError) as refused:
        record_world_events(_transfer_spec(tmp_path), "ideal", folder)
    text = str(refused.value)
    assert "recorded with other settings (setting 1 is 'gripper.model=xxx" in text, text
    assert " there, " in text and "in this world)" in text, text
    difference = text.split("other settings (")[1].split("); give")[0]
    assert len(difference) < 160, difference
    assert "a=1" not in text, text
