"""`tegrasp trial`: what it does when a write fails after the simulation; its timeline."""

import errno
import json
import re
import types

from tegrasp_drake.commands.trial import print_result
from tegrasp_drake.scenario.trial_result import TrialResult
from tests.bad_input.probes import run_cli
from tests.fake_trials import whole_result


class _FinishedTrial:
    """What run_trial returns, reduced to what the command writes (the simulation is not
    what these tests are about)."""
    log = types.SimpleNamespace(save=lambda path: path.write_bytes(b"log") and path)

    def to_dict(self):
        return {"hold": "SUCCESS", "unload": "SUCCESS"}


def test_a_replay_that_cannot_be_written_names_html_keeps_the_run_and_exits_1(
        tmp_path, monkeypatch, capfd):
    def no_space(meshcat, path):
        raise OSError(errno.ENOSPC, "No space left on device")
    monkeypatch.setattr("tegrasp_drake.runs.trial.run_trial",
                        lambda *args, **kwargs: _FinishedTrial())
    monkeypatch.setattr("tegrasp_drake.figures.trial_figures.write_trial_figures",
                        lambda log, stage, fmt: {})
    monkeypatch.setattr("tegrasp_drake.commands.trial.start_viewer", lambda args: None)
    monkeypatch.setattr("tegrasp_drake.commands.trial.write_replay_html", no_space)
    out = tmp_path / "run"
    code, text = run_cli(["trial", "--out", str(out), "--html", str(tmp_path / "r.html"),
                          "--json", "-q"], capfd)
    assert code == 1
    errors = [line for line in text.splitlines() if line.startswith("tegrasp: error:")]
    assert len(errors) == 1 and "Traceback" not in text, text
    assert f"--html {tmp_path / 'r.html'}: cannot write it (No space left on device)" in errors[0]
    assert f"the run is kept in {out}" in errors[0]
    result = json.loads((out / "result.json").read_text())
    assert result["hold"] == "SUCCESS" and "replay_html" not in result
    assert (out / "trial.npz").read_bytes() == b"log"
    assert not (tmp_path / "r.html").exists()


def test_the_timeline_shows_the_code_of_the_rule_beside_each_transition(capsys):
    def entry(t, from_mode, to_mode, trigger, reason, **fields):
        return {"t": t, "from": from_mode, "to": to_mode, "trigger": trigger,
                "reason": reason, **fields}
    result = TrialResult.from_dict(whole_result(**{
        "object": "box", "offset_m": [0.0, 0.025], "controller": "taxel_aware", "seed": 680,
        "transitions": [
            entry(1.0, "Reach", "Re-Reach", "corrective", "a finger struck the object",
                  code="finger_strike"),
            entry(2.0, "Re-Reach", "Reach", "timer", "moved"),  # no code (as open loop)
            entry(3.0, "Reach", "Load", "memorized_event", "Reach-Load event",
                  scores=[0.9, 0.9, 0.9, 0.9], code="reach_event")],
        "final_mode": "Load", "corrective_actions": ["re_reach"], "hold_time_s": 0.0,
        "final_tilt_deg": 0.0, "sim_time_s": 4.0, "wall_time_s": 8.0, "real_time_factor": 0.5}))
    print_result(result)
    timeline = capsys.readouterr().out.splitlines()[1:4]
    assert re.search(r"Reach -> Re-Reach +\[corrective: finger_strike\] a finger struck",
                     timeline[0]), timeline
    assert re.search(r"Re-Reach -> Reach +\[timer\] moved", timeline[1]), timeline
    assert re.search(r"Reach -> Load +\[memorized_event: reach_event\] Reach-Load event",
                     timeline[2]), timeline


def _simulation_fails(*args, **kwargs):
    from tegrasp_drake.runs.trial import SimulationFailedError
    raise SimulationFailedError("the simulation failed at t = 1.0 s (a test's failure)")


def _interrupted(*args, **kwargs):
    raise KeyboardInterrupt


def _with_trial(monkeypatch, run_trial):
    monkeypatch.setattr("tegrasp_drake.runs.trial.run_trial", run_trial)
    monkeypatch.setattr("tegrasp_drake.commands.trial.start_viewer", lambda args: None)


def test_a_trial_that_fails_removes_the_out_folder_and_the_parents_it_made(
        tmp_path, monkeypatch, capfd):
    _with_trial(monkeypatch, _simulation_fails)
    code, text = run_cli(["trial", "--out", str(tmp_path / "a" / "b" / "run"), "-q"], capfd)
    assert code != 0 and "the simulation failed at t = 1.0 s" in text
    assert list(tmp_path.iterdir()) == [], text


def test_an_interrupted_trial_removes_the_numbered_folder_it_claimed(tmp_path, monkeypatch):
    _with_trial(monkeypatch, _interrupted)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "out" / "trial").mkdir(parents=True)
    from tegrasp_drake import cli
    assert cli.main(["trial", "-q"]) != 0
    assert sorted(path.name for path in (tmp_path / "out").iterdir()) == ["trial"]


def test_a_failed_trial_keeps_a_folder_that_was_there_and_what_it_holds(
        tmp_path, monkeypatch, capfd):
    _with_trial(monkeypatch, _simulation_fails)
    out = tmp_path / "run"
    out.mkdir()
    (out / "notes.txt").write_text("the user's")
    code, text = run_cli(["trial", "--out", str(out), "-q"], capfd)
    assert code != 0
    assert [path.name for path in out.iterdir()] == ["notes.txt"]
    empty = tmp_path / "empty"
    empty.mkdir()
    code, text = run_cli(["trial", "--out", str(empty), "-q"], capfd)
    assert code != 0 and empty.is_dir()
