"""A FileWindow answers len(), slices and find() as the file's bytes do, reading a window at
a time."""

import io

import numpy as np
import pytest

from tegrasp_drake.rig.file_window import FileWindow

SYNC = b"\xed\xa1\xda\x01"


def _file_bytes(size: int = 5000) -> bytes:
    rng = np.random.default_rng(7)
    data = bytearray(rng.integers(0, 256, size, dtype=np.uint8).tobytes())
    for position in (0, 61, 62, 127, 1000, 4995):  # across and at the windows' edges
        data[position:position + 4] = SYNC
    return bytes(data[:size])


def test_slices_are_the_files_bytes_across_window_edges():
    data = _file_bytes()
    window = FileWindow(io.BytesIO(data), len(data), window=64)
    assert len(window) == len(data)
    rng = np.random.default_rng(3)
    for start, length in zip(rng.integers(-10, len(data) + 10, 300),
                             rng.integers(0, 300, 300)):
        start = int(start)
        assert window[start:start + int(length)] == data[start:start + int(length)]
    assert window[len(data) - 3:len(data) + 50] == data[-3:]
    with pytest.raises(TypeError):
        window[::2]


def test_find_is_bytes_find_also_across_window_edges():
    data = _file_bytes()
    window = FileWindow(io.BytesIO(data), len(data), window=64)
    for start in [0, 1, 59, 60, 61, 62, 63, 64, 100, 128, 999, 1001, 4994, 4996, 5000, 6000]:
        assert window.find(SYNC, start) == data.find(SYNC, start), start
    assert window.find(b"not there at all", 0) == -1


def test_reads_are_at_most_the_window_for_small_slices():
    data = _file_bytes()
    sizes = []

    class Recorded(io.BytesIO):
        def read(self, size=-1):
            sizes.append(size)
            return super().read(size)

    window = FileWindow(Recorded(data), len(data), window=64)
    position = 0
    while position >= 0:
        position = window.find(SYNC, position + 1)
        window[position:position + 28]
    assert sizes and all(0 <= size <= 64 for size in sizes)
