"""The user's files: atomic writes (a temporary file beside the target, then a
rename), signals deferred while renames commit one result, a folder claimed with one mkdir,
the folders a failed command made removed again while empty, bounded reads that refuse
FIFOs and devices, SIGTERM and SIGHUP ending a run as Ctrl-C does,
one-line UserPathError, strict JSON, and the one reader of a JSON file (read_json_file)."""

import contextlib
import contextvars
import errno
import fcntl
import json
import os
import pathlib
import re
import shutil
import signal
import stat
import sys
import tempfile
import threading


def _umask() -> int:
    """The process's umask (read by setting it and setting it back)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _honour_umask(descriptor: int) -> None:
    """Gives a mkstemp file (made 0600) the mode a plain `open` would have made."""
    os.fchmod(descriptor, 0o666 & ~_umask())


def staged_file(path, data: str | bytes) -> pathlib.Path:
    """A flushed temporary file beside `path` holding `data` (text as UTF-8), for a later
    os.replace onto `path`: this process's staging file of `path`
    (`.NAME.XXXXXXXX.PID.staging`, own_staging_suffix), which the caller removes if that never
    comes and which, should it be killed past its handlers, the next writer of `path` removes
    (remove_stale_staging_files_of)."""
    path = pathlib.Path(path)
    payload = data.encode("utf-8") if isinstance(data, str) else data
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=own_staging_suffix(),
                                             dir=path.parent)
    try:
        _honour_umask(descriptor)
        with os.fdopen(descriptor, "wb") as stream:
            stream.write(payload)
            stream.flush()
            os.fsync(stream.fileno())
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    return pathlib.Path(temporary)


# A file a process writes until it commits it, beside its final name: `.NAME.PID.staging`,
# or `.NAME.XXXXXXXX.PID.staging` with staged_file's 8 random characters (tempfile's
# lowercase letters, digits and underscore), PID the writing process's, so that what a
# process killed past its handlers (SIGKILL, a power cut) left is told from a live writer's.
# `rest` is the target's name, with the random part when there is one.
_STAGING_NAME = re.compile(r"\.(?P<rest>.+)\.(?P<pid>[1-9][0-9]{0,9})\.staging", re.DOTALL)
_RANDOM_PART = re.compile(r"\.[a-z0-9_]{8}")


def is_staging_name(name: str) -> bool:
    """Whether `name` is a staging file's (`.NAME.PID.staging`, staged_file's or a writer's)."""
    return _STAGING_NAME.fullmatch(name) is not None


def own_staging_suffix() -> str:
    """The suffix of this process's staging files (`.PID.staging`)."""
    return f".{os.getpid()}.staging"


def stale_staging_files_of(target, start: bytes) -> list[pathlib.Path]:
    """The staging files that writers of `target` which have ended left beside it: named
    for `target` itself (`.NAME.PID.staging`, staged_file's random part or not), regular
    files (not links), holding what `target` holds, known by how such a file starts (`start`:
    a format's magic, e.g. an LCM log's sync word, `{` for JSON) or a part of it (a writer
    killed early leaves its first bytes or nothing). A file named for another target, or
    holding something else, is not a writer's of `target` and is not listed."""
    target = pathlib.Path(target)
    return stale_staging_files_in(target.parent, [target.name], start)


def stale_staging_files_in(folder, names, start: bytes) -> list[pathlib.Path]:
    """The staging files that ended writers of the files `names` (names in `folder`, each
    holding what starts with `start`) left, as stale_staging_files_of lists one target's,
    from one listing of `folder` (a folder of many targets: a sweep's records)."""
    names = set(names)
    try:
        entries = sorted(pathlib.Path(folder).iterdir())
    except OSError:
        return []
    return [path for path in entries
            if (match := _STAGING_NAME.fullmatch(path.name)) is not None
            and _staging_target(match["rest"]) & names
            and not process_alive(int(match["pid"])) and file_starts_with(path, start)]


def _staging_target(rest: str) -> set[str]:
    """The target names a staging file's name part `rest` (before `.PID.staging`) can be
    of: `rest` itself, or `rest` without staged_file's random part when it ends in one."""
    names = {rest}
    if len(rest) > 9 and _RANDOM_PART.fullmatch(rest[-9:]):
        names.add(rest[:-9])
    return names


def remove_stale_staging_files_of(target, start: bytes) -> list[pathlib.Path]:
    """Removes the staging files that ended writers of `target` left, holding what `target`
    holds (stale_staging_files_of), and returns them; one that cannot be removed is left."""
    target = pathlib.Path(target)
    return remove_stale_staging_files_in(target.parent, [target.name], start)


def remove_stale_staging_files_in(folder, names, start: bytes) -> list[pathlib.Path]:
    """Removes the staging files that ended writers of the files `names` in `folder` left,
    holding what starts with `start` (stale_staging_files_in), and returns them; one that
    cannot be removed is left."""
    removed = []
    for path in stale_staging_files_in(folder, names, start):
        with contextlib.suppress(OSError):
            path.unlink()
            removed.append(path)
    return removed


