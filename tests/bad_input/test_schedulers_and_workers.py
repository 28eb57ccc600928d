"""Sweep runners: more workers than cores is refused unless asked for; a Dask scheduler
address that is not one (a form, a path, an in-process address, another service) is one
error; a scheduler is connected to once, and one that goes away mid-sweep is one line with
its finished trials kept; a --trial-function that is not module:name or fails on import is
one line."""

import contextlib
import re
import subprocess
import sys
import time

import pytest

from tegrasp_drake import cli
from tegrasp_drake.sweep.records import load_records
from tests import killed_runs
from tests.bad_input.probes import FAKE_TRIALS, assert_one_line_error, one_line_of, run_cli


def test_more_workers_than_cores_is_refused_unless_asked_for(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.sweep import runner
    monkeypatch.setattr(runner, "default_workers", lambda: 2)
    code, text = run_cli(["sweep", "--workers", "54", "--out", str(tmp_path / "sw")], capfd)
    assert_one_line_error(code, text, "--workers 54", "2 core(s)", "--oversubscribe")
    assert not (tmp_path / "sw").exists()


# Rule: a setting a command cannot use stops it before it does any work. `--scheduler` is
# checked whole (its address, the Dask extra, whether the scheduler answers) by the runner
# arguments' check that sweep, transfer and sensitivity share, so transfer and sensitivity
# refuse it before recording any world's events, as sweep refuses it before any trial.
@pytest.mark.parametrize("command, spec", [
    ("transfer", "analysis/transfer_matrix.yaml"),
    ("sensitivity", "analysis/sensitivity.yaml"),
])
@pytest.mark.parametrize("cause, words", [("no extra", "tegrasp-drake[dask]"),
                                          ("no answer", "cannot reach the Dask scheduler")])
def test_a_scheduler_that_cannot_work_is_refused_before_any_event_is_recorded(
        tmp_path, monkeypatch, capsys, command, spec, cause, words):
    from tegrasp_drake.sweep import runner
    from tegrasp_drake.transfer import matrix

    def no_recording(*args, **kwargs):
        raise AssertionError("events recorded before --scheduler was checked")

    monkeypatch.setattr(matrix, "record_world_events", no_recording)
    if cause == "no extra":
        monkeypatch.setitem(sys.modules, "distributed", None)  # as if it were not installed
    else:
        pytest.importorskip("distributed", reason="the optional 'dask' extra is not installed")
        monkeypatch.setattr(runner, "DASK_CONNECT_TIMEOUT_S", 1.0)
    code = cli.main([command, spec, "--workers", "1", "--no-progress",
                     "--scheduler", "tcp://127.0.0.1:1", "--out", str(tmp_path / "out")])
    lines = capsys.readouterr().err.splitlines()
    assert code == 1, lines  # an option's value: bad input
    if cause == "no answer":  # what it connects to, said before the wait (none without Dask)
        announced = lines.pop(0)
        assert announced.startswith(f"tegrasp {command}: connecting to the Dask scheduler at "
                                    "tcp://127.0.0.1:1"), announced
    assert len(lines) == 1 and words in lines[0], lines
    assert not (tmp_path / "out").exists()


# Rule: --scheduler is connected to once: the check that it answers hands its connection to
# the sweeps, rather than each (the check, each sweep of a transfer's cells) connecting anew.
@pytest.mark.parametrize("command", ["sweep", "transfer"])
def test_a_scheduler_is_connected_to_once(tmp_path, monkeypatch, capsys, command):
    distributed = pytest.importorskip("distributed",
                                      reason="the optional 'dask' extra is not installed")
    from tegrasp_drake.transfer import matrix
    monkeypatch.setattr(matrix, "record_world_events", lambda *args, **kwargs: 0)
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n  a: {scenario: memorizing_world}\n  b: {scenario: "
                    "faithful_world}\ncells: [[a, a], [a, b]]\nsweep: {controllers: [memorized], "
                    "attempts: 1, objects: [box], grid: [[0.0, 0.0]]}\n")
    words = {"sweep": ["--objects", "box", "--controllers", "memorized", "--attempts", "1",
                       "--trial-function", "tests.fake_trials:fake_trial"],
             "transfer": [str(spec), *FAKE_TRIALS]}[command]
    # Its own HTTP port (":0", any free one): 8787 may be another cluster's on a shared host.
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  protocol="tcp://", dashboard_address=":0") as cluster:
        connections = []

        class CountedClient(distributed.Client):
            def __init__(self, *args, **kwargs):
                connections.append(args[0] if args else kwargs.get("address"))
                super().__init__(*args, **kwargs)

        monkeypatch.setattr(distributed, "Client", CountedClient)
        code = cli.main([command, *words, "--no-progress", "--format", "svg",
                         "--scheduler", cluster.scheduler_address,
                         "--out", str(tmp_path / "out")])
    out, error = capsys.readouterr()
    assert code == 0, error
    assert "dask:" + cluster.scheduler_address in out or command == "transfer", out
    assert connections == [cluster.scheduler_address], connections


