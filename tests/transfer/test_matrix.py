"""The transfer matrix: its spec, its worlds as scenarios, and `tegrasp transfer` end to end
(a fake trial for the machinery; two real trials, interrupted and resumed)."""

import dataclasses
import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from tegrasp_drake.events.ra_noise_floor import (FALSE_ALARM_PER_TRIAL, TRIAL_HORIZON_S,
                                                  floor_sigmas)
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.transfer.matrix import (LoadTransferSpec, TransferWorld,
                                           check_kept_events, record_world_events,
                                           world_assignments, world_events_folder,
                                           world_scenario)
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.cheap_contact import cheap_contact_yaml

TESTS = Path(__file__).resolve().parents[1]
REPOSITORY = TESTS.parent
TIMEOUT_S = 900


def write_spec(folder, text):
    path = Path(folder) / "transfer.yaml"
    path.write_text(textwrap.dedent(text))
    return path


TWO_WORLDS = """\
    worlds:
      ideal: {scenario: memorizing_world}
      faithful: {scenario: faithful_world}
    cells: [[ideal, faithful]]
    sweep:
      objects: [box]
      controllers: [memorized]
      grid: [[0.0, 0.0]]
      attempts: 2
      base_seed: 600
    """


def test_the_two_worlds_are_the_presets_as_scenarios():
    ideal = LoadScenario(overrides=world_assignments(TransferWorld("memorizing_world")))
    assert ideal.gripper.model == "prismatic"
    assert (ideal.tactile.transducer, ideal.tactile.sample_rate_hz) == ("force", 1000.0)
    assert ideal.tactile.noise_std_n == 0.0 and ideal.tactile.quantization_n == 0.0
    assert ideal.vibration.transducer == "accelerometer"
    faithful = LoadScenario(overrides=world_assignments(
        TransferWorld("faithful_world", ("grasp.grip_force=50",))))
    assert faithful.gripper.model == "linkage"
    assert (faithful.tactile.transducer, faithful.tactile.sample_rate_hz) == ("capacitive",
                                                                             108.0)
    assert faithful.vibration.transducer == "film"
    assert faithful.grasp.grip_force == 50.0
    assert LoadScenario(name="faithful_world").tactile.transducer == "capacitive"


def test_the_committed_matrix_spec_loads_with_both_ends_and_one_factor_worlds():
    spec = LoadTransferSpec(REPOSITORY / "analysis" / "transfer_matrix.yaml")
    assert {"ideal", "faithful"} <= set(spec.worlds)
    assert ("ideal", "faithful") in spec.cells and ("faithful", "ideal") in spec.cells
    assert ("ideal", "ideal") in spec.cells and ("faithful", "faithful") in spec.cells
    assert len(spec.sweep.objects) * len(spec.sweep.grid) * spec.sweep.attempts == 81


def test_the_remedy_spec_is_cells_of_the_matrix_with_the_envelope_and_floor_in_every_world():
    plain = LoadTransferSpec(REPOSITORY / "analysis" / "transfer_matrix.yaml")
    remedy = LoadTransferSpec(REPOSITORY / "analysis" / "transfer_matrix_remedy.yaml")
    assert remedy.worlds == {name: plain.worlds[name] for name in remedy.worlds}
    assert set(remedy.cells) <= set(plain.cells)
    ends = {(a, b) for a in ("ideal", "faithful") for b in ("ideal", "faithful")}
    assert ends <= set(remedy.cells)
    k = floor_sigmas(FALSE_ALARM_PER_TRIAL, int(TRIAL_HORIZON_S * 1000.0 * 2))
    assert remedy.sweep == dataclasses.replace(plain.sweep, scenario_overrides=(
        "controller.matching.ra_envelope_hz=2.0", f"controller.matching.ra_noise_floor_sigmas={k:.2f}"))