def file_starts_with(path, start: bytes) -> bool:
    """Whether `path` is a regular file (not a link) whose first bytes are `start`, or the
    first part of it (all the file holds); False when it cannot be read."""
    try:
        descriptor = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return False
    try:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):
            return False
        head = os.read(descriptor, len(start))
    except OSError:
        return False
    finally:
        os.close(descriptor)
    return start.startswith(head)


def process_alive(pid: int) -> bool:
    """Whether a process `pid` exists (one of another user's too)."""
    try:
        os.kill(pid, 0)  # no signal sent: only whether it could be
    except (ProcessLookupError, OverflowError):  # no such process; past any process id
        return False
    except PermissionError:  # another user's
        return True
    return True


# How the files of the text kinds this project writes start, for write_atomically's `start`
# (the kind a killed writer's staging file must hold to be removed; binary kinds sit beside
# their writers: FIGURE_STARTS, NPZ_START, HTML_START, LCM_LOG_START). A JSON text's first
# character is its top value's (RFC 8259, 2; json.dumps writes no whitespace before it), an
# object's `{` or an array's `[`; every Markdown page the project writes (reports, docs
# pages) opens on its level-1 heading, `# `, but a page that is one table (a sweep's
# summary.md, a block for the results page), which opens on its header row's `| `.
JSON_OBJECT_START = b"{"
JSON_ARRAY_START = b"["
MARKDOWN_START = b"# "
MARKDOWN_TABLE_START = b"| "


def write_atomically(path, data: str | bytes, *, start: bytes) -> pathlib.Path:
    """Writes `data` (text as UTF-8) to `path` through this process's staging file in its
    (existing) folder (`.NAME.XXXXXXXX.PID.staging`) and a rename; UserPathError (an OSError)
    naming `path`, the target untouched, when it cannot (a full disk, a folder that is not
    one). `start` is how a file of `path`'s kind starts (its format's
    magic: JSON_OBJECT_START, MARKDOWN_START, ...): the staging files of `path` that writers
    killed past their handlers (SIGKILL, a power cut) left holding that kind are removed
    first (remove_stale_staging_files_of). Required, so that no write leaves a file that
    nothing removes."""
    remove_stale_staging_files_of(path, start)
    try:
        temporary = staged_file(path, data)
        try:
            os.replace(temporary, path)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(temporary)
            raise
    except UserPathError:
        raise
    except OSError as error:
        raise UserPathError(f"cannot write {path}: {os_error_text(error)}; "
                            f"{write_error_remedy(error)}", error) from None
    return pathlib.Path(path)


def os_error_text(error: BaseException) -> str:
    """The words of an OSError on a file, after the path it names: the system's (strerror),
    but a symbolic-link loop (ELOOP: links that lead back to each other, which no disk or
    permission explains) said as one; the error's text when it carries no errno."""
    if getattr(error, "errno", None) == errno.ELOOP:
        return "it is a symbolic-link loop: links that lead back to each other, never to a file"
    return getattr(error, "strerror", None) or str(error)


# What to do about a symbolic-link loop, read or written: the link is the problem, not the disk.
_LINK_LOOP_REMEDY = "fix or remove the symbolic link, or give the file's own path"


def write_error_remedy(error: OSError) -> str:
    """What to do about a write that failed with `error`, in the words every writer's error
    line ends with: room for a full disk or quota (ENOSPC, EDQUOT), the link for a
    symbolic-link loop (ELOOP), another folder otherwise (no permission, a read-only disk,
    ...), where space would not help."""
    if error.errno in (errno.ENOSPC, errno.EDQUOT):
        return "free some space or write it to another disk"
    if error.errno == errno.ELOOP:
        return _LINK_LOOP_REMEDY
    if error.errno == errno.ENAMETOOLONG:
        return "give a shorter name"
    return "give a folder you can write"


def read_error_remedy(error: OSError) -> str:
    """What to do about a read that failed with `error`, in the words a reader's error line
    ends with: its owner's permission for a file this user may not read (EACCES, EPERM); the
    link for a symbolic-link loop (ELOOP); else (EIO: a failing disk, a network file system
    gone) the system could not read it, which says nothing of its content: never a damaged
    file, never one to remake."""
    if error.errno in (errno.EACCES, errno.EPERM):
        return "ask its owner to make it readable, or give a file you can read"
    if error.errno == errno.ELOOP:
        return _LINK_LOOP_REMEDY
    return ("the system could not read it, which says nothing of its content; read it again "
            "once the disk or file system answers, or give a copy")


# A seek or read at a position the file itself gave (a zip directory's offset past the end
# or negative) is refused by the system as EINVAL or EOVERFLOW: the content's fault, not the
# disk's. (The package's own OSErrors that carry EINVAL, NotAFileError and UserPathError, are
# not the system's and stay read failures.)
_POSITION_ERRNOS = frozenset({errno.EINVAL, errno.EOVERFLOW})


