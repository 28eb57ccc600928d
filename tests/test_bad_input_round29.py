"""Signals the fourteenth hostile pass sent to a running `tegrasp`: a second one while the
first is handled, one while pydrake is imported. Each test runs the real command line
(`python -m tegrasp_drake`) in a subprocess whose signals are sent from inside the calls
they must interrupt (a staging folder made or removed, a module imported, the interpreter's
exit), so what arrives when does not depend on how loaded the machine is: a sitecustomize
module, which Python imports at start-up, wraps those calls."""

import signal
import subprocess
import sys

from tests import killed_runs

# The wrapped calls, chosen by the variable SIGNALS_AT. "staging": SIGHUP as the run's
# staging folder is made and SIGTERM as it is removed (the second signal during the first's
# cleanup), then SIGINT and SIGTERM at the interpreter's exit. "import": SIGTERM as
# pydrake.common, a C++ module, imports its first Python module (inside the C++
# initialisation that catches a KeyboardInterrupt). "exec": SIGTERM inside code run by
# exec() of a string (as scipy imports numpy) while the run's folder is made.
_SITECUSTOMIZE = """
import atexit, importlib.abc, os, pathlib, shutil, signal, sys, tempfile

def send(number):
    os.kill(os.getpid(), number)

where = os.environ.pop("SIGNALS_AT", "")
if where == "staging":
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
elif where == "import":
    class SignalAtPydrake(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.startswith("pydrake.common.") and not getattr(self, "sent", False):
                self.sent = True
                send(signal.SIGTERM)
            return None

    sys.meta_path.insert(0, SignalAtPydrake())
elif where == "exec":
    mkdir = pathlib.Path.mkdir

    def signalled_mkdir(self, *args, **kwargs):
        if self.name == "run":
            exec("send(signal.SIGTERM)", {"send": send, "signal": signal})
        return mkdir(self, *args, **kwargs)

    pathlib.Path.mkdir = signalled_mkdir
"""


def _default_signal_dispositions():
    """The child's termination signals as a terminal's shell leaves them: a suite run under
    `nohup` (or a runner that ignores SIGHUP) would pass its SIG_IGN on, which tegrasp
    rightly leaves alone, and the SIGHUP this test sends would never arrive."""
    for number in (signal.SIGHUP, signal.SIGTERM, signal.SIGINT):
        signal.signal(number, signal.SIG_DFL)


def _run_signalled(where, tmp_path, *arguments):
    """(exit code, stderr) of `python -m tegrasp_drake ARGUMENTS` signalled at `where`."""
    hooks = tmp_path / "hooks"
    hooks.mkdir()
    (hooks / "sitecustomize.py").write_text(_SITECUSTOMIZE)
    environment = killed_runs.environment()
    environment.update(PYTHONPATH=f"{hooks}:{environment['PYTHONPATH']}", SIGNALS_AT=where,
                       PYTHONUTF8="1")
    finished = subprocess.run([sys.executable, "-m", "tegrasp_drake", *arguments],
                              env=environment, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True, timeout=600,
                              preexec_fn=_default_signal_dispositions)
    return finished.returncode, finished.stderr


def _assert_one_interruption_line(code, text, name):
    assert "Traceback" not in text and "At:" not in text, text
    assert code == 128 + signal.Signals[name].value, (code, text)
    assert text.strip().splitlines()[-1] == (
        f"tegrasp: interrupted ({name}); the run's unfinished files were removed"), text


# Rule: the first termination signal is taken once; more while it is handled, or while the
# interpreter exits, neither print a traceback nor change the exit code nor keep a file.
def test_a_second_signal_during_the_cleanup_of_the_first_is_not_a_traceback(tmp_path):
    code, text = _run_signalled("staging", tmp_path, "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    _assert_one_interruption_line(code, text, "SIGHUP")
    assert not (tmp_path / "run").exists()  # the staging folder removed, and the folder made for it


# Rule: a signal during pydrake's import is acted on once the import returned: the one line,
# not pydrake's own report of a KeyboardInterrupt in its initialisation.
def test_a_signal_while_pydrake_is_imported_is_the_one_interruption_line(tmp_path):
    code, text = _run_signalled("import", tmp_path, "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    _assert_one_interruption_line(code, text, "SIGTERM")
    assert not (tmp_path / "run").exists()


# Rule: the exit code is the signal's even when its KeyboardInterrupt passed through code
# that exec() ran from a string (CPython then ends a `python -m` process by SIGINT).
def test_an_interrupt_raised_inside_exec_keeps_the_signals_exit_code(tmp_path):
    code, text = _run_signalled("exec", tmp_path, "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    _assert_one_interruption_line(code, text, "SIGTERM")
    assert not (tmp_path / "run").exists()
