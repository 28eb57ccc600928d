"""The arrays an .npz declares, checked from their .npy headers (names, dtypes, sizes)
before np.load, which would allocate whatever shape a few-kB file declares."""

import io
import math
import os
import stat
import struct
import tokenize
import zipfile
import zlib

import numpy as np
import numpy.lib.format as npy_format

from tegrasp_drake.rig.files import is_read_failure
from tegrasp_drake.rig.ranges import is_integer


# How an .npz file starts: a zip archive's first local file header (PKWARE APPNOTE 4.3.7).
NPZ_START = b"PK\x03\x04"
# 11 float64 columns at 20 kHz: 512 MB is 4.8 minutes, far beyond any trial
MAX_TRIAL_LOG_BYTES = 512 * 2**20


class NpzHeaderError(ValueError):
    """An .npz file's arrays are not what its reader accepts; the message says which."""


class NotAnNpzError(NpzHeaderError):
    """The file is no .npz at all: it does not start as a zip archive (an .npy, raw bytes, a
    zip behind other bytes); the message says what it starts with."""


class DamagedNpzError(NpzHeaderError):
    """The file starts as an .npz but is incomplete or damaged: cut short (no zip directory at
    its end), or a member's bytes differ from what its CRC-32 says was written."""


class DeclaredArraysError(NpzHeaderError):
    """The arrays an .npz's headers declare are not what its reader accepts (the reader's own
    check: their shapes, dtypes, rows); the message is the check's, in the reader's words."""


# dtype kinds a numeric log or its JSON metadata may hold: bool, integers, floats, text.
_ALLOWED_KINDS = frozenset("biufU")
# A plain array's .npy header is a few hundred bytes (64-byte multiples).
_MAX_HEADER_BYTES = 65_536
# zipfile reads the whole central directory the archive's end record declares, a ZipInfo
# a member, before a header can be checked: a file of millions of empty members would take
# gigabytes. An .npz's entry is 46 bytes, its name and a zip64 extra field (~100 bytes): a
# trial log's 14 arrays take under 2 kB, and 64 kB holds over 600 members.
MAX_CENTRAL_DIRECTORY_BYTES = 65_536
# The zip end records (PKWARE APPNOTE 4.3.14-4.3.16): signature, fixed size, and where the
# central directory's size lies in it.
_END_RECORD = (b"PK\x05\x06", 22, "<I", 12)
_ZIP64_LOCATOR = (b"PK\x06\x07", 20)
_ZIP64_END_RECORD = (b"PK\x06\x06", 56, "<Q", 40)


def central_directory_bytes(path) -> int | None:
    """The size of the central directory that the end record of the zip archive at `path`
    declares, the zip64 end record's where one is located (as zipfile reads it), from the
    file's last 64 kB; None when no end record is found (zipfile then refuses the file)."""
    signature, size, form, at = _END_RECORD
    with open(path, "rb") as file:
        length = file.seek(0, os.SEEK_END)
        tail_start = max(0, length - size - 65_535)  # the end record and its comment
        file.seek(tail_start)
        tail = file.read()
        end = tail.rfind(signature)
        if end < 0 or end + size > len(tail):
            return None
        declared = struct.unpack_from(form, tail, end + at)[0]
        locator = end - _ZIP64_LOCATOR[1]
        if locator < 0 or tail[locator:locator + 4] != _ZIP64_LOCATOR[0]:
            return declared
        signature, size, form, at = _ZIP64_END_RECORD
        offset = struct.unpack_from("<Q", tail, locator + 8)[0]
        if offset + size > length:
            return declared
        file.seek(offset)
        record = file.read(size)
        if record[:4] != signature:
            return declared
        return struct.unpack_from(form, record, at)[0]


def npz_array_headers(zip_file: zipfile.ZipFile) -> dict[str, tuple[tuple, np.dtype, int]]:
    """{array name: (shape, dtype, bytes of data)} of every member of an open .npz, from the
    headers alone; NpzHeaderError for a member that is not an .npy array, or for a second
    member of one array name (np.load would read one of them, the zip library's choice)."""
    headers = {}
    for info in zip_file.infolist():
        name = info.filename[:-4] if info.filename.endswith(".npy") else info.filename
        if name in headers:
            raise NpzHeaderError(f"'{info.filename}' is stored twice in the archive (which "
                                 "one is read would be the zip library's choice)")
        with zip_file.open(info) as member:
            shape, dtype = _read_npy_header(member, name)
            header_bytes = member.tell()
        if dtype.kind not in _ALLOWED_KINDS or dtype.hasobject or dtype.fields:
            raise NpzHeaderError(f"'{name}' holds {dtype} values; only numbers and text are "
                                 "read")
        if any(not is_integer(n) or n < 0 for n in shape):
            raise NpzHeaderError(f"'{name}' declares the shape {shape}")
        data_bytes = math.prod(shape) * dtype.itemsize
        if header_bytes + data_bytes != info.file_size:
            raise NpzHeaderError(f"'{name}' declares {shape} {dtype} ({data_bytes} bytes) but "
                                 f"its member holds {info.file_size - header_bytes} bytes")
        headers[name] = (tuple(shape), dtype, data_bytes)
    return headers