@pytest.mark.parametrize("text, words", [
    ("worlds: {ideal: {scenario: nowhere}}\ncells: [[ideal, ideal]]\n",
     "field 'worlds.ideal.scenario': scenario 'nowhere' is not in"),
    ("worlds: {ideal: {scenario: memorizing_world}}\ncells: [[ideal, other]]\n",
     "unknown world 'other'"),
    ("worlds: {ideal: {scenario: memorizing_world}}\ncells: [[ideal, ideal], [ideal, ideal]]\n",
     "field 'cells' lists the cell ['ideal', 'ideal'] twice; list each cell once"),
    ("worlds: {ideal: {scenario: memorizing_world, overrides: [object.name=box]}}\n"
     "cells: [[ideal, ideal]]\n", "'object.name' is set per trial"),
    ("worlds: {ideal: {scenario: memorizing_world, overrides: \"gripper.model=linkage\"}}\n"
     "cells: [[ideal, ideal]]\n", "field 'worlds.ideal.overrides' must be a list of KEY=VALUE "
     "settings, got str 'gripper.model=linkage' (write it as a list: [gripper.model=linkage])"),
    ("worlds: {ideal: {scenario: memorizing_world, overrides: [tactile.transducer=piezo]}}\n"
     "cells: [[ideal, ideal]]\n", "tactile.transducer"),
    ("worlds: {ideal/x: {scenario: memorizing_world}}\ncells: [[ideal/x, ideal/x]]\n",
     "letters, digits and '_'"),
    ("worlds: {ideal: {scenario: memorizing_world}}\ncells: [[ideal, ideal]]\n"
     "sweep: {attempts: 0}\n", "field 'attempts'"),
    ("worlds: {ideal: {scenario: memorizing_world}}\ncells: [[ideal, ideal]]\n"
     "events_seed: -1\n", "field 'events_seed' must lie in [0, 4294967295]"),
    ("worlds: {ideal: {scenario: memorizing_world}}\ncells: [[ideal, ideal]]\n"
     "events_seed: 4294967296\n", "field 'events_seed' must lie in [0, 4294967295]"),
    ("worlds: {ideal: {scenario: memorizing_world}}\ncells: [[ideal, ideal]]\n"
     "events_seed: 650.5\n", "field 'events_seed' must be a whole number"),
])
def test_a_bad_spec_is_refused_naming_the_field(tmp_path, text, words):
    with pytest.raises(ConfigError) as error:
        LoadTransferSpec(write_spec(tmp_path, text))
    assert words in str(error.value)
    assert "\n" not in str(error.value)


def environment():
    entries = [str(REPOSITORY), str(TESTS), os.environ.get("PYTHONPATH", "")]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(e for e in entries if e)}


def transfer_arguments(spec, out, *extra) -> list[str]:
    """`tegrasp transfer SPEC --out OUT` with one worker and no bar, then `extra`."""
    return ["transfer", str(spec), "--out", str(out), "--workers", "1", "--no-progress", *extra]


def transfer_command(spec, out, *extra) -> list[str]:
    """The transfer_arguments as a child process's command line."""
    return [sys.executable, "-m", "tegrasp_drake.cli", *transfer_arguments(spec, out, *extra)]


def test_each_cell_is_a_sweep_with_its_memorizing_worlds_events_and_resumes(tmp_path):
    spec = write_spec(tmp_path, TWO_WORLDS.replace("cells: [[ideal, faithful]]",
                                                   "cells: {memorize_in: [ideal, faithful], "
                                                   "run_in: [faithful]}"))
    out = tmp_path / "out"
    for world in ("ideal", "faithful"):  # events there already: nothing is recorded
        shutil.copytree(paths.package_events_dir(), out / "events" / world,
                        ignore=shutil.ignore_patterns("ensemble", "corrective", "prismatic"))
    command = transfer_command(spec, out, "--trial-function",
                               "tests.fake_trials:fake_trial_with_events")
    first = subprocess.run(command, env=environment(), capture_output=True, text=True,
                           timeout=TIMEOUT_S)
    assert first.returncode == 0, first.stderr
    for world in ("ideal", "faithful"):
        records = sorted((out / "cells" / f"{world}-in-faithful" / "trials").glob("*.json"))
        assert len(records) == 2
        for record in records:
            result = json.loads(record.read_text())["result"]
            assert result["events_dir"] == str(out / "events" / world)
    assert "recording" not in first.stdout
    table = (out / "transfer.md").read_text()
    assert "| ideal | faithful | memorized | 2 | 100 % (2/2) (30 ms) |" in table
    assert "| faithful | faithful | memorized | 2 | 100 % (2/2) (30 ms) |" in table
    assert (out / "transfer_matrix.png").stat().st_size > 0

    again = subprocess.run(command, env=environment(), capture_output=True, text=True,
                           timeout=TIMEOUT_S)
    assert again.returncode == 0, again.stderr
    assert again.stdout.count("2 already finished, 0 run now") == 2


def test_a_folder_of_another_worlds_events_is_refused(tmp_path):
    spec = write_spec(tmp_path, TWO_WORLDS)
    out = tmp_path / "out"
    (out / "events" / "ideal").mkdir(parents=True)
    (out / "events" / "ideal" / "world.json").write_text(json.dumps(["gripper.model=1"]))
    done = subprocess.run(transfer_command(spec, out), env=environment(),
                          capture_output=True, text=True, timeout=TIMEOUT_S)
    assert done.returncode == 2
    assert "holds the events of world 'ideal' recorded with other settings" in done.stderr


