"""Fixtures shared by test modules."""

import fcntl
import functools
import os
import signal

import pytest

from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario.trial_log_file import ARRAY_FIELDS, load_trial_log
from tegrasp_drake.hardware.realtime import realtime_scheduling


def pytest_configure(config):
    """The suite runs as a user at a terminal runs a command: Ctrl-C (SIGINT) and Ctrl-\\
    (SIGQUIT) stop it. A shell without job control starts a background job with both
    ignored, and the commands rightly leave an ignored signal ignored; the tests of what such
    a signal does would then see none. The commands the tests start get the default action
    back too: exec resets a handled signal and keeps an ignored one."""
    defaults = {signal.SIGINT: signal.default_int_handler, signal.SIGQUIT: signal.SIG_DFL}
    for number, handler in defaults.items():
        if signal.getsignal(number) == signal.SIG_IGN:
            signal.signal(number, handler)


def pytest_collection_modifyitems(items):
    """Test files marked `long_file` run first. `tests/run` gives each file whole to one
    worker (xdist's `--dist loadfile`) in the order collected, so a file that takes a
    quarter of the suite's time, started late, ends running alone on one core while the
    other waits. The sort is stable: within each group the collected order stays."""
    items.sort(key=lambda item: item.get_closest_marker("long_file") is None)


@pytest.fixture(scope="module", autouse=True)
def deployment_scheduling_for_real_time_tests(request):
    """A module marked `real_time` (devices or emulators against the clock, with timeouts of
    50-500 ms) runs at the scheduling a deployment uses (SCHED_FIFO 10, where allowed; the
    threads it starts inherit it), so that a busy host cannot starve it past a timeout: beside
    a CPU hog on every core such tests failed at normal scheduling."""
    if request.node.get_closest_marker("real_time") is None:
        yield
        return
    with realtime_scheduling("fifo", 10):
        yield


@pytest.fixture(autouse=True)
def empty_user_events_folder(tmp_path_factory, monkeypatch):
    """Tests read the package's events, never the developer's own recorded ones: the user's
    events folder (TEGRASP_EVENTS_DIR) is an empty folder of the test session."""
    folder = tmp_path_factory.getbasetemp() / "user-events"
    folder.mkdir(exist_ok=True)
    monkeypatch.setenv("TEGRASP_EVENTS_DIR", str(folder))
    return folder


@pytest.fixture(scope="session")
def ideal_grasp_log(tmp_path_factory):
    """ideal_grasp_log(object_name) -> the TrialLog of that object's ideal grasp on its
    built-in scenario.

    Each grasp is simulated once per test run (a minute or more each) and shared by every
    test that asks for it: the first pytest-xdist worker to ask simulates it and saves it in
    the run's shared folder, under a lock the others wait on. Every test gets the log as
    read back from that file, whichever worker simulated it; its arrays are read-only, so
    that no test can change another's data.
    """
    shared = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):  # basetemp/popen-gwN: the parent is the run's
        shared = shared.parent
    shared = shared / "ideal-grasps"
    shared.mkdir(exist_ok=True)

    @functools.cache
    def run(object_name: str):
        saved = shared / f"{object_name}.npz"
        with open(shared / f"{object_name}.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
            if not saved.exists():
                log, _ = run_ideal_grasp(LoadScenario(name=object_name))
                log.save(saved)
        log = load_trial_log(saved)
        for name in ARRAY_FIELDS:
            getattr(log, name).setflags(write=False)
        return log
    return run
