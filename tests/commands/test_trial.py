"""`tegrasp trial`: what it does when a write fails after the simulation."""

import errno
import json
import types

from tests.test_bad_input import run_cli


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