def test_the_events_are_recorded_at_the_specs_events_seed(tmp_path):
    """A spec's events_seed is the seed of the ideal grasps that record its worlds' events;
    left out, the default scenario's, as before a spec could set it."""
    chosen = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS + "events_seed: 650\n"))
    assert chosen.events_seed == 650
    assert world_scenario(chosen, "ideal", "box").random_seed == 650
    default = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS))
    assert world_scenario(default, "ideal", "box").random_seed == LoadScenario().random_seed


def test_events_recorded_at_another_events_seed_are_refused(tmp_path):
    """A world's events recorded at one events_seed are not resumed at another, either way."""
    seeded = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS + "events_seed: 650\n"))
    default = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS))
    from tegrasp_drake.sweep.runner import SweepError
    for first, then in ((seeded, default), (default, seeded)):
        folder = tmp_path / f"events_{first.events_seed}" / "ideal"
        shutil.copytree(paths.package_events_dir(), folder,  # there already: none recorded
                        ignore=shutil.ignore_patterns("ensemble", "corrective", "prismatic"))
        assert record_world_events(first, "ideal", folder) == 0
        assert record_world_events(first, "ideal", folder) == 0  # the same seed: resumed
        with pytest.raises(SweepError, match="recorded with other settings"):
            record_world_events(then, "ideal", folder)


def _unreadable_index(folder, kind):
    """`folder`/index.json made a `kind` ("fifo", "folder", "loop") no reader can read."""
    folder.mkdir(parents=True)
    index = folder / "index.json"
    if kind == "fifo":
        os.mkfifo(index)  # no writer: an open() for reading would block for ever
    elif kind == "folder":
        index.mkdir()
    else:
        index.symlink_to(index)


@pytest.mark.parametrize("kind", ["fifo", "folder", "loop"])
def test_a_world_events_index_that_cannot_be_read_is_refused_not_recorded_over(
        tmp_path, monkeypatch, kind):
    """Something in the place of a world's events index is not taken for no index (which
    would record the events again beside it): it is refused by name."""
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.recording import paper_events

    def refuse_to_record(*arguments):
        raise AssertionError("recorded over an index it could not read")
    monkeypatch.setattr(paper_events, "record_events", refuse_to_record)
    spec = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS))
    _unreadable_index(tmp_path / "ideal", kind)
    with pytest.raises(MemorizedEventError, match="index.json"):
        record_world_events(spec, "ideal", tmp_path / "ideal")


@pytest.mark.parametrize("kind", ["fifo", "folder", "loop"])
def test_a_kept_world_index_that_cannot_be_read_is_refused_before_anything_runs(tmp_path,
                                                                               kind):
    from tegrasp_drake.events import MemorizedEventError
    spec = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS))
    out = tmp_path / "out"
    _unreadable_index(world_events_folder(out, "ideal"), kind)
    with pytest.raises(MemorizedEventError, match="index.json"):
        check_kept_events(spec, out)


def test_the_committed_transfer_events_resume_at_the_default_events_seed(tmp_path):
    """analysis/results_transfer's events were recorded before a spec could set the seed:
    its spec, which sets none, still resumes them."""
    spec = LoadTransferSpec(REPOSITORY / "analysis" / "transfer_ends.yaml")
    for world in ("ideal", "faithful"):
        folder = tmp_path / world
        shutil.copytree(REPOSITORY / "analysis" / "results_transfer" / "events" / world, folder)
        assert record_world_events(spec, world, folder) == 0


def wait_for(condition, process, what):
    deadline = time.monotonic() + TIMEOUT_S
    while not condition():
        assert process.poll() is None, f"the command ended before {what}"
        assert time.monotonic() < deadline, f"no {what} in time"
        time.sleep(0.2)


