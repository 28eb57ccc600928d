"""Bad inputs and environments the ninth review found, one test per rule."""

import os
import pathlib
import signal
import subprocess
import sys
import time

import pytest

from tests import killed_runs


def _processes_naming(path: pathlib.Path) -> list[int]:
    """The ids of the processes whose command line names `path` (Linux's /proc)."""
    found = []
    for entry in pathlib.Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and str(path).encode() in (entry / "cmdline").read_bytes():
                found.append(int(entry.name))
        except OSError:
            continue
    return found


def _wait_until(condition, what: str, timeout_s: float = 120.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not condition():
        assert time.monotonic() < deadline, what
        time.sleep(0.05)


# Rule: a run killed past its handlers (SIGKILL) leaves nothing running and nothing for ever:
# its staging log is removed by the next run logging to the same --log, a live run's is left
# alone.
@pytest.mark.slow
@pytest.mark.skipif(not pathlib.Path("/proc/self/cmdline").exists(), reason="no /proc")
def test_a_killed_hardware_runs_staging_log_is_removed_by_the_next_run(tmp_path,
                                                                       ideal_grasp_log):
    from tegrasp_drake.emulators.emulator_process import EmulatedDevices
    from tegrasp_drake.hardware.config import hardware_config_to_yaml
    trial = ideal_grasp_log("box").save(tmp_path / "box.npz")
    logs = tmp_path / "logs"
    url = f"udpm://239.255.76.67:{7500 + (os.getpid() * 7) % 100}?ttl=0"
    command = [sys.executable, "-m", "tegrasp_drake", "hardware", "--config",
               str(tmp_path / "hw.yaml"), "--scenario-name", "box", "--controller",
               "heuristic", "--config-set", "scheduling=normal"]
    with EmulatedDevices(lcm_url=url, trial=trial, scheduling="normal") as devices:
        (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(devices.config))
        run = subprocess.Popen([*command, "--log", str(logs / "run.lcmlog")],
                               env=killed_runs.environment(), stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        staging = logs / f".run.lcmlog.{run.pid}.staging"
        try:
            _wait_until(lambda: staging.exists() and staging.stat().st_size > 0,
                        "the run never logged")
        finally:
            run.kill()  # SIGKILL, the run alone (as the OOM killer does)
            run.wait()
    assert run.returncode == -signal.SIGKILL and staging.exists()
    _wait_until(lambda: not _processes_naming(staging), "the run's lcm-logger outlived it")
    live = logs / f".run.lcmlog.{os.getpid()}.staging"  # a run still going
    live.write_bytes(b"being written")
    done = subprocess.run([*command, "--log", str(logs / "run.lcmlog"),
                           "--config-set", "tactile.port=/dev/no_such_port",
                           "--config-set", "ready_timeout=1"],
                          env=killed_runs.environment(), capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 1, done.stderr  # the devices did not come up: quickly done
    assert sorted(path.name for path in logs.iterdir()) == [live.name]


# Rule: a public function's number takes the range its command-line or scenario twin takes,
# from one declaration.
def _declared(function, argument: str):
    """The Range annotated on `function`'s `argument`."""
    import typing
    from tegrasp_drake.rig.ranges import Range
    hint = typing.get_type_hints(function.__wrapped__, include_extras=True)[argument]
    (declared,) = [m for m in hint.__metadata__ if isinstance(m, Range)]
    return declared


def test_seeds_workers_and_simulated_durations_are_declared_once():
    import tegrasp_drake
    from tegrasp_drake.rig.ranges import SEED_RANGE, SIMULATED_DURATION, field_range
    from tegrasp_drake.sweep.runner import WORKER_COUNT
    assert _declared(tegrasp_drake.MakeGraspStation, "random_seed") == SEED_RANGE
    assert field_range(tegrasp_drake.Scenario, "random_seed") == SEED_RANGE
    assert field_range(tegrasp_drake.SweepSpec, "base_seed") == SEED_RANGE
    assert _declared(tegrasp_drake.run_sweep, "workers") == WORKER_COUNT
    assert _declared(tegrasp_drake.run_trial, "max_time") == SIMULATED_DURATION
    assert _declared(tegrasp_drake.run_ideal_grasp, "duration") == SIMULATED_DURATION


@pytest.mark.parametrize("controller", ["memorized", "taxel_aware"])
def test_a_trial_longer_than_the_scenarios_time_limit_is_refused_before_it_is_built(
        controller, monkeypatch):
    import tegrasp_drake
    from tegrasp_drake.runs import ideal_grasp, trial
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    scenario = tegrasp_drake.LoadScenario(name="box", controller=controller)
    limit = MakeGraspDiagram(scenario, log=False).time_limit  # where `tegrasp trial` stops

    def not_built(*args, **kwargs):
        raise AssertionError("built before the argument was checked")
    monkeypatch.setattr(trial, "MakeGraspDiagram", not_built)
    monkeypatch.setattr(ideal_grasp, "MakeGraspDiagram", not_built)
    words = f"must lie in (0, {limit:g}] s (the scenario's time limit"
    with pytest.raises(ValueError, match="run_trial: argument 'max_time'") as refused:
        tegrasp_drake.run_trial(scenario, max_time=1.0e7)
    assert words in str(refused.value)
    with pytest.raises(ValueError, match="argument 'max_time' must be above 0 s"):
        tegrasp_drake.run_trial(scenario, max_time=0.0)
    with pytest.raises(ValueError, match="run_ideal_grasp: argument 'duration' must lie in"):
        tegrasp_drake.run_ideal_grasp(scenario, duration=1.0e7)
    with pytest.raises(AssertionError, match="built before"):  # the limit itself is accepted
        tegrasp_drake.run_trial(scenario, max_time=limit)


# Rule: a log record stderr refuses (-v on a full disk) is dropped, never Python logging's
# traceback ("--- Logging error ---"); the command ends as a full stdout ends it: one line,
# EXIT_ERROR. (The package logs only to stderr: there is no log-file option.)
class _StderrRefusingLogRecords:
    """A stderr whose disk is full for the log records only (it fills, then frees)."""

    def __init__(self):
        self.lines = []

    def write(self, text):
        if "INFO" in text:
            raise OSError(28, "No space left on device")
        self.lines.append(text)
        return len(text)

    def flush(self):
        pass


def _verbose_command(func):
    """A command line whose one command `say` (with -v/-q) runs `func`."""
    import argparse
    from tegrasp_drake.commands.verbosity import add_verbosity_arguments
    parser = argparse.ArgumentParser(prog="tegrasp")
    say = parser.add_subparsers(dest="command", required=True).add_parser("say")
    add_verbosity_arguments(say)
    say.set_defaults(func=func)
    return parser


def _logs_and_prints(args):
    import logging
    for step in range(3):
        logging.getLogger("tegrasp_drake.say").info("step %d", step)
    print("said")
    return 0


FULL_STDERR_LINE = "tegrasp: error: cannot write to standard error: No space left on device"


def test_a_log_record_stderr_refuses_ends_the_command_in_one_line(monkeypatch, capsys):
    import logging
    from tegrasp_drake import cli
    monkeypatch.setattr(logging.getLogger(), "handlers", [])  # the command line's own
    monkeypatch.setattr(cli, "build_parser", lambda: _verbose_command(_logs_and_prints))
    stderr = _StderrRefusingLogRecords()
    monkeypatch.setattr(sys, "stderr", stderr)
    assert cli.main(["say", "-v"]) == cli.EXIT_ERROR
    assert "".join(stderr.lines).splitlines() == [FULL_STDERR_LINE]
    assert capsys.readouterr().out == "said\n"


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full")
def test_verbose_logging_to_a_full_stderr_ends_with_the_error_code(tmp_path):
    script = ("import sys\nfrom tegrasp_drake import cli\n"
              "from tests.test_bad_input_round9 import _logs_and_prints, _verbose_command\n"
              "cli.build_parser = lambda: _verbose_command(_logs_and_prints)\n"
              "sys.exit(cli.main(['say', '-v']))\n")
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-c", script], stdout=subprocess.PIPE,
                              stderr=full, text=True, env=killed_runs.environment(),
                              timeout=300)
    assert (done.returncode, done.stdout) == (1, "said\n")
