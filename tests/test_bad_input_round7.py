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


@pytest.mark.parametrize("override, words", [
    ("object.mass=1.0e-9", "field 'object.mass' must lie in [0.01, 5] kg"),
    ("object.mass=1e-30", "field 'object.mass' must lie in [0.01, 5] kg"),  # read as a number
    ("object.size=[1.0e-4,1.0e-4,0.11]", "field 'object.size[0]' must lie in [0.005, 0.5] m"),
])
def test_a_tiny_object_is_refused_before_drake_sees_it(override, words):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    with pytest.raises(ConfigError) as error:
        LoadScenario(name="box", overrides=[override])
    assert words in str(error.value)


def test_the_smallest_object_is_one_the_contact_geometry_resolves():
    from tegrasp_drake.rig.objects import MIN_SIZE_M
    from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y
    from tegrasp_drake.simulation.object_model import MESH_RESOLUTION_M
    assert MESH_RESOLUTION_M <= MIN_SIZE_M <= min(CELL_X, CELL_Y)