@pytest.mark.slow
def test_two_real_trials_run_end_to_end_and_resume_after_a_kill(tmp_path):
    """Memorize in the idealised world, run in the faithful one: the events are recorded,
    the first trial finishes, the command is killed, and the rerun runs only the second."""
    # The cheap contact in both worlds: the claim is the command's recording, killing and
    # resuming, the same in whichever contact.
    spec = write_spec(tmp_path, TWO_WORLDS.replace(
        "_world}", f"_world, overrides: {cheap_contact_yaml()}}}"))
    out = tmp_path / "out"
    trials = out / "cells" / "ideal-in-faithful" / "trials"
    process = subprocess.Popen(transfer_command(spec, out), env=environment(),
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               start_new_session=True)
    try:
        wait_for(lambda: trials.is_dir() and any(trials.glob("*.json")), process,
                 "first trial record")
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=60)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait(timeout=60)
    (finished,) = sorted(trials.glob("*.json"))
    before = finished.read_bytes()
    assert (out / "events" / "ideal" / "index.json").is_file()

    resumed = subprocess.run(transfer_command(spec, out), env=environment(),
                             capture_output=True, text=True, timeout=TIMEOUT_S)
    assert resumed.returncode == 0, resumed.stderr
    assert "1 already finished, 1 run now" in resumed.stdout
    assert "recording" not in resumed.stdout
    assert finished.read_bytes() == before
    assert len(list(trials.glob("*.json"))) == 2
    for record in trials.glob("*.json"):
        result = json.loads(record.read_text())["result"]
        assert isinstance(result["hold_success"], bool) and result["transitions"]
    assert "| ideal | faithful | memorized | 2 |" in (out / "transfer.md").read_text()


def test_missing_events_of_a_cell_are_named_before_any_trial_runs(tmp_path, monkeypatch):
    """A controller reading events from a folder a world's recording does not make (the
    paper's events and the taxel_aware ensemble are made; here the ensemble's folder is
    renamed) is refused in one line before anything is recorded or run."""
    from tegrasp_drake.control.controller_config import TaxelAwareControllerConfig
    from tegrasp_drake.sweep.trial_function import run_trial_from_spec
    from tegrasp_drake.transfer.matrix import run_transfer
    monkeypatch.setattr(TaxelAwareControllerConfig, "events_folder", "unrecorded")
    spec = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS.replace(
        "controllers: [memorized]", "controllers: [taxel_aware]")))
    out = tmp_path / "out"
    with pytest.raises(ConfigError) as refused:
        run_transfer(spec, run_trial_from_spec, out, workers=1, progress=False)
    message = str(refused.value)
    assert message.startswith("trial taxel_aware/box/") and "unrecorded" in message
    assert message.endswith("so record these there first or drop the controller")
    assert "\n" not in message
    assert not out.exists()


def test_a_world_override_out_of_range_names_its_entry_in_the_spec(tmp_path):
    """Named where the user wrote it (worlds.<name>.overrides[i]), brackets balanced, no
    count of the preset's settings the user did not give."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n  ideal: {scenario: memorizing_world}\n"
                    "  big: {scenario: faithful_world, overrides: [grasp.hold_s=2.0, "
                    "grasp.grip_force=5000.0]}\ncells: [[ideal, big]]\n"
                    "sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], "
                    "attempts: 1}\n")
    with pytest.raises(ConfigError) as refused:
        LoadTransferSpec(spec)
    text = str(refused.value)
    assert text.startswith(f"{spec}: field 'worlds.big.overrides[1]' 'grasp.grip_force=5000.0'"
                           ": field 'grasp.grip_force' must lie in [20, 235] N"), text
    assert "got 5000.0; correct the entry, or drop it" in text, text
    assert text.count("(") == text.count(")") and text.count("[") == text.count("]"), text
    assert "scenario_overrides" not in text and "other --set" not in text, text


def test_a_world_whose_recording_would_not_read_back_is_refused_and_saves_nothing(
        tmp_path, monkeypatch):
    """A recording the events reader would refuse (here Load-Lift before Reach-Load) is a
    SweepError naming the world, not an internal error, and leaves no event file."""
    from tegrasp_drake.events import load_memorized_events
    from tegrasp_drake.recording import paper_events
    from tegrasp_drake.sweep.runner import SweepError
    recorded = load_memorized_events(paths.package_events_dir(), "box")
    out_of_order = dict(recorded, load_lift=dataclasses.replace(
        recorded["load_lift"], transition_time_s=recorded["reach_load"].transition_time_s / 2))
    monkeypatch.setattr(paper_events, "record_events", lambda *args: out_of_order)
    spec = LoadTransferSpec(write_spec(tmp_path, TWO_WORLDS))
    with pytest.raises(SweepError, match="^world ideal: .*load_lift.*nothing was saved"):
        record_world_events(spec, "ideal", tmp_path / "ideal")
    from tegrasp_drake.transfer.matrix import WORLD_FILE
    kept = [path.name for path in (tmp_path / "ideal").rglob("*") if path.is_file()]
    assert kept == [WORLD_FILE]  # the world's settings, no event
