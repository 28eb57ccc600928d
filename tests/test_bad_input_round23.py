"""Bad inputs the fourteenth review found, one test per rule."""

import tracemalloc

import pytest

from tegrasp_drake.commands import emulate


# Rule: a file is read with a bound before its end: --write-config looks at the first line
# of the file it would replace, and reads no more of it (a sparse 200 MB file here).
def test_write_config_reads_only_the_first_line_of_the_file_it_would_replace(tmp_path):
    big = tmp_path / "big.yaml"
    with open(big, "wb") as f:
        f.truncate(200_000_000)
    tracemalloc.start()
    try:
        with pytest.raises(SystemExit, match="was not written by `tegrasp emulate`"):
            emulate._check_config_target(big)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 10_000_000, f"{peak} bytes allocated to check a 200 MB file's first line"


# Rule: an events folder missing a file a trial needs is bad input (exit 1, one line naming
# the file), as a missing --events folder is; exit 2 is kept for a refused sweep spec.
def test_a_sweep_events_folder_missing_a_file_exits_1(tmp_path, capfd):
    import shutil
    from tegrasp_drake.rig import paths
    from tests.test_bad_input import run_cli
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events)
    (events / "box" / "load_lift.json").unlink()
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "memorized",
                          "--base-seed", "640", "--attempts", "1", "--workers", "1",
                          "--out", str(tmp_path / "sw"), "--events", str(events)], capfd)
    assert code == 1, text
    assert "load_lift.json" in text and len(text.strip().splitlines()) == 1, text
    assert "Traceback" not in text and not (tmp_path / "sw").exists(), text


# Rule: a sweep simulates its trials, and a transfer world runs a sweep: an override that
# makes the station the real devices' is refused when the spec is loaded, naming the world.
def test_a_transfer_world_on_the_hardware_station_is_refused(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n  w: {scenario: faithful_world, overrides: "
                    "['station=!HardwareStationConfig {}']}\n"
                    "cells:\n  memorize_in: [w]\n  run_in: [w]\n"
                    "sweep:\n  objects: [box]\n  controllers: [heuristic]\n  attempts: 1\n")
    with pytest.raises(ConfigError, match=r"worlds\.w.*HardwareStationConfig.*simulates"):
        LoadTransferSpec(spec)


# Rule: an event file's numbers are in their ranges when read: the transition's time in its
# trial is not before the trial started.
def test_an_event_whose_transition_time_is_negative_is_refused(tmp_path):
    import json
    import shutil
    from tegrasp_drake.events import MemorizedEventError, load_memorized_events
    from tegrasp_drake.rig import paths
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events)
    path = events / "box" / "reach_load.json"
    data = json.loads(path.read_text())
    data["transition_time_s"] = -50.0
    path.write_text(json.dumps(data))
    with pytest.raises(MemorizedEventError, match="transition_time_s"):
        load_memorized_events(events, "box")


# Rule: what is in the place of a run's own file is a regular file, or the run is refused
# before it simulates (a FIFO, a device link, a folder there is no earlier run's file).
@pytest.mark.parametrize("make", [
    lambda path: __import__("os").mkfifo(path),
    lambda path: path.symlink_to("/dev/zero"),
    lambda path: path.mkdir(),
], ids=["fifo", "device-link", "folder"])
def test_an_overwrite_over_a_run_file_that_is_no_regular_file_is_refused(tmp_path, capfd,
                                                                         monkeypatch, make):
    from tegrasp_drake.runs import trial as trial_module
    from tests.test_bad_input import run_cli
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    out = tmp_path / "o"
    out.mkdir()
    make(out / "result.json")
    code, text = run_cli(["trial", "--set", "random_seed=600", "--out", str(out),
                          "--overwrite"], capfd)
    assert code == 1 and "result.json" in text and "remove it yourself" in text, text
    assert len(text.strip().splitlines()) == 1, text


# Rule: a transition's numbers are in their ranges when built: a Lift-Load's grip force is
# one the 2F-85 can give.
def test_a_transition_with_a_grip_force_beyond_the_gripper_is_refused():
    import tegrasp_drake as T
    with pytest.raises(ValueError, match="grip_force_n"):
        T.Transition(t=1.0, from_mode=T.Mode.LIFT, to_mode=T.Mode.LOAD,
                     trigger=list(T.Trigger)[0], reason="x", grip_force_n=1e9)


# Rule: a run removes only the staging folders a run left (named as mkdtemp names them,
# holding nothing but a run's own files), never a folder of the user's with that prefix.
def test_a_run_keeps_a_users_folder_named_like_a_staging_folder(tmp_path):
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    mine = {".staging-mydata": "thesis.txt", ".staging-x": "notes.txt",
            ".staging-abcd1234": "notes.txt"}
    for name, file in mine.items():
        (folder / name).mkdir()
        (folder / name / file).write_text("the user's")
    left = folder / ".staging-k2j4h5g6"
    left.mkdir()
    (left / "trial.npz").write_bytes(b"a killed run's")
    (left / "states.png").write_bytes(b"a killed run's")
    with run_folder.staged_run(folder):
        pass
    for name, file in mine.items():
        assert (folder / name / file).read_text() == "the user's"
    assert not left.exists()


# Rule: an --overwrite leaves the replay an earlier --html wrote into the folder (a file the
# user named, and may have replaced with their own since).
def test_an_overwrite_keeps_the_earlier_replay_html(tmp_path):
    import json
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    (folder / "trial.npz").write_bytes(b"earlier")
    (folder / "notes.html").write_text("<html>my own notes</html>")
    (folder / "result.json").write_text(json.dumps(
        {run_folder.REPLAY_KEY: str(folder / "notes.html")}))
    with run_folder.staged_run(folder) as stage:
        (stage / "trial.npz").write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    assert (folder / "notes.html").read_text() == "<html>my own notes</html>"


# Rule: a duplicate key is refused naming both lines, a merge key '<<' too (the first
# merge's values were dropped without a word); one '<<' with a list of mappings merges both.
def test_two_merge_keys_in_one_mapping_are_refused(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    twice = tmp_path / "twice.yaml"
    twice.write_text("default:\n  object: {name: box}\nother:\n  <<: {random_seed: 681}\n"
                     "  <<: {random_seed: 682}\n")
    with pytest.raises(ConfigError, match="key '<<' appears twice.*list of them"):
        LoadScenario(str(twice), "other")
    listed = tmp_path / "listed.yaml"
    listed.write_text("default:\n  object: {name: box}\nother:\n"
                      "  <<: [{random_seed: 681}, {object: {name: thin_cylinder}}]\n")
    scenario = LoadScenario(str(listed), "other")
    assert scenario.random_seed == 681 and scenario.object.name == "thin_cylinder"
