"""Scripts of analysis/ and the `tegrasp` command line run as a user runs them, each in a
process of its own, forked from one process per test worker that imported their modules
once (tests/script_server.py): a run costs about 0.1 s instead of 3-8 s of imports. Tests of
what a process does with signals, its process group or a terminal start a real one."""

import atexit
import os
import subprocess

from tests.script_server import ANALYSIS, REPOSITORY, ScriptServer


def script_environment(env: dict | None = None) -> dict:
    """The environment a run gets: `env` (default this process's), the repository importable
    and matplotlib drawing to files."""
    return dict(os.environ if env is None else env, PYTHONPATH=str(REPOSITORY),
                MPLBACKEND="Agg")


_server: ScriptServer | None = None


def _started_server() -> ScriptServer:
    global _server
    if _server is None:
        _server = ScriptServer(script_environment())
        atexit.register(_server.close)
    return _server


def run_analysis_script(name: str, arguments: list[str], cwd, *,
                        stdout: str | None = None) -> subprocess.CompletedProcess:
    """`python analysis/NAME.py ARGUMENTS` run from `cwd`; `stdout` a path for its standard
    output (/dev/full) instead of reading it back."""
    return _started_server().run(ANALYSIS / f"{name}.py", arguments, cwd,
                                 script_environment(), stdout=stdout)


def run_tegrasp(arguments: list[str], cwd, *, env: dict | None = None,
                timeout_s: float = 300.0) -> subprocess.CompletedProcess:
    """`python -m tegrasp_drake ARGUMENTS` (what `tegrasp` runs) from `cwd`, with `env`
    (default this process's environment)."""
    return _started_server().run(None, arguments, cwd, script_environment(env),
                                 module="tegrasp_drake", timeout_s=timeout_s)