def is_read_failure(error: BaseException) -> bool:
    """Whether `error` is the operating system's refusal to read a file (an OSError carrying
    an errno: EIO, EACCES, ...), not a reader's finding about what the file holds (zipfile's,
    numpy's and the package's own OSErrors carry none; the system's refusal of a position the
    file gave, _POSITION_ERRNOS on a plain OSError, is the file's)."""
    if not isinstance(error, OSError) or error.errno is None:
        return False
    return not (type(error) is OSError and error.errno in _POSITION_ERRNOS)


@contextlib.contextmanager
def temporary_sibling(path, *, start: bytes):
    """A temporary file name beside `path` for a writer that wants a name (np.savez,
    matplotlib: tell it the format, which the name does not end in); on success it is renamed
    over `path`, on any error removed. It is this process's staging file of `path`
    (`.NAME.XXXXXXXX.PID.staging`), and the staging files of `path` that writers killed past
    their handlers (SIGKILL, a power cut) left, holding what starts with `start` (the
    format's magic), are removed first (remove_stale_staging_files_of)."""
    path = pathlib.Path(path)
    remove_stale_staging_files_of(path, start)
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.",
                                             suffix=own_staging_suffix(), dir=path.parent)
    try:
        _honour_umask(descriptor)
    finally:
        os.close(descriptor)
    try:
        yield pathlib.Path(temporary)
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise


@contextlib.contextmanager
def interruptions_deferred():
    """Holds TERMINATION_SIGNALS back until the block ends, then acts on the first as the
    previous handler would (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received = []
    previous = {number: signal.signal(number, lambda got, frame: received.append(got))
                for number in TERMINATION_SIGNALS}
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
        if received:
            handler = previous[received[0]]
            if callable(handler):
                handler(received[0], None)
            elif handler == signal.SIG_DFL:
                os.kill(os.getpid(), received[0])


def _nearest_existing_part(path) -> tuple[pathlib.Path | None, OSError | None]:
    """The nearest part of `path` (itself first) that exists, or None; with the OSError that
    stopped the look there (a symlink loop, a name too long) if one did."""
    path = pathlib.Path(path)
    for place in (path, *path.parents):
        try:
            if place.exists():
                return place, None
            if place.is_symlink():  # a dangling link, or a loop (exists() says False to both)
                os.stat(place)
        except FileNotFoundError:
            return place, None
        except OSError as e:
            return place, e
    return None, None


def _place_problem(path) -> str | None:
    """What makes `path` no place for the user's output whatever its folder's permissions:
    a relative path when the current folder has been deleted; a path inside the installed
    package (installed_package_dir), which pip deletes with everything in it."""
    path = pathlib.Path(path)
    if not path.is_absolute():
        try:
            os.getcwd()
        except FileNotFoundError:
            return "cannot be written: the current folder no longer exists; cd to one that does"
    package = installed_package_dir()
    if package is not None:
        try:
            real = pathlib.Path(os.path.realpath(path))
        except (OSError, RuntimeError):
            return None
        if real == package or package in real.parents:
            return (f"is inside the installed package ({package}), which pip deletes with "
                    "everything in it when it upgrades or removes the package; use a folder "
                    "outside it")
    return None


def installed_package_dir() -> pathlib.Path | None:
    """The installed tegrasp_drake folder (a real path), None for a source checkout's (one
    beside a pyproject.toml: its maintainers place files in it, and pip does not remove it)."""
    package = pathlib.Path(__file__).resolve().parents[1]
    if (package.parent / "pyproject.toml").is_file():
        return None
    return package


# Whether folder_problem may prove a folder writable by making (and removing at once) an entry
# in it; unprobed_folder_checks turns it off for a block.
_WRITE_PROBES = contextvars.ContextVar("tegrasp_write_probes", default=True)


@contextlib.contextmanager
def unprobed_folder_checks():
    """folder_problem without its probe entry for the block: a dry run leaves no trace, not
    even a folder's changed modification time or an entry another process could see for a
    moment. It asks access(2) (os.access) alone, which reads the mode bits, ACLs and a
    read-only mount; what only a write shows (a full disk, a server that refuses) is left to
    the real run's own check."""
    token = _WRITE_PROBES.set(False)
    try:
        yield
    finally:
        _WRITE_PROBES.reset(token)


def folder_problem(path) -> str | None:
    """Why `path` cannot be, or be made as, a folder this user writes in (None if it can),
    proven by making an entry in its nearest existing part (permission bits do not tell;
    within unprobed_folder_checks, os.access alone); _place_problem first."""
    problem = _place_problem(path)
    if problem:
        return problem
    place, error = _nearest_existing_part(path)
    if error:
        return f"{place}: {os_error_text(error)}"
    if place is None:
        return None
    if not place.is_dir():
        return f"{place} is not a folder"
    if not os.access(place, os.W_OK | os.X_OK):
        return f"{place} is not writable"
    if not _WRITE_PROBES.get():
        return None
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".tegrasp-probe-", dir=place))
    except OSError as e:
        return (f"{place} cannot be written in: making a folder there failed "
                f"({os_error_text(e)})")
    return None


def _unreadable_folder_error(folder, error: OSError) -> "UserPathError":
    return UserPathError(f"{folder} cannot be read ({os_error_text(error)}); ask its owner "
                         "to make it readable, or give a folder you can read", error)


