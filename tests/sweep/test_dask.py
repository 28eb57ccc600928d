"""The same sweep on a Dask distributed cluster (a local one here)."""

import logging
import threading

import pytest

from tegrasp_drake.sweep import runner
from tegrasp_drake.sweep.records import load_records
from tegrasp_drake.sweep.runner import SweepError, run_sweep
from tegrasp_drake.sweep.spec import SweepSpec
from tests.fake_trials import failing_fake_trial, fake_trial, process_reporting_fake_trial

distributed = pytest.importorskip(
    "distributed", reason="the optional 'dask' extra (dask, distributed) is not installed")

SPEC = SweepSpec(objects=("box", "thick_cylinder"), controllers=("memorized", "heuristic"),
                 attempts=1)


@pytest.fixture(scope="module")
def scheduler_address():
    import dask
    # Dask's 30 s connection timeouts are hang guards; a busy host can take longer to
    # start two worker processes, which is no failure of the sweep.
    with dask.config.set({"distributed.comm.timeouts.connect": "600s",
                          "distributed.comm.timeouts.tcp": "600s"}), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=":0") as cluster:  # any free port:
        # None means Dask's default :8787, which another process on the host may hold
        yield cluster.scheduler_address


def test_dask_cluster_records_the_same_as_the_process_pool(tmp_path, scheduler_address):
    dask_dir, pool_dir = tmp_path / "dask", tmp_path / "pool"
    summary = run_sweep(SPEC, fake_trial, dask_dir, scheduler=scheduler_address,
                        progress=False)
    assert summary.backend == f"dask:{scheduler_address}"
    assert (summary.ran, summary.errors, summary.unfinished) == (36, (), ())
    run_sweep(SPEC, fake_trial, pool_dir, workers=2, progress=False)
    assert load_records(dask_dir).records == load_records(pool_dir).records


def test_dask_run_records_errors_and_reruns_them_on_resume(tmp_path, scheduler_address):
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=2)
    summary = run_sweep(spec, failing_fake_trial, tmp_path, scheduler=scheduler_address,
                        progress=False)
    assert len(summary.errors) == 9 and summary.ran == 18
    summary = run_sweep(spec, fake_trial, tmp_path, scheduler=scheduler_address,
                        progress=False)
    assert (summary.ran, summary.skipped, summary.errors) == (9, 9, ())


def test_an_unreachable_scheduler_is_reported(tmp_path, monkeypatch):
    monkeypatch.setattr(runner, "DASK_CONNECT_TIMEOUT_S", 1.0)
    with pytest.raises(SweepError, match="cannot reach the Dask scheduler"):
        run_sweep(SPEC, fake_trial, tmp_path, scheduler="tcp://127.0.0.1:9", progress=False)
    assert not (tmp_path / "trials").exists()


def test_a_cluster_with_more_workers_than_cores_runs_every_trial_once(tmp_path):
    workers = runner.default_workers() + 2
    spec = SweepSpec(objects=("box",), controllers=("memorized", "heuristic"), attempts=2)
    # Its own dashboard port (":0", any free one): the module's cluster may still hold 8787.
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
        summary = run_sweep(spec, process_reporting_fake_trial, tmp_path,
                            scheduler=cluster.scheduler_address, progress=False)
    assert (summary.ran, summary.errors, summary.unfinished) == (36, (), ())
    records = load_records(tmp_path).records
    assert len(records) == 36
    assert len({r["result"]["worker_pid"] for r in records.values()}) > runner.default_workers()


def test_a_trial_whose_worker_dies_is_named_lost_and_runs_on_resume(tmp_path, scheduler_address,
                                                                     capsys):
    """A trial that kills its Dask worker (each time the scheduler retries it) leaves no
    record; the sweep names it in one line with the command that runs it, and the same
    command with a working trial function finishes it."""
    from tegrasp_drake import cli
    command = ["sweep", "--objects", "box", "--controllers", "memorized", "--attempts", "1",
               "--scheduler", scheduler_address, "--out", str(tmp_path), "--no-progress",
               "--trial-function"]
    code = cli.main(command + ["tests.fake_trials:dying_fake_trial"])
    out = capsys.readouterr().out
    lost = [line for line in out.splitlines() if "memorized/box/m11/a0" in line]
    assert code == 1 and len(lost) == 1, out
    assert "a worker died" in lost[0] and "same command" in lost[0]
    # the trial killed with its worker (it may take another running there with it): each
    # one left without a record is named, and none is recorded as finished
    recorded = load_records(tmp_path).records
    from tegrasp_drake.sweep.spec import marker_names
    missing = {f"memorized/box/{marker}/a0"
               for marker in marker_names(SweepSpec().grid)} - set(recorded)
    assert "memorized/box/m11/a0" in missing
    assert f"{len(missing)} trial(s) unfinished" in lost[0]
    assert all(trial_id in lost[0] for trial_id in missing)
    assert cli.main(command + ["tests.fake_trials:fake_trial"]) == 0
    out = capsys.readouterr().out
    assert f"{len(missing)} run now" in out and f"{9 - len(missing)} already finished" in out
    assert len(load_records(tmp_path).records) == 9


