"""Bad inputs the thirteenth hostile pass found (round 21), one test per rule."""

import contextlib
import fcntl
import os
import subprocess
import sys

import numpy as np
import pytest
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem
from pydrake.systems.primitives import ConstantVectorSource

from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_STATUS_CHANNEL, NEGATIVE_UTIME, make_jaco_status)
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver
from tests.test_bad_input import assert_one_line_error, folder_contents, run_cli
from tests.test_bad_input_round14 import _FAKE_TRIALS, _transfer_out

Q = [0.1, 2.8, 0.9, -0.4, 0.5, -0.6]  # [rad] inside the JACO2's joint ranges
ZERO = [0.0] * 6


# Rule: an arm status whose utime is impossible (negative: the arm's clock starts at 0) is
# counted under its reason and skipped; the receiver keeps the last good status. (The order
# of utime is not checked: jaco_lcm.jaco_status_boundary says why.)
def jaco_driver_on_memq(q):
    """(lcm, driver, simulator, the status receiver's context): the Jaco LCM driver on an
    in-process bus, its tracker held at joint angles `q` [rad], initialized."""
    lcm = DrakeLcm("memq://")
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    driver = AddJacoLcmDriver(builder, lcm=lcm)
    source = builder.AddSystem(ConstantVectorSource(np.concatenate([q, ZERO])))
    builder.Connect(source.get_output_port(), driver.tracker.GetInputPort("desired_state"))
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    return (lcm, driver, simulator,
            driver.status_receiver.GetMyContextFromRoot(simulator.get_context()))


def test_an_arm_status_with_a_negative_utime_is_skipped():
    lcm, driver, simulator, context = jaco_driver_on_memq(Q)
    real = [q + 0.2 for q in Q]
    forged = [2.0] * 6

    def publish(utime, position):
        lcm.Publish(JACO_STATUS_CHANNEL,
                    make_jaco_status(utime, position, ZERO, ZERO).encode())
        simulator.AdvanceTo(simulator.get_context().get_time() + 0.01)
        return (driver.status_receiver.GetOutputPort("time_measured").Eval(context)[0],
                list(driver.status_receiver.GetOutputPort("position_measured").Eval(context)))

    assert publish(20_000, real) == (pytest.approx(0.02), pytest.approx(real))
    for utime in (-2**63, -1):
        assert publish(utime, forged) == (pytest.approx(0.02), pytest.approx(real))
    assert publish(30_000, real) == (pytest.approx(0.03), pytest.approx(real))
    counters = driver.status_boundary.counters()
    assert counters.accepted == 2
    assert counters.rejected == {NEGATIVE_UTIME: 2}
    for rejection in driver.status_boundary.new_rejections():
        assert "\n" not in driver.status_boundary.describe(rejection)


@contextlib.contextmanager
def _held(folder):
    """The output folder held as another run's process holds it (a flock on the folder)."""
    folder.mkdir(parents=True, exist_ok=True)
    lock = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        yield
    finally:
        os.close(lock)


# Rule: another run writing into the --out folder is an error outside the run (exit 1, one
# "tegrasp: error:" line naming the folder), not a refused spec (exit 2).
def test_a_sweep_into_a_folder_another_run_holds_is_an_error_outside_the_run(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n")
    out = tmp_path / "out"
    with _held(out):
        code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(out), "--no-progress",
                              "--trial-function", "tests.fake_trials:fake_trial"], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error:", str(out), "another")
    assert not (out / "trials").exists()


def _no_recording(monkeypatch):
    """An object's recordings (paper events, ensemble) replaced by a failure: the tests below
    must stop before any simulation."""
    from tegrasp_drake.recording import ensemble_events, paper_events

    def recorded(*args, **kwargs):
        raise AssertionError("an object's events were recorded")
    monkeypatch.setattr(paper_events, "record_events", recorded)
    monkeypatch.setattr(ensemble_events, "record_object_ensemble", recorded)