def is_folder(path) -> bool:
    """Whether a folder is at `path` (symlinks followed); False when nothing is there or a
    file is on its path; UserPathError naming it when it cannot be looked at (no permission
    to search a folder on its path, an I/O error), which pathlib's is_dir() calls False."""
    try:
        return stat.S_ISDIR(os.stat(path).st_mode)
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError as error:
        raise _unreadable_folder_error(path, error) from None


def folder_entries(folder) -> list[pathlib.Path] | None:
    """The entries of `folder`, sorted by name; None when no folder is there (nothing at the
    path, or a file on it). UserPathError naming it when it is there but cannot be listed
    (no permission, an I/O error): a folder this user cannot read is not an empty or absent
    one, which is what pathlib's is_dir(), exists() and glob() would make of it."""
    folder = pathlib.Path(folder)
    try:
        with os.scandir(folder) as scan:
            names = sorted(entry.name for entry in scan)
    except (FileNotFoundError, NotADirectoryError):
        return None
    except OSError as error:
        raise _unreadable_folder_error(folder, error) from None
    return [folder / name for name in names]


def free_bytes(path) -> int:
    """The bytes this user may still write on the disk holding `path` (its nearest existing
    part): the one free-space probe of the package (shutil.disk_usage, the blocks available
    to an unprivileged user). OSError when it cannot be asked."""
    place, error = _nearest_existing_part(path)
    if error:
        raise error
    return shutil.disk_usage(place if place is not None else ".").free


def free_space_problem(path, needed_bytes: int, for_what: str) -> str | None:
    """Why the disk holding `path` (an output, or the folder it goes in) cannot take
    `needed_bytes` more, in words that follow the path, or None; `for_what` says what needs
    them and why that much (e.g. "its log (ten seconds of the bus)"). Asked before a run's
    work, so that a full disk refuses the run rather than ending it."""
    try:
        free = free_bytes(path)
    except OSError as e:
        return f"cannot be checked for free space: {os_error_text(e)}"
    if free < needed_bytes:
        return (f"is on a disk with {free // 1000} kB free; the run needs at least "
                f"{round(needed_bytes / 1e6, 1):g} MB for {for_what}: free some space or "
                "write it to another disk")
    return None


def replace_problem(path) -> str | None:
    """Why an atomic write (a temporary file renamed onto `path`) cannot put a file at `path`, in
    words that follow it, or None: a folder in its place (a rename never replaces one) or a
    non-folder on its folder path; ask before the work, so its result is never lost."""
    path = pathlib.Path(path)
    try:
        mode = os.lstat(path).st_mode
    except (FileNotFoundError, NotADirectoryError):  # the latter: a file on its folder path
        mode = None
    except OSError as e:
        return f"cannot be used ({os_error_text(e)})"
    if mode is not None and stat.S_ISDIR(mode):
        return "is a folder where a file belongs (no file can replace a folder); move it away"
    blocked = non_folder_on_path(path.parent)
    if blocked:
        place, error = blocked
        if error:
            return f"cannot be used ({place}: {os_error_text(error)})"
        return f"cannot be written: {place} is not a folder"
    return None


def output_file_problem(path) -> str | None:
    """Why a command may not write the file `path` (an output option's value), in words that
    follow it, or None; asked before the work starts. Refuses an existing device, FIFO, socket
    or folder (a rename onto a device node would replace it), /proc and /sys, and a folder the
    user cannot write in; _place_problem first."""
    path = pathlib.Path(path)
    problem = _place_problem(path)
    if problem:
        return problem
    try:
        mode = os.stat(path).st_mode
    except (FileNotFoundError, NotADirectoryError):
        mode = None
    except OSError as e:
        return f"cannot be used ({os_error_text(e)})"
    if mode is not None and not stat.S_ISREG(mode):
        if stat.S_ISDIR(mode):
            return "is a folder where a file belongs; give a file name"
        return (_kind_problem(mode) or "is not a regular file").split(";")[0] + \
            "; give a regular file to write"
    problem = replace_problem(path)
    if problem:
        return f"{problem}; give a file in a folder you can write"
    real = os.path.realpath(path)
    top = next((top for top in ("/proc", "/sys", "/dev")
                if real == top or real.startswith(top + "/")), None)
    # /dev holds device nodes, but a RAM-backed folder mounted in it (/dev/shm) holds files.
    if top and not (top == "/dev" and _filesystem_type(os.path.dirname(real)) == "tmpfs"):
        return f"is in {top}, not a place for files; give a file in a folder you can write"
    problem = folder_problem(path.parent)
    if problem:
        return f"{problem}; give a file in a folder you can write"
    return None


def _filesystem_type(folder: str) -> str | None:
    """The type of the filesystem `folder` (a real path) is on, from the mount table
    (/proc/self/mounts: the longest mount point that holds it); None if unknown."""
    try:
        with open("/proc/self/mounts", encoding="utf-8", errors="replace") as mounts:
            table = [line.split()[1:3] for line in mounts if len(line.split()) >= 3]
    except OSError:
        return None
    best, kind = "", None
    for point, fs_type in table:
        point = point.replace("\\040", " ")
        inside = folder == point or folder.startswith(point.rstrip("/") + "/")
        if inside and len(point) >= len(best):
            best, kind = point, fs_type
    return kind


