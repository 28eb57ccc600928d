"""Writing the user's files so that an interruption never leaves a half-made one.

- write_atomically: a temporary file in the same folder, then a rename over the target; a
  crash, Ctrl-C or a full disk leaves the old file whole (and no temporary behind).
- interruptions_deferred: Ctrl-C and SIGTERM wait while several renames commit one result
  (an object's event files and their index), so that it is all old or all new.
- claim_folder: a fresh folder made with one mkdir, so that two runs never take the same.
- folder_problem: what stops a folder from being written, checked before any long work.
"""

import contextlib
import os
import pathlib
import signal
import tempfile
import threading


def staged_file(path, data: str | bytes) -> pathlib.Path:
    """A temporary file beside `path` holding `data` (text as UTF-8), flushed to disk, for
    a later os.replace onto `path`; the caller removes it if that never comes."""
    path = pathlib.Path(path)
    payload = data.encode("utf-8") if isinstance(data, str) else data
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp",
                                             dir=path.parent)
    try:
        with os.fdopen(descriptor, "wb") as stream:
            stream.write(payload)
            stream.flush()
            os.fsync(stream.fileno())
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    return pathlib.Path(temporary)


def write_atomically(path, data: str | bytes) -> pathlib.Path:
    """Writes `data` (text as UTF-8) to `path` through a temporary file in its folder and a
    rename; the folder must exist. OSError (the target untouched) when it cannot."""
    temporary = staged_file(path, data)
    try:
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    return pathlib.Path(path)


@contextlib.contextmanager
def temporary_sibling(path):
    """A temporary file name beside `path` for a writer that wants a name (np.savez,
    matplotlib); on success it is renamed over `path`, on any error removed."""
    path = pathlib.Path(path)
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix,
                                             dir=path.parent)
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
    """Holds SIGINT and SIGTERM back until the block ends, then acts on the first that came
    as the handler before would have (Ctrl-C: KeyboardInterrupt). Python-level handlers, not
    a signal mask: in a process with threads the kernel may hand the signal to any of them.
    Only the main thread can set handlers; elsewhere the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received = []
    previous = {number: signal.signal(number, lambda got, frame: received.append(got))
                for number in (signal.SIGINT, signal.SIGTERM)}
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


def folder_problem(path) -> str | None:
    """Why `path` cannot be, or be made as, a folder this user writes in (None if it can):
    its nearest existing part must be a writable folder."""
    path = pathlib.Path(path)
    for place in (path, *path.parents):
        try:
            exists = place.exists() or place.is_symlink()
        except OSError as e:  # a symlink loop, a name too long
            return f"{place}: {e.strerror or e}"
        if exists:
            if not place.is_dir():
                return f"{place} is not a folder"
            if not os.access(place, os.W_OK | os.X_OK):
                return f"{place} is not writable"
            return None
    return None


def claim_folder(path) -> bool:
    """Makes `path` (its parents as needed) with one mkdir; False if it already existed."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        path.mkdir()
    except FileExistsError:
        return False
    return True