@pytest.mark.parametrize("hook", ["..x:y", ".x:y", "x:", ":y", "x y:z", "x:y.z"])
def test_a_trial_function_not_module_colon_name_is_refused_in_one_line(tmp_path, capfd, hook):
    spec = tmp_path / "s.yaml"
    spec.write_text("controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                    "grid: [[0.0, 0.0]]\nbase_seed: 640\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--workers", "1", "--no-progress", "--trial-function", hook], capfd)
    assert code in (1, 2), text
    assert "trial function" in text and "Traceback" not in text and "internal error" not in text


def test_a_trial_function_module_that_raises_on_import_is_one_line(tmp_path, capfd,
                                                                    monkeypatch):
    (tmp_path / "bad_trials_module.py").write_text("raise RuntimeError('broken at import')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    from tegrasp_drake.commands.sweep import SweepError, resolve_trial_function
    with pytest.raises(SweepError, match="RuntimeError: broken at import"):
        resolve_trial_function("bad_trials_module:run")


@pytest.fixture
def listener():
    """A local TCP service on a free port that is not a Dask scheduler: `silent` accepts and
    says nothing; `garbage` sends 0xff bytes (a frame length of 2**64 - 1) and hangs up;
    `huge_frame` declares a frame of 2**62 bytes (what random bytes mostly declare: numpy's
    MemoryError when distributed allocates it) and hangs up."""
    import socket
    import threading
    servers, held = [], []

    def start(kind):
        server = socket.socket()
        server.bind(("127.0.0.1", 0))
        server.listen(8)
        servers.append(server)

        def serve():
            while True:
                try:
                    connection, _ = server.accept()
                except OSError:
                    return
                if kind == "silent":
                    held.append(connection)
                    continue
                reply = (2**62).to_bytes(8, "little") * 512 if kind == "huge_frame" else (
                    b"\xff" * 4096)
                with contextlib.suppress(OSError):
                    connection.sendall(reply)
                connection.close()
        threading.Thread(target=serve, daemon=True).start()
        return f"tcp://127.0.0.1:{server.getsockname()[1]}"
    yield start
    for connection in [*servers, *held]:
        connection.close()


@pytest.mark.parametrize("kind", ["silent", "garbage", "huge_frame"])
def test_a_scheduler_address_that_is_not_a_dask_scheduler_is_one_error(listener, monkeypatch,
                                                                       kind):
    """A silent peer held the Client past distributed's timeout (forever); garbage was exit
    70 from inside distributed's frame reader, and a reply declaring a huge frame is said as
    no Dask reply, not as the MemoryError of allocating it. The wall-time bound is shortened
    here only so the test takes seconds."""
    pytest.importorskip("distributed")
    from tegrasp_drake.sweep import runner
    monkeypatch.setattr(runner, "DASK_ANSWER_BOUND_S", 3.0)
    address = listener(kind)
    with pytest.raises(runner.SweepError) as refused:
        runner.connect_scheduler(address)
    text = one_line_of(refused.value)
    if kind != "silent":
        assert text == (f"what answers at {address} is not a Dask scheduler (its reply is "
                        "not Dask's protocol): give the address `dask scheduler` prints")


# Rule: a scheduler that cannot be reached is said in one line as soon as that is known: a
# host name that does not resolve (".invalid" never does, RFC 6761) and a port where nothing
# listens are refused before distributed is asked (it retries both until its 30 s timeout).
@pytest.mark.parametrize("address, words", [
    ("tcp://no-such-host.invalid:8786", "the host name no-such-host.invalid does not resolve"),
    ("no-such-host.invalid:8786", "the host name no-such-host.invalid does not resolve"),
    ("127.0.0.1:{port}", "nothing listens on port {port} (connection refused)"),
    ("tcp://127.0.0.1:{port}", "nothing listens on port {port} (connection refused)"),
])
def test_a_scheduler_that_cannot_be_reached_is_said_before_dask_retries(address, words,
                                                                       monkeypatch):
    distributed = pytest.importorskip("distributed")
    import socket
    from tegrasp_drake.sweep import runner
    with socket.socket() as closed:  # a port free a moment ago: nothing listens there
        closed.bind(("127.0.0.1", 0))
        port = closed.getsockname()[1]
    address, words = address.format(port=port), words.format(port=port)

    def asked(*args, **kwargs):
        raise AssertionError("distributed was asked to connect")
    monkeypatch.setattr(distributed, "Client", asked)
    with pytest.raises(runner.SweepError) as raised:
        runner.connect_scheduler(address)
    message = str(raised.value)  # the resolver's reason, in its words, may follow the host's
    assert message.startswith(f"cannot reach the Dask scheduler at {address}: {words}"), message
    assert message.endswith("; start `dask scheduler` there, or give the address it prints")
    assert "\n" not in message


def test_a_scheduler_address_without_its_protocol_is_tcp(monkeypatch):
    distributed = pytest.importorskip("distributed")
    from tegrasp_drake.sweep import runner
    with distributed.LocalCluster(n_workers=0, processes=False, protocol="tcp://",
                                  dashboard_address=":0") as cluster:
        bare = cluster.scheduler_address.removeprefix("tcp://")
        client = runner.connect_scheduler(bare)
        try:
            assert client.scheduler.address == cluster.scheduler_address
        finally:
            client.close()


def test_an_inproc_scheduler_address_is_refused_by_its_form(tmp_path, capfd):
    spec = tmp_path / "s.yaml"
    spec.write_text("controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                    "grid: [[0.0, 0.0]]\nbase_seed: 640\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--workers", "1", "--scheduler", "inproc://x", *FAKE_TRIALS], capfd)
    assert code == 1 and "--scheduler 'inproc://x' is not a scheduler address" in text, text


# Rule: a --scheduler address that does not parse as tcp://HOST:PORT or HOST:PORT (no host,
# no port, a port that is no number, an unclosed '[', a HOST that is no host name nor IP
# address) is a command line that does not parse: exit 2, pointing to --help, in its own
# words, never urllib's ("Port could not be cast to integer value"); one that parses and names
# what no scheduler is reached at (another protocol, port 0, a port past 65535, a path) stays
# bad input, exit 1.
FORM = "give tcp://HOST:PORT or HOST:PORT, e.g. tcp://127.0.0.1:8786"


@pytest.mark.parametrize("command", ["sweep", "transfer", "sensitivity"])
@pytest.mark.parametrize("address, words", [
    ("tcp://x:y", f"port 'y' is not a number; {FORM}"),
    ("tcp://x:-1", f"port '-1' is not a number; {FORM}"),
    ("tcp://[::1]:8786x", f"port '8786x' is not a number; {FORM}"),
    ("tcp://x", f"it has no port; {FORM}"),
    ("tcp://:8786", f"it has no HOST; {FORM}"),
    ("tcp://[::1", f"its HOST has a '[' without its ']'; {FORM}"),
    ("localhost", f"it has no port; {FORM}"),
    ("exa mple:8786", f"HOST 'exa mple' is not a host name (letters, digits, '-' and '.') "
                      f"nor an IP address; {FORM}"),
    ("tcp://-x-:8786", f"HOST '-x-' is not a host name (letters, digits, '-' and '.') nor an "
                       f"IP address; {FORM}"),
    ("tcp://[x]:8786", f"its [HOST] is not an IPv6 address; {FORM}"),
])
def test_a_scheduler_address_that_does_not_parse_is_a_usage_error(command, address, words,
                                                                  tmp_path, capfd):
    code, text = run_cli([command, "--scheduler", address, "--out", str(tmp_path / "o")],
                         capfd)
    assert code == 2, text
    assert_one_line_error(code, text, f"tegrasp: error: argument --scheduler: "
                          f"{address!r}: {words} (see tegrasp {command} --help)")
    assert "could not be cast" not in text and "Invalid IPv6" not in text, text
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("address, words", [
    ("tcp://x:99999", "names port 99999, past the last TCP port (65535)"),
    ("x:99999", "names port 99999, past the last TCP port (65535)"),
    ("tcp://x:0", "names port 0, which no scheduler listens on"),
    ("http://x:y", "is not a scheduler address PROTOCOL://HOST:PORT (PROTOCOL tcp)"),
    ("tcp://x:1/p", "has a path beside PROTOCOL://HOST:PORT"),
])
def test_a_scheduler_address_that_parses_and_is_refused_stays_bad_input(address, words,
                                                                        tmp_path, capfd):
    code, text = run_cli(["sweep", "--scheduler", address, "--out", str(tmp_path / "o"),
                          *FAKE_TRIALS], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, f"tegrasp: error: --scheduler {address!r} {words}")
    assert "Port out of range" not in text and "--help" not in text, text


def _scheduler_process(log_path):
    """`dask scheduler` on a free port, and its address (from its log)."""
    with open(log_path, "w") as log:  # the scheduler holds its own copy of the file
        process = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
             "--port", "0", "--no-dashboard"], stdout=log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 300.0
    while True:
        address = re.search(r"Scheduler at:\s*(tcp://\S+)", log_path.read_text())
        if address:
            return process, address.group(1)
        assert process.poll() is None and time.monotonic() < deadline, log_path.read_text()
        time.sleep(0.2)


def test_a_scheduler_that_goes_away_mid_sweep_is_one_line_and_its_trials_kept(tmp_path):
    pytest.importorskip("distributed", reason="the optional 'dask' extra is not installed")
    scheduler, address = _scheduler_process(tmp_path / "scheduler.log")
    worker = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nworkers", "1",
         "--nthreads", "1", "--no-dashboard"], env=killed_runs.environment(),
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = tmp_path / "out"
    sweep = subprocess.Popen(
        [sys.executable, "-m", "tegrasp_drake", "sweep", "--scheduler", address, "--out",
         str(out), "--trial-function", "tests.fake_trials:slow_fake_trial", "--no-progress"],
        env=killed_runs.environment(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        text=True)
    try:
        deadline = time.monotonic() + 300.0
        while len(list((out / "trials").glob("*.json"))) < 3:  # trials are being recorded
            assert sweep.poll() is None and time.monotonic() < deadline, sweep.communicate()
            time.sleep(0.1)
        scheduler.kill()
        text, err = sweep.communicate(timeout=600)
    finally:
        for process in (sweep, worker, scheduler):
            with contextlib.suppress(ProcessLookupError):
                process.kill()
            process.wait()
    assert sweep.returncode == 1, err
    announced, *said = err.strip().splitlines()  # what it connects to, then the one error line
    assert announced.startswith(
        f"tegrasp sweep: connecting to the Dask scheduler at {address}"), err
    assert text == "" and "Traceback" not in err and len(said) == 1, err
    finished = re.search(r"lost the Dask scheduler at \S+ after (\d+) of 243 trials", err)
    assert finished, err
    records = load_records(out)
    assert not records.corrupt and len(records.records) == int(finished.group(1)), err


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:8786/../x", "tcp://127.0.0.1:8786?a=1",
                                     "tcp://me@127.0.0.1:8786"])