def non_folder_on_path(folder) -> tuple[pathlib.Path, OSError | None] | None:
    """The nearest existing part of `folder` (itself first) when not a folder, with the OSError
    that stopped the look if any; None when `folder` is one or can be made."""
    place, error = _nearest_existing_part(folder)
    if error:
        return place, error
    if place is None or place.is_dir():
        return None
    return place, None


def absent_folders(folder) -> list[pathlib.Path]:
    """`folder` and its parents that do not exist yet, deepest first: what making it makes."""
    folder = pathlib.Path(folder)
    return [path for path in (folder, *folder.parents) if not os.path.lexists(path)]


@contextlib.contextmanager
def made_folders_removed_if_empty(made):
    """For a block that makes the folders `made` (absent_folders, deepest first): when it
    raises or is interrupted (an error, Ctrl-C, SIGTERM), each of them still empty is removed
    again, deepest first, stopping at the first that is not (rmdir removes only an empty
    folder): a command that wrote nothing leaves nothing. A folder that was there before is
    never in `made`, so it stays, empty or not."""
    try:
        yield
    except BaseException:
        remove_made_folders_if_empty(made)
        raise


def remove_made_folders_if_empty(made) -> None:
    """Removes each of the folders `made` (absent_folders, deepest first) that is still
    empty, stopping at the first that is not: what a run that wrote nothing made."""
    for path in made:
        try:
            path.rmdir()
        except OSError:  # holds something (or was never made): it, and its parents, stay
            break


def claim_folder(path) -> bool:
    """Makes `path` (its parents as needed) with one mkdir; False if it already existed."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        path.mkdir()
    except FileExistsError:
        return False
    return True


class FolderHeldError(OSError):
    """Another process holds the folder (held_folder): another run is writing there."""


# What a held folder says of its holder: the lock (a flock on the folder) records no more
# than that some run holds it (a trial, a hardware run, a sweep, ...), so no kind is named.
FOLDER_HELD = "another run is writing there now"


_SHARED_HOLDS = {}  # resolved folder -> how many nested shared holds this process has on it


@contextlib.contextmanager
def held_folder(folder, *, shared: bool = False):
    """Holds an exclusive flock on `folder` itself (its directory, opened read-only: no file
    is made in it) for the block, so every command that writes a run into a folder (a trial,
    a hardware run, a sweep, a transfer, a sensitivity study) refuses a second one at once;
    the kernel drops the lock when the process ends, however it ends. A `shared` hold nested
    in another shared hold of the folder in this process (a sensitivity study holding its
    folder across the transfer it runs) shares the outer one; any other second hold is
    refused, in this process as in another. FolderHeldError when another hold has it;
    OSError when the folder cannot be opened."""
    key = pathlib.Path(folder).resolve()
    if shared and _SHARED_HOLDS.get(key):
        _SHARED_HOLDS[key] += 1
        try:
            yield
        finally:
            _SHARED_HOLDS[key] -= 1
        return
    descriptor = os.open(key, os.O_RDONLY | os.O_DIRECTORY)
    try:
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise FolderHeldError(errno.EWOULDBLOCK, FOLDER_HELD, str(folder)) from None
        if shared:
            _SHARED_HOLDS[key] = 1
        try:
            yield
        finally:
            if shared:
                del _SHARED_HOLDS[key]
    finally:
        os.close(descriptor)  # releases the lock


class FileHeldError(OSError):
    """Another process holds the file (held_file): another run is writing it."""


@contextlib.contextmanager
def held_file(path):
    """Holds an exclusive flock on `.NAME.lock` beside `path` for the block, so a second run
    writing the same output (whose own writes go through staging files and renames, which no
    lock on the output itself would cover) is refused at once; the lock file is removed at
    the end, and the kernel drops the lock when the process ends, however it ends.
    FileHeldError when another process holds it; OSError when it cannot be made."""
    path = pathlib.Path(path)
    lock = path.with_name(f".{path.name}.lock")
    while True:
        descriptor = os.open(lock, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(descriptor)
            raise FileHeldError(errno.EWOULDBLOCK, "another run is writing it now",
                                str(path)) from None
        try:
            same = os.path.samestat(os.fstat(descriptor), os.stat(lock))
        except FileNotFoundError:
            same = False
        if same:
            break
        # The holder before us removed the file between our open and our lock: the lock
        # we hold is on a file nobody else will see; take the one on the path again.
        os.close(descriptor)
    try:
        yield
    finally:
        with contextlib.suppress(OSError):
            lock.unlink()  # while still held: a waiting opener then retries on a new file
        os.close(descriptor)


class InputTooLargeError(OSError):
    """A file is larger than its reader accepts; raised before the rest is read."""

    def __init__(self, path, limit: int):
        super().__init__(errno.EFBIG, f"more than {limit} bytes (the most this reads)")
        self.path, self.limit = str(path), limit


class NotAFileError(OSError):
    """A path names a folder, FIFO, socket or device; `strerror` says which, after the path."""

    def __init__(self, path, words: str):
        super().__init__(errno.EINVAL, words)
        self.path = str(path)


def _kind_problem(mode: int) -> str | None:
    """Why a file of stat mode `mode` is not one to read (None: it is a regular file). Every
    device is refused alike, /dev/null and /dev/zero too: no input of this tool is a device."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "is a folder, not a file; give a file"
    if stat.S_ISFIFO(mode):
        return "is a named pipe (FIFO), not a file; give a regular file"
    if stat.S_ISSOCK(mode):
        return "is a socket, not a file; give a regular file"
    return "is a device, not a file; give a regular file"


