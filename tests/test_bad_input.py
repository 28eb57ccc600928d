"""Bad inputs through the command line: each stops
before anything runs, with one line that names the file, field or value and says what to do,
and a non-zero exit; none runs with a value other than the one given."""

import hashlib
import json
import pathlib
import shutil

import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.scenario.trial_log_file import ARRAY_FIELDS, FORMAT_VERSION
from tegrasp_drake.rig import paths

OWN_CYLINDER = ["--set", "object.shape=cylinder", "--set", "object.size=[0.04,0.1]",
                "--set", "object.mass=0.12", "--set", "object.friction=0.6"]


def run_cli(argv, capfd) -> tuple[int, str]:
    """(exit code, what it printed) of `tegrasp ARGV`, run in this process."""
    try:
        code = cli.main(argv)
        message = ""
    except SystemExit as exit_:
        code, message = (1, exit_.code) if isinstance(exit_.code, str) else (exit_.code, "")
    captured = capfd.readouterr()
    return code, "\n".join(part for part in (message, captured.err, captured.out) if part)


def folder_contents(folder: pathlib.Path) -> dict:
    """Every regular file under `folder` (relative path -> sha256): what a refused command
    must leave as it was."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and not p.is_symlink()}


def run_probe(make, argv, folder: pathlib.Path, monkeypatch, capfd):
    """Runs `tegrasp ARGV` in `folder`, after `make(folder)` (when given) laid out its
    hostile inputs; returns (the folder's files before, its entries before, exit code,
    what it printed)."""
    monkeypatch.chdir(folder)
    if make:
        make(folder)
    before, entries = folder_contents(folder), sorted(folder.iterdir())
    code, text = run_cli(argv, capfd)
    return before, entries, code, text


def assert_one_line_error(code, text, *expected):
    assert code != 0, text
    assert "Traceback" not in text, text
    error_lines = [line for line in text.splitlines() if "error" in line]
    assert len(error_lines) == 1, text
    assert len(text.strip().splitlines()) == 1, text  # nothing else printed
    for words in expected:
        assert words in error_lines[0], text


# --- scenario values ----------------------------------------------------------------------

@pytest.mark.parametrize("overrides, expected", [
    (["object.friction=0"], "field 'object.friction' must be positive"),
    (["object.mass=0"], "field 'object.mass' must be positive"),
    (["object.mass=.nan"], "field 'object.mass' must be a finite number, got float nan"),
    (["object.mass=.inf"], "field 'object.mass' must be a finite number, got float inf"),
    (["object.friction=.inf"], "field 'object.friction' must be a finite number"),
    (["controller.matching.sa_threshold=.nan"], "field 'controller.matching.sa_threshold' must be a finite"),
    (["controller.matching.ra_threshold=2"], "field 'controller.matching.ra_threshold' must lie in [-1, 1]"),
    (["gripper.position_loop_hz=10"], "field 'gripper.position_loop_hz' must lie in [40, 150]"),
    (["gripper.screw_efficiency=0.9"], "field 'gripper.screw_efficiency' must lie in [0.2, 0.5]"),
    (["controller.matching.ra_envelope_hz=-1"], "field 'controller.matching.ra_envelope_hz' must be 0 (no RA"),
    (["controller.matching.ra_envelope_hz=500"], "between 0 and half the RA rate (500 Hz), got 500"),
    (["controller.matching.ra_noise_floor_sigmas=5.39", "controller.matching.ra_noise_quiet_s=3"],
     "field 'controller.matching.ra_noise_quiet_s' must end with the approach, by grasp.settle_s + "
     "grasp.reach_s = 2.8 s"),
    (["placement.offset=[.nan,0]"], "field 'placement.offset[0]' must be a finite number"),
    (["placement.yaw_deg=.nan"], "field 'placement.yaw_deg' must be a finite number"),
    (["plant_config.time_step=.nan"], "field 'plant_config.time_step' must be a finite"),
    (["controller.event_object_may_differ=[colour]"],
     "field 'controller.event_object_may_differ[0]' must name a field"),
])
def test_a_bad_scenario_value_is_named_and_nothing_runs(overrides, expected, capfd):
    argv = ["trial", "--controller", "memorized"]
    for assignment in overrides:
        argv += ["--set", assignment]
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, expected, f"--set {overrides[0]}")


@pytest.mark.parametrize("command", [["trial"], ["record-events"]])
def test_your_own_object_needs_its_own_name(command, capfd):
    code, text = run_cli([*command, *OWN_CYLINDER], capfd)
    assert_one_line_error(code, text, "field 'object.name'", "needs its own name",
                          "not the built-in 'box'")


def test_a_yaml_syntax_error_in_a_scenario_file_is_named(tmp_path, capfd):
    scenario = tmp_path / "bad.yaml"
    scenario.write_text("mine:\n  object: {name: box\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario), "not valid YAML: line 3, column 1: "
                          "expected ',' or '}'")


@pytest.mark.parametrize("command", [["record-events"], ["trial"]])
def test_a_built_in_scenario_name_given_as_its_file_says_use_scenario_name(command, capfd):
    code, text = run_cli([*command, "--scenario", "memorizing_world"], capfd)
    assert_one_line_error(code, text, "'memorizing_world' is a built-in scenario",
                          "--scenario-name memorizing_world")


# --- object model files ----------------------------------------------------------------

TWO_LINKS = """<?xml version="1.0"?><sdf version="1.9"><model name="two">
<link name="a"><inertial><mass>0.1</mass></inertial></link>
<link name="b"><inertial><mass>0.1</mass></inertial></link></model></sdf>"""


@pytest.mark.parametrize("content, expected", [
    ("this is not SDF", "is not a model Drake can load"),
    (TWO_LINKS, "must hold one model with one body"),
    (None, "is not a model Drake can load"),  # a package:// URL that does not exist
])
def test_a_bad_object_model_file_is_named(content, expected, tmp_path, capfd):
    if content is None:
        file = "package://tegrasp/no_such_object.sdf"
    else:
        file = tmp_path / "object.sdf"
        file.write_text(content)
    code, text = run_cli(["trial", "--set", "object.name=mine", "--set", "object.shape=file",
                          "--set", f"object.file={file}", "--set", "object.size=[0.04,0.04,0.1]",
                          "--set", "object.mass=0.1", "--set", "object.friction=0.5"], capfd)
    assert_one_line_error(code, text, "field 'object.file'", expected)


# --- hardware configs -------------------------------------------------------------------

@pytest.mark.parametrize("text, expected", [
    ("- arm\n- gripper\n", "must be a mapping of HardwareStationConfig fields"),
    ("watchdog: {tactile_timeout: .nan}\n", "field 'watchdog.tactile_timeout' must be a finite"),
    ("ready_timeout: -5\n", "field 'ready_timeout' must be positive"),
    ("tactile: {max_backlog: -3}\n", "field 'tactile.max_backlog' must be zero or a positive"),
    ("watchdog: {arm_timeout: 0}\n", "field 'watchdog.arm_timeout' must be positive"),
    ("arm: {lcm_url: 'udpm://239.255.76.67:99999?ttl=0'}\n",
     "field 'arm.lcm_url' cannot be opened by LCM"),
    ("arm: {lcm_url: garbage}\n", "field 'arm.lcm_url' is not an LCM bus URL"),
    ("watchdog: {arm_timeout: 0.05\n", "not valid YAML"),
    ("scheduling: deadline\n", "field 'scheduling' must be one of 'fifo', 'nice', 'normal'"),
])
def test_a_bad_hardware_config_is_named_before_any_device_is_opened(text, expected, tmp_path,
                                                                     capfd):
    config = tmp_path / "hw.yaml"
    config.write_text(text)
    code, output = run_cli(["hardware", "--config", str(config), "--controller", "heuristic"],
                           capfd)
    assert_one_line_error(code, output, str(config), expected)


# --- memorized events -------------------------------------------------------------------

@pytest.fixture
def events_copy(tmp_path):
    """A copy of the package's events to spoil."""
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("__init__.py", "__pycache__"))
    return folder


