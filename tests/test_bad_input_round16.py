"""Bad inputs the sixteenth review found, one test per rule."""

import pytest

from tegrasp_drake import cli
from tegrasp_drake.sweep.runner import SweepError
from tegrasp_drake.sweep.spec import MAX_TRIALS

_FAKE_TRIALS = ["--trial-function", "tests.fake_trials:fake_trial_with_events"]


_REACHED = "the run was reached"


def _stop_at_the_run(monkeypatch):
    """The runs of sweep, transfer and sensitivity replaced by a refusal saying _REACHED
    (the command got past every check); the calls (their keyword arguments) are listed in
    the list returned."""
    from tegrasp_drake.commands import sweep
    from tegrasp_drake.transfer import matrix
    calls = []

    def reached(*args, **kwargs):
        calls.append(kwargs)
        raise SweepError(_REACHED)

    monkeypatch.setattr(sweep, "run_sweep", reached)
    monkeypatch.setattr(matrix, "run_transfer", reached)
    return calls


def _transfer_spec(tmp_path, worlds=21):
    """A transfer spec of worlds x worlds cells of the paper's sweep: 441 x 243 trials and
    63 recordings (each memorizing world's, of 3 objects)."""
    names = [f"w{k}" for k in range(worlds)]
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n" + "".join(f"  {n}: {{scenario: memorizing_world}}\n"
                                          for n in names)
                    + f"cells: {{memorize_in: [{', '.join(names)}], run_in: "
                      f"[{', '.join(names)}]}}\n")
    return spec


def _sensitivity_spec(tmp_path):
    """A sensitivity spec whose 11 Latin-hypercube points (with the default) of a
    16200-trial sweep are 178200 trials and 33 recordings (each point's, of 3 objects)."""
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.position_loop_hz]\nsweep: {attempts: 200}\n")
    return spec


# (command line after the command's name, the study's simulations: trials and recordings)
_STUDIES = {
    "sweep": (["--attempts", "1235"], 3 * 9 * 1235 * 3),
    "transfer": (["T"], 441 * 243 + 21 * 3),
    "sensitivity": (["S", "--latin-hypercube", "10"], 11 * 200 * 81 + 11 * 3),
}


def _argv(command, tmp_path, *more):
    words, simulations = _STUDIES[command]
    spec = {"T": str(_transfer_spec(tmp_path)), "S": str(_sensitivity_spec(tmp_path))}
    return ([command, *[spec.get(w, w) for w in words], *_FAKE_TRIALS, "--workers", "1",
             "--no-progress", "--out", str(tmp_path / "out"), *more], simulations)