# Rule: a transfer or a sensitivity study holds its whole --out (the sweep runner's lock)
# before it records or writes anything, so a second run into the folder is refused at once
# (exit 1), not after recording every world's events again beside the first.
@pytest.mark.parametrize("command", ["transfer", "sensitivity"])
def test_a_second_study_into_a_held_out_is_refused_before_anything(tmp_path, capfd,
                                                                   monkeypatch, command):
    if command == "transfer":
        spec, _ = _transfer_out(tmp_path)
    else:
        spec = tmp_path / "s.yaml"
        spec.write_text("parameters: [gripper.position_loop_hz]\nsweep: {controllers: "
                        "[memorized], attempts: 1, objects: [box], grid: [[0.0, 0.0]]}\n")
    _no_recording(monkeypatch)
    out = tmp_path / "out"
    with _held(out):
        before = folder_contents(out)
        code, text = run_cli([command, str(spec), "--out", str(out), "--workers", "1",
                              "--no-progress", *_FAKE_TRIALS], capfd)
        assert folder_contents(out) == before
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error:", str(out), "another")
    assert not (out / "cells").exists()


# Rule: a transfer's events folder kept from an earlier run (its objects are not recorded
# again) is checked complete, every transition file the cells' controllers read for every
# object it lists, before anything is recorded or run; one line naming the file and the
# remedy, exit 1 (a damaged file, not a refused spec).
def test_a_kept_transfer_events_folder_missing_a_transition_is_refused_at_once(tmp_path,
                                                                            capfd,
                                                                            monkeypatch):
    spec, events = _transfer_out(tmp_path)
    (events / "box" / "load_lift.json").unlink()
    _no_recording(monkeypatch)
    code, text = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                          "--workers", "1", "--no-progress"], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error:", str(events / "box" / "load_lift.json"),
                          f"remove {events}")
    assert not (tmp_path / "out" / "cells").exists()


# Rule: an LCM URL that cannot be used is named where it came from: the LCM_DEFAULT_URL
# environment variable when it gave the default (no field the user wrote), else the field.
@pytest.mark.parametrize("command", [
    ["hardware", "--config", "hw.yaml", "--scenario-name", "box", "--duration", "1"],
    ["emulate", "jaco"],
], ids=["hardware", "emulate"])
def test_a_bad_lcm_default_url_variable_is_named(tmp_path, command):
    (tmp_path / "hw.yaml").write_text("gripper: {port: /dev/ttyUSB0}\n")
    bad = "udpm://239.255.76.67:99999?ttl=0"
    run = subprocess.run([sys.executable, "-m", "tegrasp_drake", *command], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120,
                         env={**os.environ, "LCM_DEFAULT_URL": bad})
    assert run.returncode == 1, run.stderr
    assert_one_line_error(run.returncode, run.stderr, "tegrasp: error:",
                          "environment variable LCM_DEFAULT_URL", bad)


# Rule: a sweep record names the events folder it matched against resolved (absolute), so a
# record read from another working folder names the right one; a record naming it relative
# (as records did before) still loads.
def test_a_sweep_record_names_its_events_folder_resolved(tmp_path, monkeypatch):
    import shutil

    from tegrasp_drake.rig import paths
    from tegrasp_drake.sweep.records import check_record, make_record
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    from tegrasp_drake.sweep.trial_function import events_identities
    shutil.copytree(paths.package_events_dir() / "box", tmp_path / "ev" / "box")
    shutil.copy(paths.package_events_dir() / "index.json", tmp_path / "ev")
    monkeypatch.chdir(tmp_path)
    trials = [t.to_dict() for t in expand_trials(SweepSpec(
        objects=("box",), controllers=("memorized",), attempts=1, grid=((0.0, 0.0),)))]
    identity = events_identities(trials, "ev")[trials[0]["trial_id"]]
    assert identity["folder"] == str(tmp_path.resolve() / "ev")
    old = make_record(trials[0], result={}, events={**identity, "folder": "ev"})
    assert check_record(old) is None
