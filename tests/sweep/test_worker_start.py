"""A sweep's worker processes are forked from a server that has imported the trial function's
module (and pydrake) once, rather than each importing them anew (runner.worker_context)."""

import json
import multiprocessing
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

REPOSITORY = Path(__file__).resolve().parents[2]

# In a process of its own: the fork server is started once per process, by its first sweep,
# and keeps the modules that sweep's trial function asked for.
SWEEP_TWICE = textwrap.dedent("""
    import json, os, sys
    from tegrasp_drake.sweep import SweepSpec, run_sweep
    from tests.sweep.import_process_trial import import_reporting_trial

    def main(out):
        spec = SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                         grid=((0.0, 0.0), (0.01, 0.0)))
        seen = []
        for folder in ("first", "second"):  # two sweeps share one server
            run_sweep(spec, import_reporting_trial, os.path.join(out, folder), workers=1,
                      progress=False)
            for path in sorted(os.scandir(os.path.join(out, folder, "trials")),
                               key=lambda entry: entry.name):
                result = json.load(open(path.path))["result"]
                seen.append([result["imported_in_pid"], result["worker_pid"]])
        print(json.dumps({"parent": os.getpid(), "seen": seen}))

    if __name__ == "__main__":
        main(sys.argv[1])
""")


@pytest.mark.skipif("forkserver" not in multiprocessing.get_all_start_methods(),
                    reason="the platform has no fork server; workers are spawned")
def test_workers_fork_from_a_server_that_imported_the_trial_function(tmp_path):
    script = tmp_path / "sweep_twice.py"
    script.write_text(SWEEP_TWICE)
    done = subprocess.run([sys.executable, str(script), str(tmp_path)], cwd=REPOSITORY,
                          env={"PYTHONPATH": str(REPOSITORY), "PATH": "/usr/bin:/bin"},
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout.strip().splitlines()[-1])
    seen = report["seen"]
    assert len(seen) == 4
    importers = {importer for importer, _ in seen}
    workers = {worker for _, worker in seen}
    assert len(importers) == 1, seen  # one process imported the module, for every worker
    assert not importers & workers and report["parent"] not in importers, report
    assert len(workers) >= 2  # the second sweep started workers of its own