# Rule: a study over the trial bound (sweep, transfer, sensitivity) is refused with its cost
# and the option that runs it; the option, given at least the study's size, runs it; given
# less, it is refused again: a confirmation never covers a bigger study than the user saw.
@pytest.mark.parametrize("command", sorted(_STUDIES))
def test_a_study_over_the_bound_is_refused_with_the_option_that_runs_it(
        tmp_path, monkeypatch, capsys, command):
    calls = _stop_at_the_run(monkeypatch)
    argv, simulations = _argv(command, tmp_path)
    assert simulations > MAX_TRIALS
    assert cli.main(argv) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "core-hours" in error, error
    assert f"add --confirm-trials {simulations} to run it" in error, error
    assert not calls

    assert cli.main(_argv(command, tmp_path, "--confirm-trials",
                          str(simulations - 1))[0]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1, error
    assert f"--confirm-trials {simulations - 1}" in error, error
    assert f"add --confirm-trials {simulations} to run it" in error, error
    assert not calls

    assert cli.main(_argv(command, tmp_path, "--confirm-trials", str(simulations))[0]) == 2
    assert _REACHED in capsys.readouterr().err and len(calls) == 1


# Rule: --confirm-trials is a count of trials, and one under the study's is refused even
# for a study under the bound: it confirms a study other than the one given.
@pytest.mark.parametrize("value, words", [
    ("0", "at least 1"), ("-5", "at least 1"), ("many", "is not an integer"),
    ("242", "add --confirm-trials 243 to run it")])
def test_a_confirmation_that_is_no_count_or_too_few_is_refused(tmp_path, monkeypatch, capsys,
                                                               value, words):
    calls = _stop_at_the_run(monkeypatch)
    try:
        code = cli.main(["sweep", "--confirm-trials", value, *_FAKE_TRIALS, "--workers", "1",
                         "--no-progress", "--out", str(tmp_path / "out")])
    except SystemExit as stopped:  # argparse's refusal of text that is no integer
        code = stopped.code
    # a count that is none: the option's value (1); too few: argparse (2), the study's size (2)
    assert code == (1 if value in ("0", "-5") else 2)
    error = capsys.readouterr().err
    assert "--confirm-trials" in error and value in error and words in error, error
    assert "Traceback" not in error and not calls, error


def _count_scenario_file_parses(monkeypatch):
    """A list that grows by one each time the built-in scenario file's text is parsed."""
    from tegrasp_drake.rig import paths, typed_yaml
    parses, parse = [], typed_yaml.parse_yaml

    def counted(text, source, **kwargs):
        if source == str(paths.scenarios_file()):
            parses.append(source)
        return parse(text, source, **kwargs)
    monkeypatch.setattr(typed_yaml, "parse_yaml", counted)
    return parses


def _worlds(count):
    """A transfer matrix of `count` worlds of the default scenario, each its own point."""
    from tegrasp_drake.sweep.spec import SweepSpec
    from tegrasp_drake.transfer.matrix import TransferSpec, TransferWorld
    names = [f"w{k}" for k in range(count)]
    return TransferSpec(worlds={n: TransferWorld(
        "default", (f"gripper.position_loop_hz={40.0 + k}",))
                                for k, n in enumerate(names)},
                        cells=tuple((n, n) for n in names), sweep=SweepSpec())


# Rule: checking a study's worlds (each world's preset and overrides with every controller)
# parses the scenario file once, not once a world and controller: a 1000-point study's check
# took a minute, most of it parsing the same file.
def test_checking_many_worlds_parses_the_scenario_file_at_most_once(monkeypatch):
    from tegrasp_drake.transfer.matrix import check_worlds
    parses = _count_scenario_file_parses(monkeypatch)
    check_worlds(_worlds(5), "study")
    assert len(parses) <= 1, parses  # none when an earlier check read it in this process


# Rule: a check of many worlds, which takes a while, says so on stderr when it starts and
# how long it took when it ends, rather than running silently.
def test_a_long_check_of_worlds_says_what_it_checks_and_how_long_it_took(capsys):
    from tegrasp_drake.transfer.matrix import check_worlds
    check_worlds(_worlds(3), "study")
    assert capsys.readouterr().err == ""
    check_worlds(_worlds(50), "study")
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 2, lines
    assert lines[0].startswith("checking 50 worlds"), lines
    assert lines[1].startswith("checked 50 worlds in "), lines


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
             "transfer": [str(spec), *_FAKE_TRIALS]}[command]
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


def test_the_python_api_bounds_a_study_as_the_commands_do(tmp_path, monkeypatch):
    """run_sweep and run_transfer, called from a script, refuse a study over the trial bound
    with its cost before listing a trial, and run it when confirmed."""
    from tegrasp_drake.sweep import runner
    from tegrasp_drake.sweep.spec import SweepSpec, trial_count
    from tegrasp_drake.transfer import matrix

    spec = SweepSpec(attempts=1235)
    assert trial_count(spec) > MAX_TRIALS

    def listed(*args, **kwargs):
        raise AssertionError("the trials were listed before the study's size was checked")

    monkeypatch.setattr(runner, "expand_trials", listed)
    with pytest.raises(Exception, match="add --confirm-trials 100035 to run it"):
        runner.run_sweep(spec, print, tmp_path / "out", workers=1)
    with pytest.raises(AssertionError, match="listed before"):  # confirmed: past the check
        runner.run_sweep(spec, print, tmp_path / "out", workers=1, confirmed_trials=100035)

    transfer = matrix.LoadTransferSpec(_transfer_spec(tmp_path), confirmed_trials=10**6)
    with pytest.raises(Exception, match="add --confirm-trials 107226 to run it"):
        matrix.run_transfer(transfer, print, tmp_path / "t")