def _edit(path, change):
    data = json.loads(path.read_text())
    change(data)
    path.write_text(json.dumps(data))


def _zero_channel(folder):
    _edit(folder / "box" / "load_lift.json",
          lambda data: data["samples"].update(ra_left=[0.0] * len(data["samples"]["ra_left"])))


def _drop_index_entry(folder):
    _edit(folder / "index.json", lambda data: data.update(events=[
        e for e in data["events"] if (e["object"], e["transition"]) != ("box", "load_lift")]))


def _copy_other_objects_events(folder):
    """The thick cylinder's well-formed events copied in as the box's."""
    for file in (folder / "thick_cylinder").glob("*.json"):
        shutil.copy(file, folder / "box" / file.name)
        _edit(folder / "box" / file.name, lambda data: data.update(object="box"))
    _edit(folder / "index.json", lambda data: data.update(events=[
        dict(e, object="box", file=e["file"].replace("thick_cylinder", "box"))
        if e["object"] == "thick_cylinder" else e
        for e in data["events"] if e["object"] != "box"]))


@pytest.mark.parametrize("spoil, expected", [
    (_zero_channel, "channels ['ra_left'] are zero throughout the window"),
    (_drop_index_entry, "lists no load_lift event of object 'box'"),
    (_copy_other_objects_events, "were recorded on another object: shape 'cylinder' "
                                 "(recorded) != 'box' (now)"),
])
def test_unusable_events_are_named_before_the_trial_runs(spoil, expected, events_copy, capfd):
    spoil(events_copy)
    code, text = run_cli(["trial", "--events", str(events_copy)], capfd)
    assert_one_line_error(code, text, str(events_copy), expected)