def file_problem(path) -> str | None:
    """Why `path` cannot be read as a file, in words that follow it ("does not exist", "is a named
    pipe (FIFO), not a file; ..."), or None; nothing is opened."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return "does not exist"
    except OSError as e:
        return f"cannot be read: {os_error_text(e)}"
    return _kind_problem(mode)


def open_bounded(path, limit: int):
    """The file at `path` opened for reading (a binary stream) and its size [bytes] from
    fstat: InputTooLargeError for a file larger than `limit`; NotAFileError for a folder,
    FIFO, socket or device (/dev/null and /dev/zero too); both checked before a byte is
    read, so a 3 GB file costs no 1 GB read to refuse."""
    descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        status = os.fstat(descriptor)
        problem = _kind_problem(status.st_mode)
        if problem:
            raise NotAFileError(path, problem)
        if status.st_size > limit:
            raise InputTooLargeError(path, limit)
        os.set_blocking(descriptor, True)
        stream = os.fdopen(descriptor, "rb")
    except BaseException:
        os.close(descriptor)
        raise
    return stream, status.st_size


def existing_file_head(path, size: int) -> bytes | None:
    """The first `size` bytes of the file at `path`, or None when nothing is there: what an
    output about to be replaced holds. NotAFileError for a folder, FIFO, socket or device
    (opened without blocking and checked from fstat, so a named pipe never stalls the check);
    other OSErrors pass on."""
    try:
        stream, _ = open_bounded(path, sys.maxsize)
    except (FileNotFoundError, NotADirectoryError):
        return None
    with stream:
        return stream.read(size)


def existing_output_head(path, size: int, belongs: str) -> tuple[bytes | None, str | None]:
    """(existing_file_head, None), or (None, why) in words that follow the path when what is
    there cannot be looked at: a folder, pipe, socket or device where `belongs` ("a file
    belongs; move it away, or give another file name"), or a read the system refused."""
    try:
        return existing_file_head(path, size), None
    except NotAFileError as error:
        kind = error.strerror.split(",")[0]  # "is a folder", "is a named pipe (FIFO)", ...
        return None, f"{kind} where {belongs}"
    except OSError as error:
        return None, (f"cannot be read to check what it is ({os_error_text(error)}); give "
                      "another file name")


def read_bounded(path, limit: int) -> bytes:
    """The bytes of the file at `path`: open_bounded's checks, then a file that grows while
    read is still held to `limit` by the read."""
    stream, size = open_bounded(path, limit)
    # A regular file is read with a buffer of its size, not of `limit` (read(n) allocates
    # n bytes first: 1 GiB for a run log of 1 MB); one that grew since fstat is read on to
    # the bound.
    wanted = limit + 1
    first = min(wanted, size + 1)
    with stream:
        data = stream.read(first)
        if len(data) == first < wanted:
            data += stream.read(wanted - first)
    if len(data) > limit:
        raise InputTooLargeError(path, limit)
    return data


# The signals whose default action ends the process and that a handler can catch: Ctrl-C,
# kill's default, a closed terminal, Ctrl-\ (SIGQUIT), the user-defined pair and an alarm
# (signal(7); SIGPIPE has its own handling, cli.py). SIGKILL cannot be caught: a run folder's
# next run removes what one leaves (commands/run_folder.py).
TERMINATION_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT,
                       signal.SIGUSR1, signal.SIGUSR2, signal.SIGALRM)

_received_interrupts = []  # the names of the signals _interrupt took, first first


def _interrupt(signal_number, frame):
    """Raises KeyboardInterrupt for the first signal only. A later one (a second Ctrl-C, or
    the SIGHUP `timeout` relays twice within ms) arrives while the first's KeyboardInterrupt
    unwinds, inside the `finally` that removes the run's files: raising again there would
    stop that cleanup and end the command in a traceback. It is recorded, nothing more."""
    _received_interrupts.append(signal.Signals(signal_number).name)
    if len(_received_interrupts) == 1:
        raise KeyboardInterrupt(_received_interrupts[0])


def interrupt_received() -> str | None:
    """The name of the first signal that interrupted the process inside termination_interrupts, or
    None (a KeyboardInterrupt raised in a Drake callback may come out wrapped in another)."""
    return _received_interrupts[0] if _received_interrupts else None


