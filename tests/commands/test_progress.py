"""The progress bar in simulated seconds: drawn on a terminal only, never with --quiet or
in a pipe; lines printed while it is shown come out whole; -v/-vv/--quiet set logging."""

import argparse
import fcntl
import io
import logging
import os
import pathlib
import pty
import re
import struct
import subprocess
import sys
import termios

import pytest

import tegrasp_drake
from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.commands.verbosity import add_verbosity_arguments, log_level
from tests.cheap_contact import cheap_contact_arguments


class Terminal(io.StringIO):
    def isatty(self):
        return True


def package_path() -> str:
    """PYTHONPATH for a child that imports this same tegrasp_drake."""
    parent = str(pathlib.Path(tegrasp_drake.__file__).resolve().parent.parent)
    return os.pathsep.join(filter(None, [parent, os.environ.get("PYTHONPATH")]))


def arguments(*argv):
    parser = argparse.ArgumentParser()
    add_verbosity_arguments(parser)
    return parser.parse_args(argv)


def test_a_bar_only_on_a_terminal_and_never_with_quiet():
    assert progress_wanted(arguments(), Terminal())
    assert not progress_wanted(arguments("--quiet"), Terminal())
    assert not progress_wanted(arguments(), io.StringIO())  # a pipe or a file


def test_the_bar_counts_simulated_seconds_to_the_runs_end():
    stream = Terminal()
    with SimulatedTimeBar("trial", enabled=True, stream=stream) as progress:
        for t in (0.25, 5.0, 10.0):
            progress(t, 23.5)
        progress(13.0, 13.0)  # the state machine ended: the end moves in
    shown = stream.getvalue()
    assert re.search(r"trial:.*10\.0/23\.5 s simulated", shown), shown
    assert re.search(r"100%.*13\.0/13\.0 s simulated", shown), shown


def test_a_disabled_bar_draws_nothing_and_prints_lines(capsys):
    stream = Terminal()
    with SimulatedTimeBar("trial", enabled=False, stream=stream) as progress:
        progress(1.0, 10.0)
        progress.write("[   1.000 s] Reach -> Load")
    assert stream.getvalue() == ""
    assert capsys.readouterr().out == "[   1.000 s] Reach -> Load\n"


def test_verbosity_sets_the_package_log_level():
    assert log_level(0, False) == logging.WARNING
    assert log_level(1, False) == logging.INFO
    assert log_level(2, False) == logging.DEBUG
    assert log_level(0, True) == logging.WARNING
    with pytest.raises(SystemExit):
        arguments("-v", "--quiet")  # one or the other



@pytest.mark.parametrize("flags, says_meshcat_port", [((), False), (("-q",), False),
                                                     (("-v",), True)])
def test_drakes_info_lines_show_only_with_verbose(flags, says_meshcat_port):
    # Meshcat logs its port at INFO through pydrake's "drake" logger: not a warning. In a
    # child process: pytest's own root handlers would take the records here.
    script = ("import argparse, sys\n"
              "from pydrake.geometry import Meshcat\n"
              "from tegrasp_drake.commands.verbosity import (add_verbosity_arguments,\n"
              "                                              configure_logging)\n"
              "parser = argparse.ArgumentParser()\n"
              "add_verbosity_arguments(parser)\n"
              "configure_logging(parser.parse_args(sys.argv[1:]))\n"
              "Meshcat()\n")
    child = subprocess.run([sys.executable, "-c", script, *flags], capture_output=True,
                           text=True, timeout=300,
                           env={**os.environ, "PYTHONPATH": package_path()})
    assert child.returncode == 0, child.stderr
    assert ("Meshcat listening" in child.stderr) == says_meshcat_port, child.stderr

@pytest.mark.slow
@pytest.mark.parametrize("quiet", [False, True])
def test_a_demo_on_a_terminal_shows_the_bar_unless_quiet(tmp_path, quiet):
    """The real command, its stderr on a pseudo-terminal (its stdout a pipe, as in a script
    that reads --json): the bar is drawn there, and stdout holds only the JSON."""
    controller, terminal = pty.openpty()
    fcntl.ioctl(terminal, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))  # 120 columns
    # The cheap contact: the claim is where the bar and the JSON go, not the grasp.
    command = [sys.executable, "-m", "tegrasp_drake.cli", "demo", "--controller",
               "open_loop", "--json", "--out", str(tmp_path / "demo"),
               *cheap_contact_arguments(), "--quiet" if quiet else "-v"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=terminal,
                               stdin=subprocess.DEVNULL, cwd=tmp_path,
                               env=dict(os.environ, PYTHONPATH=package_path()))
    os.close(terminal)
    shown = b""
    while True:
        try:
            chunk = os.read(controller, 4096)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        shown += chunk
    stdout, _ = process.communicate(timeout=600)
    os.close(controller)
    assert process.returncode == 0, shown.decode(errors="replace")
    shown = shown.decode(errors="replace")
    assert stdout.decode().count("\n") == 1 and stdout.startswith(b"{")
    if quiet:
        assert "s simulated" not in shown and "INFO" not in shown, shown
    else:
        assert re.search(r"demo:.*\d+\.\d/\d+\.\d s simulated", shown), shown
        assert "INFO tegrasp_drake.runs.trial: trial: box" in shown, shown
    assert (tmp_path / "demo" / "result.json").is_file()
