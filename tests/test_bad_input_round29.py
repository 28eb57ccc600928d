"""Signals the fourteenth hostile pass sent to a running `tegrasp`: a second one while the
first is handled, one while pydrake is imported. Each test runs the real command line
(`python -m tegrasp_drake`) in a subprocess whose signals are sent from inside the calls
they must interrupt (a staging folder made or removed, a module imported, the interpreter's
exit), so what arrives when does not depend on how loaded the machine is."""

import signal
import subprocess
import sys

from tests import killed_runs

# Runs `python -m tegrasp_drake ARGS` after wrapping the calls named by the first argument:
# "staging" sends SIGHUP as the run's staging folder is made and SIGTERM as it is removed
# (the second signal during the first's cleanup), then SIGINT and SIGTERM at the
# interpreter's exit; "import" sends SIGTERM as pydrake.common, a C++ module, imports its
# first Python module (inside the C++ initialisation that catches a KeyboardInterrupt).
_BOOTSTRAP = """
import atexit, importlib.abc, os, runpy, shutil, signal, sys, tempfile

def send(number):
    os.kill(os.getpid(), number)

if sys.argv[1] == "staging":
    made, removed = tempfile.mkdtemp, shutil.rmtree

    def mkdtemp(*args, **kwargs):
        folder = made(*args, **kwargs)
        if os.path.basename(folder).startswith(".staging-"):
            send(signal.SIGHUP)
        return folder

    def rmtree(path, *args, **kwargs):
        if os.path.basename(str(path)).startswith(".staging-"):
            send(signal.SIGTERM)
        return removed(path, *args, **kwargs)

    tempfile.mkdtemp, shutil.rmtree = mkdtemp, rmtree
    atexit.register(lambda: (send(signal.SIGINT), send(signal.SIGTERM)))
else:
    class SignalAtPydrake(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.startswith("pydrake.common.") and not getattr(self, "sent", False):
                self.sent = True
                send(signal.SIGTERM)
            return None

    sys.meta_path.insert(0, SignalAtPydrake())
sys.argv = [sys.argv[0], *sys.argv[2:]]
runpy.run_module("tegrasp_drake", run_name="__main__", alter_sys=True)
"""


def _run_signalled(how, *arguments):
    """(exit code, stderr) of `tegrasp ARGUMENTS` signalled as `how` says (_BOOTSTRAP)."""
    finished = subprocess.run([sys.executable, "-c", _BOOTSTRAP, how, *arguments],
                              env={**killed_runs.environment(), "PYTHONUTF8": "1"},
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                              timeout=600)
    return finished.returncode, finished.stderr


def _assert_one_interruption_line(code, text, name):
    assert "Traceback" not in text and "At:" not in text, text
    assert code == 128 + signal.Signals[name].value, (code, text)
    assert text.strip().splitlines()[-1] == (
        f"tegrasp: interrupted ({name}); the run's unfinished files were removed"), text


# Rule: the first termination signal is taken once; more while it is handled, or while the
# interpreter exits, neither print a traceback nor change the exit code nor keep a file.
def test_a_second_signal_during_the_cleanup_of_the_first_is_not_a_traceback(tmp_path):
    code, text = _run_signalled("staging", "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    _assert_one_interruption_line(code, text, "SIGHUP")
    assert list((tmp_path / "run").iterdir()) == []  # the staging folder removed


# Rule: a signal during pydrake's import is acted on once the import returned: the one line,
# not pydrake's own report of a KeyboardInterrupt in its initialisation.
def test_a_signal_while_pydrake_is_imported_is_the_one_interruption_line(tmp_path):
    code, text = _run_signalled("import", "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    _assert_one_interruption_line(code, text, "SIGTERM")
    assert not (tmp_path / "run").exists()