def test_a_scheduler_address_with_more_than_host_and_port_is_not_an_address(address, tmp_path,
                                                                           capfd):
    code, text = run_cli(["sweep", "--scheduler", address, "--out", str(tmp_path / "o")],
                         capfd)
    assert_one_line_error(code, text, "beside PROTOCOL://HOST:PORT",
                          "give tcp://127.0.0.1:8786")



def test_an_analysis_script_refuses_more_workers_than_cores_as_sweep_does(tmp_path, monkeypatch):
    from tegrasp_drake.commands.script_output import run_script
    from tegrasp_drake.sweep import runner
    from tests.analysis_script import load_analysis_script
    monkeypatch.setattr(runner, "default_workers", lambda: 2)
    script = load_analysis_script("explain_open_loop")
    monkeypatch.setattr(script.concurrent.futures, "ProcessPoolExecutor", None)  # no trial runs
    out = tmp_path / "open_loop.png"
    with pytest.raises(SystemExit) as refused:
        run_script(script.main, "explain_open_loop", [str(out), "--workers", "54"])
    assert_one_line_error(1, refused.value.code, "explain_open_loop: error: --workers 54",
                          "2 core(s)", "--oversubscribe")
    assert not out.exists()


def test_an_analysis_script_takes_at_most_the_cores_by_default_and_more_when_asked():
    from tegrasp_drake.commands.script_output import script_parser
    from tegrasp_drake.sweep import runner
    parser = script_parser("a_script", "A script.")
    parser.add_workers()
    assert parser.parse_args([]).workers == min(2, runner.default_workers())
    assert parser.parse_args(["--workers", "54", "--oversubscribe"]).workers == 54