def test_a_scheduler_address_is_read_in_any_case(tmp_path, scheduler_address):
    """distributed knows the protocol "tcp" only in lower case; the address check reads it
    in any case, and the connection passes it on in lower case."""
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1)
    shouted = scheduler_address.replace("tcp://", "TCP://")
    client = runner.connect_scheduler(shouted)
    try:
        summary = run_sweep(spec, fake_trial, tmp_path, scheduler=client, progress=False)
    finally:
        client.close()
    assert (summary.ran, summary.errors) == (9, ())


class _ActOnNoWorkersLine(logging.Handler):
    """Keeps the sweep's warnings; on the no-worker line, does `act` (what a user would)."""

    def __init__(self, act):
        super().__init__(level=logging.WARNING)
        self.said, self.act, self.told = [], act, threading.Event()

    def emit(self, record):
        self.said.append(record.getMessage())
        if "has had no worker" in record.getMessage():
            self.told.set()
            self.act()


@pytest.fixture
def cluster_without_workers(monkeypatch):
    """A scheduler with no worker (a LocalCluster of none, scaled up by a test when it
    likes), the sweep's no-worker delay short, and a hang guard: if the sweep never says it
    has no workers, a worker is started after ten minutes all the same, so the test fails
    on its assertions instead of hanging."""
    import dask
    monkeypatch.setattr(runner, "NO_WORKERS_NOTICE_S", 0.5)
    with dask.config.set({"distributed.comm.timeouts.connect": "600s",
                          "distributed.comm.timeouts.tcp": "600s"}), \
            distributed.LocalCluster(n_workers=0, threads_per_worker=1, processes=True,
                                     dashboard_address=":0") as cluster:
        handlers = []
        guard_ends = threading.Event()
        guard = threading.Thread(
            target=lambda: guard_ends.wait(600.0) or any(h.told.is_set() for h in handlers)
            or cluster.scale(1), daemon=True)
        guard.start()
        try:
            yield cluster, handlers
        finally:
            guard_ends.set()
            for handler in handlers:
                runner.logger.removeHandler(handler)


def _said_no_workers(handler, cluster) -> str:
    told = [line for line in handler.said if "has had no worker" in line]
    assert len(told) == 1, handler.said
    address = cluster.scheduler_address
    assert f"the Dask scheduler at {address} has had no worker for" in told[0]
    assert f"9 trials waiting: start one with `dask worker {address}`" in told[0]
    assert "Ctrl-C" in told[0] and "\n" not in told[0]
    return told[0]


def test_a_scheduler_without_workers_is_said_once_and_the_trials_run_when_one_joins(
        tmp_path, cluster_without_workers):
    cluster, handlers = cluster_without_workers
    handler = _ActOnNoWorkersLine(lambda: cluster.scale(1))
    handlers.append(handler)
    runner.logger.addHandler(handler)
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1)
    summary = run_sweep(spec, fake_trial, tmp_path, scheduler=cluster.scheduler_address,
                        progress=False)
    _said_no_workers(handler, cluster)
    assert (summary.ran, summary.errors, summary.unfinished) == (9, (), ())


def test_a_sweep_waiting_for_workers_stops_on_ctrl_c_and_the_same_sweep_resumes(
        tmp_path, cluster_without_workers):
    cluster, handlers = cluster_without_workers

    def press_ctrl_c():
        raise KeyboardInterrupt  # as the signal does, in the thread that waits

    handler = _ActOnNoWorkersLine(press_ctrl_c)
    handlers.append(handler)
    runner.logger.addHandler(handler)
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, fake_trial, tmp_path, scheduler=cluster.scheduler_address,
                  progress=False)
    _said_no_workers(handler, cluster)
    runner.logger.removeHandler(handler)
    cluster.scale(1)
    summary = run_sweep(spec, fake_trial, tmp_path, scheduler=cluster.scheduler_address,
                        progress=False)
    assert (summary.ran, summary.skipped, summary.errors) == (9, 0, ())
