"""A file's bytes read through a window of bounded size: `FileWindow` answers len(), slices
and find() as the file's bytes would, holding at most about `window` bytes (one slice larger
than that is read whole), so a scan of a file of any size holds one window, not the file."""

DEFAULT_WINDOW_BYTES = 1 << 20


class FileWindow:
    """The first `size` bytes of the binary `stream` (a regular file open for reading), as a
    read-only bytes-like object: len(), data[a:b] (step 1) and find(sub, start). Reads seek
    and read the stream: a forward scan reads each byte about once."""

    def __init__(self, stream, size: int, window: int = DEFAULT_WINDOW_BYTES):
        self._stream, self._size, self._window = stream, size, window
        self._start, self._bytes = 0, b""

    def __len__(self) -> int:
        return self._size

    def _hold(self, start: int, stop: int) -> None:
        """Reads the window [start, ...) unless [start, stop) is held already."""
        if self._start <= start and stop <= self._start + len(self._bytes):
            return
        self._stream.seek(start)
        self._bytes = self._stream.read(min(max(stop - start, self._window),
                                            self._size - start))
        self._start = start

    def __getitem__(self, index: slice) -> bytes:
        if not isinstance(index, slice) or index.step not in (None, 1):
            raise TypeError("a FileWindow is sliced with [start:stop] only")
        start, stop, _ = index.indices(self._size)
        if stop <= start:
            return b""
        self._hold(start, stop)
        return self._bytes[start - self._start:stop - self._start]

    def find(self, sub: bytes, start: int = 0) -> int:
        """The position of the first `sub` at or after `start`, or -1 (as bytes.find)."""
        start = max(start, 0)
        while start + len(sub) <= self._size:
            self._hold(start, start + len(sub))
            found = self._bytes.find(sub, start - self._start)
            if found >= 0:
                return self._start + found
            if self._start + len(self._bytes) >= self._size or not self._bytes:
                return -1
            start = self._start + len(self._bytes) - len(sub) + 1  # a match across the edge
        return -1
