"""Bad inputs found by the seventh hostile pass: a closed output pipe ends any command quietly,
and ranges start at a plausible physical minimum instead of an open zero."""

import io
import os

import pytest

from tegrasp_drake import cli


def _closed_pipe_stream() -> io.TextIOWrapper:
    """A buffered text stream on a pipe whose reader has gone (`tegrasp ... | head`)."""
    read, write = os.pipe()
    os.close(read)
    return io.TextIOWrapper(io.BufferedWriter(io.FileIO(write, "w"), buffer_size=1 << 16),
                            encoding="utf-8")


@pytest.mark.parametrize("argv, closed", [
    (["--help"], "stdout"),
    (["sweep", "--help"], "stdout"),
    (["trial", "--no-such-option"], "stderr"),  # argparse's usage error
])
def test_a_closed_output_pipe_ends_the_command_quietly(monkeypatch, argv, closed):
    stream = _closed_pipe_stream()
    monkeypatch.setattr(cli.sys, closed, stream)
    other = "stderr" if closed == "stdout" else "stdout"
    monkeypatch.setattr(cli.sys, other, io.StringIO())
    try:
        assert cli.main(argv) == cli.EXIT_CLOSED_PIPE
        stream.flush()  # what Python does at exit: nothing left to report
    finally:
        stream.close()
    assert "Traceback" not in getattr(cli.sys, other).getvalue()
