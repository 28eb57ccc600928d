"""The arrays an .npz declares, checked from their .npy headers (names, dtypes, sizes)
before np.load, which would allocate whatever shape a few-kB file declares."""

import math
import os
import stat
import struct
import tokenize
import zipfile
import zlib

import numpy as np
import numpy.lib.format as npy_format

from tegrasp_drake.rig.ranges import is_integer


# How an .npz file starts: a zip archive's first local file header (PKWARE APPNOTE 4.3.7).
NPZ_START = b"PK\x03\x04"
# 11 float64 columns at 20 kHz: 512 MB is 4.8 minutes, far beyond any trial
MAX_TRIAL_LOG_BYTES = 512 * 2**20


class NpzHeaderError(ValueError):
    """An .npz file's arrays are not what its reader accepts; the message says which."""


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
            try:
                version = npy_format.read_magic(member)
                if version == (1, 0):
                    shape, fortran, dtype = npy_format.read_array_header_1_0(
                        member, max_header_size=_MAX_HEADER_BYTES)
                elif version == (2, 0):
                    shape, fortran, dtype = npy_format.read_array_header_2_0(
                        member, max_header_size=_MAX_HEADER_BYTES)
                else:
                    raise ValueError(f"npy format version {version}")
            except (ValueError, EOFError, OSError, SyntaxError, tokenize.TokenError,
                    zlib.error) as e:  # numpy parses the header's dict as Python
                raise NpzHeaderError(f"'{name}' is not a numpy array ({type(e).__name__}: "
                                     f"{e})") from None
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


def checked_npz_arrays(path, names, *, max_bytes: int, optional=(), text=(),
                       max_text_chars: int | None = None, known=None,
                       kind="an .npz") -> dict[str, np.ndarray]:
    """The arrays `names` (and `optional` ones present) of the .npz at `path`, once their
    headers fit `max_bytes` and hold numbers (text for `text`, each at most `max_text_chars`
    characters when given; numpy stores 4 bytes a character), and (when `known`, the array
    names the format has, is given) it holds no other array; NpzHeaderError otherwise, naming
    `kind` (what the file is meant to be), before a byte is read when `path` is not a regular
    file (a FIFO or /dev/zero never ends)."""
    try:
        mode = os.stat(path).st_mode
    except OSError as e:
        raise NpzHeaderError(f"it cannot be read: {e.strerror or e}") from None
    if not stat.S_ISREG(mode):
        raise NpzHeaderError("it is not a regular file (a folder, named pipe or device); "
                             "give the trial.npz file")
    try:
        directory = central_directory_bytes(path)
    except OSError as e:
        raise NpzHeaderError(f"it cannot be read: {e.strerror or e}") from None
    if directory is not None and directory > MAX_CENTRAL_DIRECTORY_BYTES:
        raise NpzHeaderError(f"its zip directory declares {directory} bytes of members, more "
                             f"than the {MAX_CENTRAL_DIRECTORY_BYTES} of the few arrays {kind} "
                             "holds")
    try:
        zip_file = zipfile.ZipFile(path)
    except (RuntimeError, NotImplementedError) as e:  # a zip feature zipfile does not read
        raise NpzHeaderError(f"it cannot be read as a zip archive: {e}") from None
    with zip_file:
        try:
            headers = npz_array_headers(zip_file)
        except (RuntimeError, NotImplementedError) as e:  # encrypted, unknown compression
            raise NpzHeaderError(f"a member cannot be read: {e}") from None
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
        try:
            with np.load(path, allow_pickle=False) as data:
                return {name: data[name] for name in wanted}
        except (RuntimeError, NotImplementedError) as e:
            raise NpzHeaderError(f"a member cannot be read: {e}") from None