@contextlib.contextmanager
def termination_interrupts(process_ends: bool = False):
    """TERMINATION_SIGNALS raise KeyboardInterrupt in the main thread during the block, so
    every `finally` runs; the first signal only (_interrupt), later ones are recorded. Signals
    someone already handles are left alone. The handlers are restored when the block ends,
    unless `process_ends` (the command line: the process exits after the block) and a signal
    was taken: then the later ones are ignored until the process is gone, so none raises in
    the interpreter's exit (threads joined, atexit) and the exit code stays the first's."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {}
    _received_interrupts.clear()  # a new run (tests call cli.main many times)
    for number in TERMINATION_SIGNALS:
        if signal.getsignal(number) in (signal.SIG_DFL, signal.default_int_handler):
            previous[number] = signal.signal(number, _interrupt)
    try:
        yield
    finally:
        ignore = process_ends and bool(_received_interrupts)
        for number, handler in previous.items():
            signal.signal(number, signal.SIG_IGN if ignore else handler)


_ESCAPES = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


# U+FFFD is what a decoder puts for bytes that are not UTF-8 (errors="replace", as LCM's
# generated decoders do): printable, but it shows no byte, so it is escaped with the others.
REPLACEMENT_CHARACTER = "\ufffd"


def one_line(text: str) -> str:
    """`text` as one plain line: characters that are not printable (line breaks, ESC, ...) and
    the replacement character U+FFFD shown escaped as Python would (\\n, \\x1b, \\u2028,
    \\ufffd); a byte a path could not decode as the byte (\\xff: echo.undecoded_as_bytes)."""
    if text.isprintable() and REPLACEMENT_CHARACTER not in text:
        return text
    from tegrasp_drake.rig.echo import undecoded_as_bytes
    text = undecoded_as_bytes(text)
    return "".join(
        ch if (ch.isprintable() and ch != REPLACEMENT_CHARACTER) or ch == " " else
        _ESCAPES.get(ch) or ch.encode("unicode_escape").decode("ascii") for ch in text)


# A value pasted by mistake must not make an error hundreds of kB long: an error line's words
# longer than twice echo.ECHO_CHARS (a path, a value) are cut to about ECHO_CHARS, their start
# and end kept, and the line is at most MAX_ERROR_CHARS.
MAX_ERROR_CHARS = 1000


def error_line(text: str) -> str:
    """`text` as an error's one line (one_line), bounded: every error the user reads."""
    from tegrasp_drake.rig.echo import ECHO_CHARS, shorten
    message = one_line(text)
    message = " ".join(shorten(word) if len(word) > 2 * ECHO_CHARS else word
                       for word in message.split(" "))
    if len(message) <= MAX_ERROR_CHARS:
        return message
    half = MAX_ERROR_CHARS // 2
    return f"{message[:half]} ... ({len(message) - 2 * half} characters cut) ... {message[-half:]}"


class UserPathError(OSError):
    """A file or folder the user named cannot be used: str() is one line naming it and what to
    do; `strerror` stays the system's words."""

    def __init__(self, message: str, error: OSError | None = None):
        super().__init__(getattr(error, "errno", None) or errno.EINVAL,
                         getattr(error, "strerror", None) or message)
        self.message = one_line(message)

    def __str__(self) -> str:
        return self.message


class DuplicateKeyError(ValueError):
    """A JSON object names the same key twice (json would keep the last one silently)."""


def _refuse_duplicate_keys(pairs):
    data = {}
    for key, value in pairs:
        if key in data:
            raise DuplicateKeyError(f"key {one_line(repr(key))} appears twice in one object; "
                                    "keep one")
        data[key] = value
    return data


class JsonValueError(ValueError):
    """NaN or Infinity (not JSON, RFC 8259 6), or an integer beyond a float's range."""


def _refuse_nonstandard_constant(name: str):
    raise JsonValueError(f"holds {name}, which is not a JSON number (RFC 8259); write a "
                         "finite number")


def _float_ranged_int(text: str) -> int:
    """A JSON integer via the bounded reader (integer_text.py); refused when no float64 holds it."""
    from tegrasp_drake.rig.integer_text import IntegerTextError, read_integer
    try:
        return read_integer(text, decimal_only=True)
    except IntegerTextError as e:
        raise JsonValueError(f"holds a number that {e}; write a finite number") from None


class ByteOrderMarkError(ValueError):
    """JSON text that starts with a UTF-8 byte-order mark (RFC 8259 8.1: JSON has none; some
    Windows editors save one)."""


_UTF8_BOM = b"\xef\xbb\xbf"
BYTE_ORDER_MARK_PROBLEM = ("starts with a UTF-8 byte-order mark, which JSON does not take; save "
                           "it without one")


