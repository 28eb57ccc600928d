"""Fixtures the bad-input tests share: a copy of the package's events to spoil, a guard
that fails a test whose trial reaches its simulator, one that fails a test whose numpy reads
an array, and the package's log levels as each test found them."""

import logging
import shutil

import numpy.lib.format as npy_format
import pytest

from tegrasp_drake.commands.verbosity import DRAKE_LOGGER, PACKAGE_LOGGER
from tegrasp_drake.rig import paths


@pytest.fixture(autouse=True)
def log_levels_as_found():
    """A command run in-process sets the package's and Drake's log levels for its -v
    (verbosity.configure_logging) and leaves them set: after `cli.main([..., "-v"])` the
    package logs at INFO in every later test of the process, so a test that draws a bar on
    a refusing stderr would see the INFO record fail there first. Each test leaves the
    levels as it found them."""
    loggers = [logging.getLogger(name) for name in (PACKAGE_LOGGER, DRAKE_LOGGER)]
    levels = [logger.level for logger in loggers]
    yield
    for logger, level in zip(loggers, levels):
        logger.setLevel(level)


@pytest.fixture
def events_copy(tmp_path):
    """A copy of the package's events to spoil."""
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("__init__.py", "__pycache__"))
    return folder


@pytest.fixture
def no_simulation(monkeypatch):
    """Fails a test whose trial reaches its simulator."""
    from tegrasp_drake.runs import trial

    def simulated(*args, **kwargs):
        raise AssertionError("the trial was simulated")
    monkeypatch.setattr(trial, "MakeSimulator", simulated)


@pytest.fixture
def no_array_is_read(monkeypatch):
    """Fails the test if numpy is asked to read (and so allocate) any array."""
    def refuse(*args, **kwargs):
        raise AssertionError("an array was read before its header was checked")
    monkeypatch.setattr(npy_format, "read_array", refuse)
