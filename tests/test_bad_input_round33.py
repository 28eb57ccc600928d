"""Bad inputs the lead found beside the fifteenth hostile pass, one test per rule."""

import subprocess
import sys

import pytest

from tegrasp_drake import cli
from tests.test_bad_input import run_cli


# Rule: a command's optional positional may follow its options, as a required one may:
# `plot signals -vv LOG` reads LOG (argparse alone gave LOG|RESULTS its default when -vv came
# first, then refused LOG as an unrecognized argument).
@pytest.mark.parametrize("argv", [["plot", "trial", "-vv", "{log}", "--out", "{png}"],
                                  ["plot", "-v", "trial", "{log}", "--out", "{png}"],
                                  ["plot", "trial", "--out", "{png}", "-q", "{log}"]])
def test_an_optional_positional_after_an_option_is_taken(tmp_path, capfd, argv):
    log, png = tmp_path / "missing.npz", tmp_path / "x.png"
    code, error = run_cli([a.format(log=log, png=png) for a in argv], capfd)
    assert code == 1, error
    assert f"trial log '{log}' does not exist" in error
    assert "unrecognized arguments" not in error


def test_two_positionals_where_one_is_taken_are_still_refused(tmp_path, capfd):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["plot", "trial", "-v", str(tmp_path / "a.npz"), str(tmp_path / "b.npz")])
    assert exit_.value.code == 2
    assert "unrecognized arguments" in capfd.readouterr().err


# Rule: a symbolic link under a run file's name (a figure, trial.npz, result.json) is the
# user's: a run writes its files itself, never a link. The trial is refused before it
# simulates, as for a FIFO there, and the link stays (--overwrite removed it as "the earlier
# run's" figure when the new run wrote another format).
@pytest.mark.parametrize("name", ["avoid.svg", "trial.npz"])
def test_a_link_under_a_run_files_name_refuses_the_trial_and_stays(tmp_path, capfd,
                                                                  monkeypatch, name):
    from tegrasp_drake.runs import trial as trial_module
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    folder, precious = tmp_path / "ow", tmp_path / "precious.svg"
    folder.mkdir()
    precious.write_text("<svg/>")
    (folder / name).symlink_to(precious)
    code, text = run_cli(["trial", "--set", "random_seed=633", "--out", str(folder),
                          "--overwrite"], capfd)
    assert code == 1, text
    assert f"{name} is a symbolic link" in text and text.count("\n") == 0, text
    assert (folder / name).is_symlink() and precious.read_text() == "<svg/>"


# Rule: a timeline's length is bounded by its own log's span and its controller's Avoid timing
# (two transitions an Avoid cycle, at least a controller update apart), not by the default
# timing over the longest run: a user's short Avoid timings over a long run fit, a 12 s log
# cannot hold the 461 entries the longest default run could.
def test_the_most_transitions_follow_the_logs_span_and_its_avoid_timing():
    import dataclasses

    from tegrasp_drake.control.controller_config import GraspControllerConfig
    from tegrasp_drake.scenario.trial_log_file import most_transitions
    quick = GraspControllerConfig()
    quick = dataclasses.replace(quick, avoid=dataclasses.replace(
        quick.avoid, hit_refractory_s=0.05, sense_s=0.01, move_s=0.04))
    corrections_only = most_transitions(0.0)  # and one Avoid cycle begun at the end
    assert most_transitions(12.0) - corrections_only == 2 * 12  # 0.93 s cycles
    assert abs(most_transitions(85.0, quick) - corrections_only - 2 * 850) <= 2  # 0.1 s
    assert most_transitions(12.0) < 461 < most_transitions(85.0, quick)
    no_pause = dataclasses.replace(quick, avoid=dataclasses.replace(
        quick.avoid, hit_refractory_s=0.0, sense_s=0.0, move_s=0.0))
    assert abs(most_transitions(1.0, no_pause) - corrections_only - 2 * 100) <= 2  # 5 ms updates


# Rule: every command that writes a run into a folder takes one lock, the folder's own: a
# sweep into the folder a trial is writing is refused at once, and the reverse (the sweep held
# D/.sweep.lock, the trial the folder itself: both ran, and the lock file stayed in the trial's
# run folder).
_HOLD = ("import sys\n"
         "from tegrasp_drake.commands.run_folder import claimed_run_folder\n"
         "with claimed_run_folder(sys.argv[1]):\n"
         "    print('held', flush=True)\n"
         "    sys.stdin.read()\n")
_CLAIM = ("import sys\n"
          "from tegrasp_drake.commands.run_folder import RunFolderError, claimed_run_folder\n"
          "try:\n"
          "    with claimed_run_folder(sys.argv[1]):\n"
          "        print('claimed')\n"
          "except RunFolderError as e:\n"
          "    print(e)\n")


def test_a_trial_and_a_sweep_exclude_each_other_on_one_folder(tmp_path):
    from tegrasp_drake.rig.files import UserPathError
    from tegrasp_drake.sweep.runner import hold_output_folder
    folder = tmp_path / "D"
    folder.mkdir()
    trial = subprocess.Popen([sys.executable, "-c", _HOLD, str(folder)], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, text=True)
    try:
        assert trial.stdout.readline() == "held\n"  # a trial's run holds the folder
        with pytest.raises(UserPathError, match="another run .* is writing there now"):
            with hold_output_folder(folder):
                pass
    finally:
        trial.communicate("", timeout=600)
    with hold_output_folder(folder):  # a sweep holds it: a trial's run is refused
        claim = subprocess.run([sys.executable, "-c", _CLAIM, str(folder)],
                               capture_output=True, text=True, timeout=600)
    assert "another run is writing there now" in claim.stdout, claim.stdout + claim.stderr
    assert list(folder.iterdir()) == []  # no lock file left behind
