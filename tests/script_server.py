"""A process that runs the scripts of analysis/ as `python analysis/NAME.py ARGS` runs them,
and the command line as `python -m tegrasp_drake ARGS` does, each in a child forked from it,
without each child importing pydrake, matplotlib and the package anew (3-8 s a run on 2
cores; a fork costs about 0.1 s). No tests here.

Run as `python tests/script_server.py` with the environment every script gets (PYTHONPATH,
MPLBACKEND): it imports every script as a module (their imports, never their `main`) and the
command line's modules, then reads one request a line on stdin (JSON: a script's path or a
module's name, argv, cwd, env, stdout and stderr paths) and answers each with a line {"pid":
N}, the child's, then one {"returncode": N}. The child leaves the loop and runs the script or
module at this file's top level, as the interpreter runs one: its SystemExit, an uncaught
exception (a traceback on stderr, exit 1) and the flush of its standard output at exit are
the interpreter's own, on the files the request named. The server has no thread of its own
(only numpy's idle BLAS threads), so a forked child holds no lock another thread held.

`ScriptServer` is the tests' side: it starts the server and sends it requests."""

import contextlib
import importlib
import json
import os
import runpy
import select
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]
ANALYSIS = REPOSITORY / "analysis"


def _serve() -> dict:
    """The server's loop; returns only in a forked child, with its request."""
    for path in sorted(ANALYSIS.glob("*.py")):
        runpy.run_path(str(path), run_name=f"preloaded_{path.stem}")
    for path in sorted((REPOSITORY / "tegrasp_drake" / "commands").glob("*.py")):
        importlib.import_module(f"tegrasp_drake.commands.{path.stem}")
    importlib.import_module("tegrasp_drake.cli")
    sys.stdout.write("ready\n")
    sys.stdout.flush()
    for line in sys.stdin:
        request = json.loads(line)
        pid = os.fork()
        if pid == 0:
            return request
        sys.stdout.write(json.dumps({"pid": pid}) + "\n")
        sys.stdout.flush()
        _, status = os.waitpid(pid, 0)
        sys.stdout.write(json.dumps({"returncode": os.waitstatus_to_exitcode(status)}) + "\n")
        sys.stdout.flush()
    sys.exit(0)


def _become(request: dict) -> None:
    """Turns this forked child into the process `python SCRIPT ARGV` (or `python -m MODULE
    ARGV`) would be, started in `cwd` with environment `env`, stdin /dev/null, stdout and
    stderr the named files."""
    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"])
    streams = ((0, os.devnull, os.O_RDONLY),
               (1, request["stdout"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC),
               (2, request["stderr"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC))
    for fd, path, flags in streams:
        opened = os.open(path, flags, 0o600)
        os.dup2(opened, fd)
        os.close(opened)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    if request.get("script"):
        sys.argv = [request["script"], *request["argv"]]
        sys.path[0] = str(Path(request["script"]).resolve().parent)
    else:
        sys.argv = [request["module"], *request["argv"]]
        sys.path[0] = request["cwd"]


def _run(request: dict) -> None:
    if request.get("script"):
        runpy.run_path(request["script"], run_name="__main__")
    else:
        runpy.run_module(request["module"], run_name="__main__", alter_sys=True)


class ScriptServer:
    """The tests' side of a server process (started on first use with `environment`, ended
    by `close` or when this process ends and its stdin closes)."""

    def __init__(self, environment: dict):
        self._environment = environment
        self._process = None

    def run(self, script: Path | None, argv: list[str], cwd, env: dict, *,
            module: str | None = None, stdout: str | None = None,
            timeout_s: float = 300.0) -> subprocess.CompletedProcess:
        """`python SCRIPT ARGV` (or `python -m MODULE ARGV`, `script` None) run in `cwd` with
        environment `env`: its exit code, and what it wrote on stdout and stderr (text);
        `stdout` a path to send its standard output to instead (/dev/full), then what it
        wrote there is not read back. A run past `timeout_s` (a hang guard) is killed with
        the server, and raises subprocess.TimeoutExpired."""
        process = self._started()
        command = ([str(script)] if script else ["-m", module]) + [str(a) for a in argv]
        with tempfile.TemporaryDirectory(prefix="script-run-") as folder:
            out = stdout or os.path.join(folder, "stdout")
            err = os.path.join(folder, "stderr")
            request = {"script": str(script) if script else None, "module": module,
                       "argv": [str(a) for a in argv], "cwd": str(cwd), "env": dict(env),
                       "stdout": out, "stderr": err}
            process.stdin.write(json.dumps(request) + "\n")
            process.stdin.flush()
            child = json.loads(process.stdout.readline())["pid"]
            ready, _, _ = select.select([process.stdout], [], [], timeout_s)
            if not ready:
                with contextlib.suppress(ProcessLookupError):
                    os.kill(child, signal.SIGKILL)
                self.close()
                raise subprocess.TimeoutExpired(command, timeout_s)
            answer = json.loads(process.stdout.readline())
            written = "" if stdout else Path(out).read_text(errors="replace")
            return subprocess.CompletedProcess(command, answer["returncode"], written,
                                               Path(err).read_text(errors="replace"))

    def _started(self) -> subprocess.Popen:
        if self._process is None or self._process.poll() is not None:
            self._process = subprocess.Popen(
                [sys.executable, __file__], env=self._environment, cwd=REPOSITORY,
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            if self._process.stdout.readline() != "ready\n":
                raise RuntimeError("the script server did not start; run "
                                   "`python tests/script_server.py` to see why")
        return self._process

    def close(self):
        if self._process is not None:
            self._process.kill()
            self._process.wait()
            self._process.stdin.close()
            self._process.stdout.close()
            self._process = None


if __name__ == "__main__":
    _request = _serve()
    _become(_request)
    _run(_request)