def load_json(text: str | bytes):
    """The data of a user's JSON text: json.loads, refusing a byte-order mark
    (ByteOrderMarkError; json alone refuses a str's as bad JSON and takes a bytes' silently), a
    duplicate key (DuplicateKeyError) and NaN, Infinity, an integer no float holds or a text
    or key with a lone surrogate, "\\ud800" (JsonValueError, naming the field), all
    ValueErrors. Every JSON file the package reads comes through here."""
    if text[:1] == "\ufeff" or text[:3] == _UTF8_BOM:
        raise ByteOrderMarkError(BYTE_ORDER_MARK_PROBLEM)
    data = json.loads(text, object_pairs_hook=_refuse_duplicate_keys,
                      parse_constant=_refuse_nonstandard_constant,
                      parse_int=_float_ranged_int)
    # Only a \\u escape (or a str that holds one as it is) spells a surrogate: UTF-8 cannot.
    if (b"\\u" in text if isinstance(text, bytes)
            else "\\u" in text or not text.isascii()):
        _refuse_lone_surrogates(data)
    return data


def _text_problem(text: str) -> str | None:
    """Where `text` holds a lone UTF-16 surrogate (U+D800 to U+DFFF), which JSON's \\u escapes
    can spell but no Unicode text holds, else None."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as error:
        return (f"\\u{ord(text[error.start]):04x} at character {error.start}, a lone UTF-16 "
                "surrogate, which is no Unicode character")
    return None


def _refuse_lone_surrogates(data) -> None:
    """JsonValueError naming the first field (a path such as events[0].file) whose text or key
    holds a lone surrogate: the escape is valid JSON syntax but no text (RFC 8259 8.2), and
    would fail later when printed or written (UTF-8 cannot encode it)."""
    pending = [("", data)]
    while pending:
        path, value = pending.pop()
        if isinstance(value, str):
            problem = _text_problem(value)
            if problem:
                where = f"field '{path}'" if path else "its text"
                raise JsonValueError(f"{where} holds {problem}; write the text without it")
        elif isinstance(value, dict):
            for key in value:
                problem = _text_problem(key)
                if problem:
                    where = f"a key of field '{path}'" if path else "a key"
                    raise JsonValueError(f"{where} holds {problem}; write the text without it")
            pending.extend((f"{path}.{key}" if path else key, item)
                           for key, item in reversed(value.items()))
        elif isinstance(value, list):
            pending.extend((f"{path}[{k}]", item) for k, item in reversed(list(enumerate(value)))
                           if isinstance(item, (str, dict, list)))


# The most a run's own state file in its --out (world.json, sensitivity's points.json, a
# run's result.json) may hold: the largest written, points.json of a 1001-point Latin
# hypercube over the 8 uncertain parameters, is 0.36 MB; an event file's bound (16 MB) leaves
# room for many more parameters and stops a sparse or endless file at once.
MAX_STATE_FILE_BYTES = 16_000_000


class JsonFileError(UserPathError):
    """A JSON file read_json_file cannot return: str() is one line, the file, what is wrong
    and the remedy; `problem` says only what is wrong, for a reader that words its own error;
    `unreadable` is the OSError that kept the file from being read (no permission, an I/O
    error), None when it was read, or is missing or not a file: a file this user cannot
    read is not a damaged one, and is never to be remade or set aside for it."""

    def __init__(self, path, problem: str, remedy: str = "", unreadable: OSError | None = None):
        self.path, self.problem = str(path), one_line(problem)
        self.unreadable = unreadable
        super().__init__(error_line(f"{path}: {problem}" + (f"; {remedy}" if remedy else "")))


def read_json_file(path, *, limit: int, kind: str, check=None, encoding: str = "utf-8",
                   remedy: str = ""):
    """The data of the JSON file at `path`, `kind` of file ("a trial record"): at most `limit`
    bytes of `encoding` text, load_json's JSON, and `check(data)` (what is wrong with data of
    the wrong shape, None: nothing). JsonFileError otherwise, naming the file and `remedy`: a
    missing file, a folder, FIFO, socket or device in its place (read_bounded; no device
    holds such a file), a byte-order mark, a decoding error, truncated JSON, a duplicate key,
    NaN, deep nesting."""
    try:
        raw = read_bounded(path, limit)
        if raw.startswith(_UTF8_BOM):  # before decoding: an ASCII file's is no decoding error
            raise ByteOrderMarkError(BYTE_ORDER_MARK_PROBLEM)
        data = load_json(raw.decode(encoding))
        problem = check(data) if check else None
    except FileNotFoundError:
        problem = "file is missing"
    except InputTooLargeError:
        problem = f"is larger than {limit} bytes, more than {kind} holds"
    except NotAFileError as error:  # which kind of file it is, without "give a file"
        problem = error.strerror.split(";")[0]
    except OSError as error:
        raise JsonFileError(path, f"cannot be read ({os_error_text(error)})", remedy,
                            unreadable=error) from None
    except UnicodeDecodeError as error:
        problem = f"is not {encoding.upper()} text (byte {error.start})"
    except json.JSONDecodeError as error:
        problem = f"is not valid JSON, perhaps truncated ({error})"
    except ValueError as error:  # DuplicateKeyError, JsonValueError: say which
        problem = str(error)
    except RecursionError:
        problem = f"nests too deeply to be {kind}"
    if problem:
        raise JsonFileError(path, problem, remedy)
    return data