# The .npy format versions read, each with the size of its header-length field (numpy's
# format.py: a little-endian uint16 in 1.0, uint32 in 2.0).
_HEADER_LENGTH_FORMS = {(1, 0): "<H", (2, 0): "<I"}


def _read_npy_header(member, name: str) -> tuple[tuple, np.dtype]:
    """(shape, dtype) of the .npy array `member` (a zip member at its start) holds, read with
    numpy's header parser once the header's declared length is known to be a plain array's;
    NpzHeaderError in the package's words otherwise. numpy's own messages are not passed on:
    they advise `allow_pickle=True` or `max_header_size`, unsafe and not the user's to set."""
    try:
        version = npy_format.read_magic(member)
    except (ValueError, EOFError, OSError, zlib.error) as error:
        if is_read_failure(error):  # the disk's, not the file's: passed on as it is
            raise
        raise NpzHeaderError(f"'{name}' is not a numpy array (it lacks the .npy magic "
                             "string)") from None
    form = _HEADER_LENGTH_FORMS.get(version)
    if form is None:
        raise NpzHeaderError(f"'{name}' is of .npy format version "
                             f"{'.'.join(map(str, version))}, which this does not read")
    try:
        length_field = member.read(struct.calcsize(form))
        declared = struct.unpack(form, length_field)[0] if len(length_field) == len(
            struct.pack(form, 0)) else None
        if declared is not None and declared > _MAX_HEADER_BYTES:
            raise NpzHeaderError(f"'{name}' has a .npy header of {declared} bytes, more than "
                                 f"the {_MAX_HEADER_BYTES} of any array written here (a "
                                 "plain array's is a few hundred)")
        header = member.read(declared) if declared is not None else b""
    except (OSError, zlib.error) as error:
        if is_read_failure(error):
            raise
        header, declared = b"", None
    if declared is None or len(header) < declared:
        raise NpzHeaderError(f"'{name}' ends inside its .npy header")
    read_header = (npy_format.read_array_header_1_0 if version == (1, 0)
                   else npy_format.read_array_header_2_0)
    try:  # the header as read, so that no seek of the member is needed
        shape, _, dtype = read_header(io.BytesIO(length_field + header),
                                      max_header_size=_MAX_HEADER_BYTES)
    except (ValueError, EOFError, OSError, SyntaxError, tokenize.TokenError,
            zlib.error) as error:  # numpy parses the header's dict as Python
        if is_read_failure(error):
            raise
        raise NpzHeaderError(f"'{name}' has a .npy header that cannot be read as an "
                             "array's (its shape, dtype and order)") from None
    return shape, dtype


