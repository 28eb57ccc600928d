"""The command line's own stdout and stderr when the system refuses them: a pipe whose reader
has gone (`tegrasp ... | head`), a full disk or an I/O error (`tegrasp ... >/dev/full`).

While a command runs, `guarded_output()` wraps both streams so that a failed write raises
OutputStreamError naming the stream, and is remembered even when a caller swallows it
(argparse ignores an OSError printing --help); a closed pipe stays a BrokenPipeError, and a
standard output the shell closed (`>&-`, Python's sys.stdout None) fails every write as a full
disk does, so that the output is never lost without a word. The
error boundary (cli.py) asks `unwritable_output()` at the end, tells a failure once with
`tell_cannot_write`, and points a stream it cannot use at the null device (`detach`), so
that Python's flush at exit finds nothing to report again."""

import contextlib
import errno
import os
import sys
from tegrasp_drake.rig.files import os_error_text

STANDARD_OUTPUT = "standard output"
STANDARD_ERROR = "standard error"


class OutputStreamError(OSError):
    """stdout or stderr refused a write (a full disk, an I/O error): the environment's doing,
    told in one line; `stream_name` says which."""

    def __init__(self, stream_name: str, error: OSError):
        super().__init__(error.errno, error.strerror)
        self.stream_name = stream_name


class _GuardedStream:
    """A text stream whose failed writes raise OutputStreamError naming it (a closed pipe
    stays a BrokenPipeError), and which writes what its encoding cannot hold escaped (\\xe9);
    everything else is the stream's. `quiet`: a failed write is only remembered, not raised
    (a standard error the shell closed: nothing can be told there, and a refusal being said
    on it keeps its own exit code)."""

    def __init__(self, stream, name: str, *, quiet: bool = False):
        self._stream, self._name, self._quiet = stream, name, quiet

    def write(self, text):
        try:
            return self._stream.write(text)
        except UnicodeEncodeError:  # PYTHONIOENCODING=ascii and a name the user gave, é
            encoding = getattr(self._stream, "encoding", None) or "ascii"
            return self._stream.write(text.encode(encoding, "backslashreplace").decode(encoding))
        except BrokenPipeError:
            raise
        except OSError as error:
            failure = self._failed(error)
            if self._quiet:
                return len(text)
            raise failure from None

    def flush(self):
        try:
            return self._stream.flush()
        except BrokenPipeError:
            raise
        except OSError as error:
            raise self._failed(error) from None

    def _failed(self, error: OSError) -> OutputStreamError:
        """The error to raise, also kept in _failed_writes: a caller may swallow it."""
        failure = OutputStreamError(self._name, error)
        _failed_writes.append(failure)
        return failure

    def __getattr__(self, name):
        return getattr(self._stream, name)


class _ClosedStream:
    """The standard output or error of a process started with it closed (`tegrasp ... >&-`,
    `2>&-`): Python gives None, and print() would drop the text and report nothing (or, for
    stderr, print it on stdout); every write fails."""

    def write(self, text):
        raise OSError(errno.EBADF, "it is closed; send it to a file, or to /dev/null to "
                                   "discard it")

    def flush(self):
        pass  # nothing was written, nothing is lost


_failed_writes: list[OutputStreamError] = []  # this command's, first first


def note_failed_write(failure: OutputStreamError) -> None:
    """Remembers a write to stdout or stderr that failed outside a guarded stream, for
    `unwritable_output` to tell (commands/verbosity.py's log handler)."""
    _failed_writes.append(failure)


@contextlib.contextmanager
def guarded_output():
    """stdout and stderr as _GuardedStreams for the block, a closed one as a stream whose
    writes fail (_ClosedStream; on stderr they are only remembered, as nothing can be told
    there); no failed write remembered yet."""
    _failed_writes.clear()
    original = sys.stdout, sys.stderr
    guarded = (_GuardedStream(original[0] or _ClosedStream(), STANDARD_OUTPUT),
               _GuardedStream(original[1] or _ClosedStream(), STANDARD_ERROR,
                              quiet=original[1] is None))
    sys.stdout, sys.stderr = guarded
    try:
        yield
    finally:
        if sys.stdout is guarded[0]:
            sys.stdout = original[0]
        if sys.stderr is guarded[1]:
            sys.stderr = original[1]


def unwritable_output() -> tuple[str, OSError] | None:
    """The first output stream a write of this command failed on, else the first of stdout and
    stderr that cannot be flushed now (not a closed pipe, which propagates as BrokenPipeError),
    with its error; a stream that cannot be flushed is pointed at the null device so that
    nothing buffered is reported again at exit."""
    found = (_failed_writes[0].stream_name, _failed_writes[0]) if _failed_writes else None
    for name, stream in ((STANDARD_OUTPUT, sys.stdout), (STANDARD_ERROR, sys.stderr)):
        try:
            if stream is not None:
                stream.flush()
        except BrokenPipeError:
            raise
        except OSError as error:
            found = found or (name, error)
            detach(stream)
        except ValueError:  # closed
            pass
    return found


def tell_cannot_write(name: str, error: OSError, program: str = "tegrasp") -> None:
    """One line on stderr, led by `program`, for the output stream `name` the system refused
    to write; that stream is pointed at the null device, so that nothing it still buffers is
    reported again (stderr too when the line itself cannot be written)."""
    _failed_writes.clear()  # told now, once
    if name == STANDARD_OUTPUT:
        detach(sys.stdout)
    if sys.stderr is None:  # closed by the shell (`2>&-`): print() would write on stdout
        return
    try:
        print(f"{program}: error: cannot write to {name}: {os_error_text(error)}",
              file=sys.stderr, flush=True)
    except (OSError, ValueError):
        detach(sys.stderr)


def detach_standard_streams() -> None:
    """Points stdout and stderr at the null device: the reader of the output has gone."""
    for stream in (sys.stdout, sys.stderr):
        detach(stream)


def detach(stream) -> None:
    """Points `stream`'s file descriptor at the null device and drops what it buffered."""
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(null, stream.fileno())
        finally:
            os.close(null)
        stream.flush()
    except (AttributeError, OSError, ValueError):
        pass


def output_closed() -> bool:
    """Whether stdout or stderr is a pipe whose reader has gone (poll reports an error)."""
    import select
    for stream in (sys.stdout, sys.stderr):
        try:
            poller = select.poll()
            poller.register(stream.fileno(), select.POLLOUT)
            if any(events & select.POLLERR for _, events in poller.poll(0)):
                return True
        except (AttributeError, OSError, ValueError):
            continue
    return False