def test_the_corrective_events_are_read_from_the_events_folder_given(events_copy, capfd):
    _edit(events_copy / "corrective" / "box" / "hold_avoid.json",
          lambda data: data["samples"].update(ra_left=[0.0] * len(data["samples"]["ra_left"])))
    code, text = run_cli(["trial", "--events", str(events_copy), "--set",
                          "controller.memorized_corrective.events=[hold_avoid]"], capfd)
    assert_one_line_error(code, text, str(events_copy / "corrective"),
                          "channels ['ra_left'] are zero throughout the window")


def test_events_of_a_changed_builtin_object_are_refused_unless_accepted(capfd):
    code, text = run_cli(["trial", "--set", "object.mass=0.3"], capfd)
    assert_one_line_error(code, text, "mass 0.15 (recorded) != 0.3 (now)",
                          "controller.event_object_may_differ=[mass]")


# --- trial logs -------------------------------------------------------------------------

def _trial_log(path, **changes):
    """A small well-formed trial log (the arrays' shapes as TrialLog.save writes them, each
    time base at its logger's period for the default scenario: 108 Hz, 1 kHz, 10 ms)."""
    n_sa, n_ra, n_slow = 11, 101, 11
    arrays = {"t_sa": np.arange(n_sa) / 108.0, "taxels": np.ones((n_sa, 24)),
              "true_taxels": np.ones((n_sa, 24)), "t_ra": np.linspace(0, 0.1, n_ra),
              "channels": np.ones((n_ra, 4)), "pad_acceleration": np.zeros((n_ra, 6)),
              "t_slow": np.linspace(0, 0.1, n_slow), "arm_q": np.zeros((n_slow, 6)),
              "arm_q_desired": np.zeros((n_slow, 6)), "gripper_command": np.zeros((n_slow, 3)),
              "gripper_status": np.zeros((n_slow, 8)), "phase": np.zeros(n_slow),
              "object_state": np.zeros((n_slow, 13))}
    arrays["object_state"][:, 0] = 1.0  # the identity orientation, a unit quaternion
    for name in ("arm_q", "arm_q_desired"):  # joints 2 and 3 within the JACO2's limits
        arrays[name][:, 1:3] = [3.0, 1.0]
    assert set(arrays) == set(ARRAY_FIELDS)
    arrays.update(changes)
    # every trial log names its controller (trial_log_file.REQUIRED_META_FIELDS): the
    # default scenario's
    meta = json.dumps({"format_version": FORMAT_VERSION, "controller": "memorized"})
    np.savez_compressed(path, meta=np.array(meta), **arrays)
    return path


def _truncate(path):
    data = path.read_bytes()
    path.write_bytes(data[:len(data) // 2])


def _flip_bits(path):
    data = bytearray(path.read_bytes())
    for k in range(200, len(data) - 200, 50):
        data[k] ^= 0x10
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("make, expected", [
    (lambda p: _truncate(_trial_log(p)), "is truncated or corrupt"),
    (lambda p: _flip_bits(_trial_log(p)), "is truncated or corrupt"),
    (lambda p: _trial_log(p, channels=np.ones((50, 4))),
     "'channels' has shape (50, 4), but 101 samples of 't_ra' need (101, 4)"),
    (lambda p: _trial_log(p, channels=np.full((101, 4), np.nan)),
     "the arrays ['channels'] hold NaN or infinite values"),
])
def test_a_damaged_trial_log_is_named_and_not_plotted(make, expected, tmp_path, capfd):
    path = tmp_path / "trial.npz"
    make(path)
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, str(path), expected)
    assert not (tmp_path / "x.png").exists()


# --- sweep specs ------------------------------------------------------------------------

@pytest.mark.parametrize("definition, expected", [
    ("{shape: box, size: [0.04, 0.09, 0.1], mass: 0.1, friction: 0.5}",
     "field 'user_objects.crate.size': makes the object 90.0 mm wide"),
    ("{shape: cylinder, size: [0.04, 0.1], mass: 0.1}",
     "field 'user_objects.crate.friction': is missing"),
    ("{shape: cylinder, size_m: [0.04, 0.1], mass_kg: 0.1, friction_coefficient: 0.5}",
     "field 'user_objects.crate.size_m': is the old name of the field: rename size_m to "
     "size, mass_kg to mass, friction_coefficient to friction"),
])
def test_a_sweep_spec_whose_objects_cannot_run_is_refused_at_load(definition, expected,
                                                                  tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"objects: [crate]\nuser_objects:\n  crate: {definition}\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--no-progress"], capfd)
    assert code == 2, text
    assert_one_line_error(code, text, str(spec), expected)
    assert not (tmp_path / "out" / "trials").exists()