def checked_npz_arrays(path, names, *, max_bytes: int, optional=(), text=(),
                       max_text_chars: int | None = None, known=None,
                       kind="an .npz", declared_problem=None) -> dict[str, np.ndarray]:
    """The arrays `names` (and `optional` ones present) of the .npz at `path`, once their
    headers fit `max_bytes` and hold numbers (text for `text`, each at most `max_text_chars`
    characters when given; numpy stores 4 bytes a character), and (when `known`, the array
    names the format has, is given) it holds no other array; NpzHeaderError otherwise, naming
    `kind` (what the file is meant to be), before a byte is read when `path` is not a regular
    file (a FIFO or /dev/zero never ends). The system's error reading the file (EIO, EACCES:
    files.is_read_failure) is raised as that OSError, never as an NpzHeaderError: a file
    that could not be read is not a damaged one. `declared_problem`, given {name: (shape,
    dtype)} of every array the headers declare, says what is wrong with them (words, or None)
    before any array is decompressed: DeclaredArraysError. A file that does not start as a zip
    archive is NotAnNpzError (np.load would unpickle it, or read it as an .npy), one cut short
    or whose bytes fail their CRC-32 DamagedNpzError."""
    if not stat.S_ISREG(os.stat(path).st_mode):
        raise NpzHeaderError("it is not a regular file (a folder, named pipe or device); "
                             "give the trial.npz file")
    with open(path, "rb") as file:
        start = file.read(len(NPZ_START))
    if not start:
        raise DamagedNpzError("it is empty (0 bytes)")
    if start != NPZ_START:
        what = ("an .npy array's magic" if start.startswith(b"\x93NUM")
                else f"the bytes {start.hex(' ')}")
        raise NotAnNpzError(f"it starts with {what}, not a zip archive's "
                            f"({NPZ_START.hex(' ')})")
    directory = central_directory_bytes(path)
    if directory is not None and directory > MAX_CENTRAL_DIRECTORY_BYTES:
        raise NpzHeaderError(f"its zip directory declares {directory} bytes of members, more "
                             f"than the {MAX_CENTRAL_DIRECTORY_BYTES} of the few arrays {kind} "
                             "holds")
    try:
        zip_file = zipfile.ZipFile(path)
    except (RuntimeError, NotImplementedError) as e:  # a zip feature zipfile does not read
        raise NpzHeaderError(f"it cannot be read as a zip archive: {e}") from None
    except zipfile.BadZipFile:  # it starts as one: its end is missing or damaged
        raise DamagedNpzError("it starts as a zip archive but has no zip directory at its "
                              "end: it was cut short (a copy or download that stopped) or "
                              "damaged") from None
    except OSError as e:
        if is_read_failure(e):
            raise
        raise DamagedNpzError("its zip directory is declared at a position the file does not "
                              "have: it is damaged") from None
    with zip_file:
        try:
            headers = npz_array_headers(zip_file)
        except (RuntimeError, NotImplementedError) as e:  # encrypted, unknown compression
            raise NpzHeaderError(f"a member cannot be read: {e}") from None
        except (zipfile.BadZipFile, zlib.error, EOFError) as e:
            raise DamagedNpzError(_damage_words(e)) from None
        except OSError as e:
            if is_read_failure(e):
                raise
            raise DamagedNpzError("a member is declared at a position the file does not "
                                  "have: it is damaged") from None
        if known is not None:
            unknown = [name for name in headers if name not in known]
            if unknown:
                raise NpzHeaderError(f"'{unknown[0]}.npy' is not an array {kind} has (it "
                                     f"has {', '.join(known)})")
        missing = [name for name in names if name not in headers]
        if missing:
            raise NpzHeaderError(f"lacks the arrays {missing}")
        wanted = [*names, *(name for name in optional if name in headers)]
        for name in wanted:
            dtype = headers[name][1]
            if dtype.kind not in ("U" if name in text else "biuf"):
                raise NpzHeaderError(f"'{name}' holds {dtype} values, not "
                                     f"{'text' if name in text else 'numbers'}")
            chars = headers[name][2] // 4
            if name in text and max_text_chars is not None and chars > max_text_chars:
                raise NpzHeaderError(f"'{name}' declares {chars} characters of text, more than "
                                     f"the {max_text_chars} {kind} holds")
        total = sum(headers[name][2] for name in wanted)
        if total > max_bytes:
            raise NpzHeaderError(f"its arrays declare {total} bytes, more than the "
                                 f"{max_bytes} this reads")
        if declared_problem is not None:
            problem = declared_problem({name: header[:2] for name, header in headers.items()})
            if problem:
                raise DeclaredArraysError(problem)
        try:
            with np.load(path, allow_pickle=False) as data:
                return {name: _member_array(data, name) for name in wanted}
        except (RuntimeError, NotImplementedError) as e:
            raise NpzHeaderError(f"a member cannot be read: {e}") from None
        except (zipfile.BadZipFile, zlib.error) as e:
            raise DamagedNpzError(_damage_words(e)) from None


def _damage_words(error: BaseException) -> str:
    """What zipfile's or zlib's `error` on a member's bytes says of the file, in words."""
    text = str(error)
    if text.startswith("Bad CRC-32"):
        return (f"a member's bytes differ from those written ({text.removeprefix('Bad ')} "
                "check fails)")
    return f"a member's compressed bytes are damaged ({type(error).__name__}: {text})"


def _member_array(data, name: str) -> np.ndarray:
    """The array `name` of an open np.load, its header checked; numpy's own error (which
    advises allow_pickle=True) said in the package's words."""
    try:
        return data[name]
    except EOFError:
        raise DamagedNpzError(f"'{name}' ends before the array its .npy header "
                              "declares") from None
    except ValueError:
        raise NpzHeaderError(f"'{name}' cannot be read as the array its .npy header "
                             "declares") from None
