"""The command line's one error boundary: a bad option, value or environment stops the
command before anything runs, with one line that names the input and says what to do and a
non-zero exit, never a traceback; the line is bounded, quotes no control character raw and
rounds its numbers by one formatter; an unforeseen exception is one line with its traceback
in a file. The table of probes below gives one bad command line a row."""

import ast
import os
import pathlib
import re
import sys

import pytest

import tegrasp_drake
import tegrasp_drake as T
from tegrasp_drake import cli
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.rig import files
from tests.bad_input.probes import (FAKE_TRIALS, SEEDED_SWEEP, assert_one_line_error,
                                    assert_probe_refused, refusal, run_cli,
                                    tegrasp_in_child_process)
from tests.runs.earlier_hardware_run import EARLIER_RESULT

OWN_BOX = ["--set", "object.shape=box", "--set", "object.size=[0.04,0.04,0.1]",
           "--set", "object.mass=0.1", "--set", "object.friction=0.5"]


def _write(name, text):
    return lambda folder: (folder / name).write_text(text)


def _nested_aliases(folder):
    lines = ["a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]"]
    lines += [f"a{k}: &a{k} [{', '.join([f'*a{k - 1}'] * 10)}]" for k in range(1, 7)]
    (folder / "bomb.yaml").write_text("\n".join(lines) + "\nmine: {object: {name: box}}\n")


def _large_scenario(folder):
    (folder / "big.yaml").write_text("mine: {object: {name: box}}\n"
                                     + "".join(f"k{k}: {'x' * 60}\n" for k in range(20_000)))


def _hardware_result(folder):
    (folder / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (folder / "run.result.json").write_text(EARLIER_RESULT)


def _earlier_run(folder):
    (folder / "run").mkdir()
    (folder / "run" / "result.json").write_text("an earlier result")
    (folder / "run" / "trial.npz").write_text("an earlier log")
    (folder / "replay").mkdir()


def _symlink_loop(folder):
    (folder / "loop").symlink_to("loop")


def _corrupt_sweep_record(folder):
    (folder / "sweep" / "trials").mkdir(parents=True)
    (folder / "sweep" / "trials" / "memorized.box.m00.a0.json").write_text('{"trial_id": ')

PROBES = [  # (name, files made first, argv, words the one error line holds)
    ("1 hardware result beside --log", _hardware_result,
     ["hardware", "--config", "hw.yaml", "--log", "run.lcmlog"],
     ["run.result.json already holds a run's result", "--overwrite"]),
    ("2 --set unclosed list", None, ["trial", "--set", "placement.offset=[0.0,0.015"],
     ["--set 'placement.offset=[0.0,0.015'", "not valid YAML", "quote"]),
    ("2 --set mapping in a name", None, ["trial", "--set", "object.name=a: b"],
     ["--set 'object.name=a: b'", "not valid YAML", "object.name='a: b'"]),
    ("2 --set undefined alias", None, ["trial", "--set", "random_seed=*foo"],
     ["--set 'random_seed=*foo'", "undefined alias 'foo'"]),
    ("2 --set python tag", None,
     ["trial", "--set", "random_seed=!!python/object/apply:os.system [touch hacked]"],
     ["Python object tag", "never loaded"]),
    ("3 sweep --logs FILE", _write("afile", "x"),
     ["sweep", "--logs", "afile", "--objects", "box", "--controllers", "heuristic",
      "--attempts", "1", "--out", "sweep"], ["--logs afile", "not a folder"]),
    ("5 emulate --write-config over a user's file", _write("hw.yaml", "port: mine\n"),
     ["emulate", "robotiq", "--write-config", "hw.yaml"],
     ["--write-config hw.yaml exists and was not written by `tegrasp emulate`"]),
    ("6 seed 2^32", None, ["trial", "--set", "random_seed=4294967296"],
     ["field 'random_seed' must lie in [0, 4294967295]", "32-bit"]),
    ("6 negative seed", None, ["trial", "--set", "random_seed=-1"],
     ["field 'random_seed' must lie in"]),
    ("6 seed 2^64", None, ["trial", "--set", "random_seed=18446744073709551616"],
     ["field 'random_seed' must lie in"]),
    ("7 negative taxel noise", None, ["trial", "--set", "tactile.noise_std_n=-0.01"],
     ["field 'tactile.noise_std_n' must be zero (no noise) or positive"]),
    ("7 negative film noise", None, ["trial", "--set", "vibration.noise_std_mps2=-0.05"],
     ["field 'vibration.noise_std_mps2' must be zero (no noise) or positive"]),
    ("7 mode frequency 0", None, ["trial", "--set", "vibration.film.mode_frequency_hz=0"],
     ["field 'vibration.film.mode_frequency_hz' must lie in [50, "]),
    ("7 hit after the trial", None, ["trial", "--set", "disturbance.hit_time_s=100"],
     ["field 'disturbance.hit_time_s' must come before the grasp's script ends"]),
    ("9 --overwrite with a bad --html", _earlier_run,
     ["trial", "--out", "run", "--overwrite", "--html", "replay"],
     ["--html replay is a folder"]),
    ("10 object name with /", None, ["record-events", "--set", "object.name=my/box", *OWN_BOX],
     ["field 'object.name' 'my/box' must be letters, digits"]),
    ("10 --out a file", _write("afile", "x"), ["trial", "--out", "afile"],
     ["--out afile: afile is not a folder"]),
    ("10 --out /dev/full", None, ["trial", "--out", "/dev/full"],
     ["--out /dev/full: /dev/full is not a folder"]),
    ("10 events folder a symlink loop", _symlink_loop,
     ["record-events", "--object", "box", "--events", "loop"], ["--events loop"]),
    ("10 time step 0.1 s", None, ["trial", "--set", "plant_config.time_step=0.1"],
     ["field 'plant_config.time_step' must lie in [0.0001, 0.001] s"]),
    ("10 time step 1e-7 s", None, ["trial", "--set", "plant_config.time_step=0.0000001"],
     ["field 'plant_config.time_step' must lie in"]),
    ("10 a 1e6 N hit", None, ["trial", "--set", "disturbance.hit_force_n=[0.0,1000000.0,0.0]"],
     ["field 'disturbance.hit_force_n' must be at most 100 N"]),
    ("10 mode mass 0", None, ["trial", "--set", "vibration.film.mode_mass_kg=0"],
     ["field 'vibration.film.mode_mass_kg' must lie in [0.001, 1] kg"]),
    ("10 taxel rate 0.001 Hz", None, ["trial", "--set", "tactile.sample_rate_hz=0.001"],
     ["field 'tactile.sample_rate_hz' must lie in [16, 20000] Hz"]),
    ("10 taxel rate 1e6 Hz", None, ["trial", "--set", "tactile.sample_rate_hz=1000000.0"],
     ["field 'tactile.sample_rate_hz' must lie in [16, 20000] Hz"]),
    ("10 scalar scenario with --set", _write("sc.yaml", "mine: 5\n"),
     ["trial", "--scenario", "sc.yaml", "--scenario-name", "mine", "--set", "random_seed=1"],
     ["sc.yaml: scenario 'mine' must be a mapping of fields, got int 5"]),
    ("10 sweep --attempts 100000000", None, ["sweep", "--attempts", "100000000", "--out", "sw"],
     ["--attempts must lie in [1, 1000000] (a sweep makes at most 1000000 trials), got "
      "100000000"]),
    ("record-events --ensemble-runs 99", None,
     ["record-events", "--ensemble-runs", "99", "--set", "object.name=mine", *OWN_BOX],
     ["--ensemble-runs 99: give 0 (none) to 50 ideal grasps"]),
    ("also --inject-fault 0x10", None, ["emulate", "robotiq", "--inject-fault", "0x10@3"],
     ["--inject-fault '0x10@3'", "4 bits"]),
    ("also --inject-fault 0 (no fault)", None, ["emulate", "robotiq", "--inject-fault", "0@3"],
     ["--inject-fault '0@3'", "0x0 being no fault; give a CODE from 0x1 to 0xf"]),
    ("also duplicate keys", _write("dup.yaml", "mine:\n  random_seed: 1\n  random_seed: 2\n"),
     ["trial", "--scenario", "dup.yaml", "--scenario-name", "mine"],
     ["dup.yaml: key 'random_seed' appears twice (line 2, column 3 and line 3, column 3)"]),
    ("also nested aliases", _nested_aliases,
     ["trial", "--scenario", "bomb.yaml", "--scenario-name", "mine"],
     ["bomb.yaml: the YAML's aliases expand to more than 100000 values"]),
    ("also a 1.3 MB scenario", _large_scenario,
     ["trial", "--scenario", "big.yaml", "--scenario-name", "mine"],
     ["big.yaml:", "bytes of YAML; a configuration is at most 1000000 bytes"]),
    ("also plot table1 with a corrupt record", _corrupt_sweep_record,
     ["plot", "table1", "sweep", "--out", "table1.png"],
     ["1 corrupt trial record(s) in sweep", "memorized.box.m00.a0.json"]),
]


@pytest.mark.parametrize("make, argv, expected", [probe[1:] for probe in PROBES],
                         ids=[probe[0] for probe in PROBES])
def test_a_probe_stops_with_one_line_and_loses_nothing(make, argv, expected, tmp_path,
                                                       monkeypatch, capfd):
    assert_probe_refused(make, argv, expected, tmp_path, monkeypatch, capfd)
    assert not (tmp_path / "hacked").exists()


# A --set selects a controller by its name or by a section's tag: either, against another
# --controller, is refused the same way.
@pytest.mark.parametrize("assignment", ["controller.name=heuristic",
                                        "controller=!HeuristicControllerConfig {}"])
@pytest.mark.parametrize("command", [["trial"], ["hardware", "--config", "hw.yaml",
                                                 "--log", "run.lcmlog"]])
def test_controller_and_another_set_controller_name_are_refused_naming_both(
        command, assignment, tmp_path, monkeypatch, capfd):
    make = _write("hw.yaml", hardware_config_to_yaml(HardwareStationConfig()))
    argv = command + ["--controller", "open_loop", "--set", assignment]
    _, text = assert_probe_refused(make, argv, [f"--controller open_loop and --set "
                                                f"{assignment} select different "
                                                "controllers; give one of them"],
                                   tmp_path, monkeypatch, capfd)
    code, _ = run_cli(argv, capfd)
    assert code == 1


@pytest.mark.parametrize("argv, words", [
    (["trial", "--out", "a", "--out", "b"], "--out given twice ('a', then 'b'); give it once"),
    (["trial", "--scenario-name", "box", "--scenario-name", "thin_cylinder"],
     "--scenario-name given twice ('box', then 'thin_cylinder'); give it once"),
    (["trial", "--set", "object.mass=0.1", "--set", "object.mass=0.2"],
     "--set sets object.mass twice ('object.mass=0.1', then 'object.mass=0.2'); set it once"),
    (["sweep", "--set", "grasp.hold_s=2", "--set", "grasp.hold_s=3", "--dry-run"],
     "--set sets grasp.hold_s twice"),
    (["record-events", "--object", "box", "--set", "object.mass=0.1", "--set",
      "object.mass=0.3"], "--set sets object.mass twice"),
    (["hardware", "--config-set", "tactile.port=/a", "--config-set", "tactile.port=/b"],
     "--config-set sets tactile.port twice ('tactile.port=/a', then 'tactile.port=/b')"),
])
def test_an_option_given_twice_with_two_values_is_refused(argv, words, tmp_path, monkeypatch,
                                                          capfd):
    """Neither value silently wins (as a YAML file's repeated key is refused): exit 2."""
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, words)
    assert code == 2 and "--help" in text, text
    assert list(tmp_path.iterdir()) == []


def test_an_option_repeated_with_the_same_value_and_different_keys_are_taken():
    from tegrasp_drake.commands import trial
    from tegrasp_drake.rig.usage_parser import UsageParser
    parser = UsageParser(prog="tegrasp")
    trial.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["trial", "--out", "a", "--out", "a", "--set", "object.mass=0.1",
                              "--set", "object.friction=0.4", "--set", "object.mass=0.1"])
    assert args.out == "a"
    assert args.overrides == ["object.mass=0.1", "object.friction=0.4", "object.mass=0.1"]


def test_controller_and_the_same_set_controller_name_agree():
    scenario = T.LoadScenario(overrides=["controller.name=open_loop"], controller="open_loop")
    assert scenario.controller.name == "open_loop"


# --- the command line's error boundary --------------------------------------------------------

def test_an_unforeseen_exception_is_one_line_with_its_traceback_in_a_file(monkeypatch, capfd):
    from tegrasp_drake.commands import plot

    def broken(args):
        raise RuntimeError("something no check foresaw\nsecond line")
    monkeypatch.setattr(plot, "run", broken)
    code, text = run_cli(["plot", "table1", "nowhere"], capfd)
    assert code == cli.EXIT_INTERNAL_ERROR
    assert len(text.strip().splitlines()) == 1, text
    assert "tegrasp: internal error: RuntimeError: something no check foresaw" in text
    assert "(-v shows it)" in text
    where = text.split("traceback in ")[1].split(" ")[0].rstrip(";")
    assert "Traceback" in pathlib.Path(where).read_text()
    os.unlink(where)
    code, text = run_cli(["plot", "table1", "nowhere", "-v"], capfd)
    assert code == cli.EXIT_INTERNAL_ERROR and "Traceback" in text
    os.unlink(text.split("traceback in ")[1].split(" ")[0].rstrip(";"))


# Arguments a command needs before the path option under test.
_POSITIONALS = {"plot": ["events"], "transfer": ["spec.yaml"], "sensitivity": ["spec.yaml"],
                "replay": ["run.lcmlog"],
                "emulate": ["myrio"]}


def _path_options():
    parser = cli.build_parser()
    commands = next(a for a in parser._actions if hasattr(a, "choices") and a.choices)
    return [(name, action.option_strings[0]) for name, command in commands.choices.items()
            for action in command._actions
            if action.dest in cli.PATH_ARGUMENTS and action.option_strings]


@pytest.mark.parametrize("command, option", _path_options())
def test_every_empty_path_option_is_refused(command, option, capfd):
    code, text = run_cli([command, *_POSITIONALS.get(command, []), option, ""], capfd)
    assert code == 2 and f"{option} '' is empty" in text and "Traceback" not in text


@pytest.mark.parametrize("argv, words", [
    (["trial", "--scenario"], "give a scenario YAML file"),
    (["emulate", "myrio", "--write-config"], "give a file to write the hardware config to"),
    (["trial", "--out"], "give an output folder"),
    (["plot", "events", "--out"], "give a figure file"),
])
def test_an_empty_path_option_is_told_what_it_takes(argv, words, capfd):
    code, text = run_cli([*argv, ""], capfd)
    assert code == 2 and words in text, text


# --- 5. safe messages ------------------------------------------------------------------------

@pytest.mark.parametrize("character", ["\x1b", "\x07", "\x9b", "\u2028", "\r", "\n"])
def test_an_error_never_quotes_a_control_character_raw(character):
    quoted = files.one_line(f"a{character}[2Jb")
    assert quoted.isprintable() and character not in quoted


def test_a_set_value_with_an_escape_is_quoted_safely(capfd):
    code, text = run_cli(["trial", "--set", "object.name=a\x1b[2Jb"], capfd)
    assert code != 0 and "\x1b" not in text and "\\x1b[2Jb" in text
    code, text = run_cli(["trial", "--controller", "x\x1b[2J"], capfd)  # argparse's words
    assert code == 2 and "\x1b" not in text and "\\x1b[2J" in text


def test_a_deleted_current_folder_is_named(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.rig.files import folder_problem, output_file_problem
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()
    for problem in (output_file_problem("f.png"), folder_problem("o")):
        assert "the current folder no longer exists; cd to one that does" in problem
    code, text = run_cli(["plot", "trial", str(tmp_path / "trial.npz"), "--out", "f.png"],
                         capfd)
    assert_one_line_error(code, text, "current folder no longer exists")


def test_a_locale_without_utf8_runs_the_command_in_utf8_mode():
    done = tegrasp_in_child_process(["trial", "--help"], LC_ALL="C", LANG="C", PYTHONUTF8="0")
    assert done.returncode == 0, done.stderr
    assert "--out" in done.stdout and done.stderr == ""


# Rule: an error is one bounded line that echoes values cut to about 80 characters, and its
# reason is the true one: a file of many plain values is not said to expand aliases.
def test_error_text_is_bounded_and_names_the_true_reason(tmp_path):
    import json
    import shutil

    from tegrasp_drake.events.event_file import MemorizedEventError
    from tegrasp_drake.rig import paths
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("prismatic", "ensemble", "corrective"))
    path = folder / "box" / "load_lift.json"
    event = json.loads(path.read_text())
    event["scenario"] = "default:\n  object: !!python/object/apply:os.system ['true']\n"
    path.write_text(json.dumps(event))
    with pytest.raises(MemorizedEventError) as refused:
        T.load_memorized_events(folder, "box")
    message = str(refused.value)
    assert "scenario" in message and "\n" not in message and len(message) < 600, message
    assert len(str(MemorizedEventError(path, "x" * 5000))) < 1200
    many = tmp_path / "many.yaml"
    many.write_text("".join(f"s{k}: {{random_seed: 1}}\n" for k in range(30_000)))
    refusal(lambda: T.LoadScenario(many, name="s7"), "holds more than 100000 values")
    aliased = tmp_path / "aliased.yaml"
    aliased.write_text("a: &a [" + ", ".join(["1"] * 1000) + "]\n"
                       + "b: [" + ", ".join(["*a"] * 200) + "]\n")
    refusal(lambda: T.LoadScenario(aliased, name="a"), "aliases expand to more than")


# Rule: an environment variable or option value is checked before a library is handed it:
# a backend matplotlib does not know, an output encoding that cannot hold a name the user
# gave, an LCM URL option LCM would ignore, a fault time beyond any hardware run.
def test_environment_and_option_values_are_checked_before_a_library_gets_them(tmp_path):
    import io
    import os
    import subprocess
    import sys

    from tegrasp_drake.cli import main
    from tegrasp_drake.commands.output_streams import guarded_output
    from tegrasp_drake.hardware.config import lcm_url_problem
    environment = dict(os.environ, MPLBACKEND="banana")
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake", "plot", "events", "--out",
                           str(tmp_path / "x.png")], env=environment, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 1, done.stderr
    assert done.stderr.strip().count("\n") == 0 and "MPLBACKEND='banana'" in done.stderr
    ascii_out = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    saved = sys.stdout
    sys.stdout = ascii_out
    try:
        with guarded_output():
            print("wrote o/été_ü.png")
    finally:
        sys.stdout = saved
    ascii_out.flush()
    assert ascii_out.buffer.getvalue() == b"wrote o/\\xe9t\\xe9_\\xfc.png\n"
    for option, words in (("ttl=zero", "does not parse as an LCM URL: ttl 'zero' is not a "
                                       "decimal integer"),
                          ("ttl=0&recv_buf_size=lots", "recv_buf_size 'lots' is not a "
                                                       "decimal integer")):
        problem = lcm_url_problem(f"udpm://239.255.76.67:8793?{option}")
        assert problem and words in problem, problem
    assert lcm_url_problem("udpm://239.255.76.67:8793?ttl=0") is None
    for fault in ("14@1e9", "14@601", "14@-1"):
        with pytest.raises(SystemExit) as refused:
            main(["emulate", "robotiq", "--inject-fault", fault, "--scheduling", "normal",
                  "--lcm-url", "udpm://239.255.76.67:8793?ttl=0"])
        assert "must lie in [0, 600] s" in str(refused.value.code), refused.value.code


# Rule: every number a message shows is written by rig.number_text (or a format spec), so
# none prints 3.997943786001997 where the others print 3.99794. Each message f-string of the
# package (raised, printed, an error's text) is read, and a value with a unit in its name
# (period_s, rate_hz, timeout, ...) or computed by arithmetic must not be formatted bare.
_UNIT_NAME = re.compile(r"(_s|_hz|_m|_n|_mps2|_rad|_mm|_kg|timeout|time_step|period|rate)$")

_MESSAGE_CALLS = ("print", "SystemExit", "warn")


def _message_fstrings(tree):
    for node in ast.walk(tree):
        if isinstance(node, ast.Raise) and node.exc is not None:
            yield node.exc
        elif isinstance(node, ast.Call):
            name = getattr(node.func, "id", None) or getattr(node.func, "attr", "")
            if name in _MESSAGE_CALLS or name.endswith("Error"):
                yield node


def _bare_float(value: ast.expr) -> bool:
    """Whether `value` is a number that needs rounding: a name with a unit, or a division."""
    if isinstance(value, ast.BinOp):
        return (isinstance(value.op, ast.Div) or _bare_float(value.left)
                or _bare_float(value.right))
    name = getattr(value, "attr", None) or getattr(value, "id", "")
    return bool(_UNIT_NAME.search(name))


def test_every_number_a_message_shows_is_rounded_by_one_formatter():
    package = pathlib.Path(tegrasp_drake.__file__).parent
    bare = set()  # a raised error's call is walked twice
    for path in sorted(package.rglob("*.py")):
        source = path.read_text()
        for message in _message_fstrings(ast.parse(source)):
            for part in ast.walk(message):
                if (isinstance(part, ast.FormattedValue) and part.format_spec is None
                        and part.conversion == -1 and _bare_float(part.value)):
                    bare.add(f"{path.relative_to(package)}:{part.lineno}: "
                             f"{ast.get_source_segment(source, part.value)}")
    assert not bare, sorted(bare)


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


@pytest.mark.parametrize("command", ["sweep", "transfer", "sensitivity"])
def test_a_runner_option_refused_is_bad_input_as_for_every_command(tmp_path, capfd, command):
    """An --out that is a file: exit 1, as `tegrasp trial` and `plot` give (the table: bad
    input, a file that cannot be written); a spec refused stays 2."""
    taken = tmp_path / "a_file"
    taken.write_text("")
    spec = tmp_path / "spec.yaml"
    spec.write_text({"sweep": "controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                              "grid: [[0.0, 0.0]]\nbase_seed: 640\n",
                     "transfer": "worlds: {w: {scenario: faithful_world}}\ncells: [[w, w]]\n"
                                 + SEEDED_SWEEP,
                     "sensitivity": "parameters: [gripper.pad_friction]\n" + SEEDED_SWEEP}[command])
    spec_argument = ["--spec", str(spec)] if command == "sweep" else [str(spec)]
    for out, code in ((taken, 1), (tmp_path / "out", 1)):
        workers = "1" if out == taken else "0"
        status, text = run_cli([command, *spec_argument, "--out", str(out), "--workers",
                                workers, "--no-progress", *FAKE_TRIALS], capfd)
        assert status == code, text
        assert len(text.strip().splitlines()) == 1, text


# Rule: a command line that does not parse is one line on stderr naming the (sub)command and
# the argument, pointing to its --help, with argparse's exit code 2 (docs/user-guide.md,
# "Exit codes"); never the usage block.
@pytest.mark.parametrize("argv, words", [
    (["sweep", "--base-seed", "1e3"],
     "tegrasp: error: argument --base-seed: '1e3' is not an integer "
     "(see tegrasp sweep --help)"),
    (["hardware", "--duration", "abc"], "tegrasp: error: argument --duration:"),
    (["emulate", "robotiq", "--inject-fault", "abc"],
     "tegrasp: error: argument --inject-fault: 'abc': expected CODE@SECONDS"),
    (["record-events", "--controller", "open_loop"],
     "tegrasp: error: unrecognized arguments: --controller open_loop "
     "(see tegrasp record-events --help)"),
    (["no-such-command"], "tegrasp: error: argument command: invalid choice"),
])
def test_a_command_line_that_does_not_parse_is_one_line_naming_the_command(argv, words, capfd):
    try:
        code = cli.main(argv)
    except SystemExit as exit_:
        code = exit_.code
    captured = capfd.readouterr()
    assert code == 2 and captured.out == "", captured
    assert captured.err.count("\n") == 1 and "usage:" not in captured.err, captured.err
    assert captured.err.startswith(words), captured.err
    command = argv[0] if argv[0] != "no-such-command" else None
    assert captured.err.endswith(f"(see tegrasp{' ' + command if command else ''} --help)\n")


# Rule: every error of `tegrasp` and its subcommands starts with one lead, `tegrasp: error: `
# (docs/user-guide.md, "Exit codes"), whoever refuses: argparse (a usage error, exit 2), the
# check of empty values, a command's own refusal (exit 1), a sweep command's refusal of its
# spec (exit 2) or option (exit 1), a file the user named.
@pytest.mark.parametrize("argv, code", [
    (["sweep", "--workers", "abc"], 2),
    (["transfer", "spec.yaml", "--out", ""], 2),
    (["sweep", "--workers", "0", *FAKE_TRIALS], 1),
    (["sweep", "--spec", "empty.yaml", "--out", "o", *FAKE_TRIALS], 2),
    (["sensitivity", "missing.yaml", "--out", "o"], 1),
    (["hardware", "--config", "missing.yaml"], 1),
    (["plot", "trial", "missing.npz"], 1),
])
def test_every_error_of_every_command_has_the_one_lead(argv, code, tmp_path, monkeypatch,
                                                       capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "empty.yaml").write_text("")
    try:
        got = cli.main(argv)
    except SystemExit as exit_:
        got = exit_.code if isinstance(exit_.code, int) else 1
        if isinstance(exit_.code, str):
            print(exit_.code, file=sys.stderr)
    captured = capfd.readouterr()
    assert got == code, captured
    lines = captured.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("tegrasp: error: "), captured.err


# Rule: `tegrasp --version` prints the package's version on standard output and exits 0,
# not "the following arguments are required: command".
def test_version_prints_the_packages_version(capfd):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["--version"])
    captured = capfd.readouterr()
    assert exit_.value.code in (0, None), captured
    assert captured.out == f"tegrasp {tegrasp_drake.__version__}\n" and captured.err == ""


# Rule: a value starting with '-' as a number does (-inf, -1@3) is the option's value, refused
# by the option's own check naming it, never "expected one argument"; an option the command
# has is still an option, so `--attempts --dry-run` lacks its argument.
def _refused_in(tmp_path, monkeypatch, capfd, argv, exit_code, *words):
    """The output of `tegrasp argv` run in tmp_path, checked to be one line holding `words`
    and `exit_code`."""
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(argv, capfd)
    assert code == exit_code, text
    assert_one_line_error(code, text, *words)
    return text


@pytest.mark.parametrize("argv, words", [
    (["sweep", "--dry-run", "--attempts", "-inf"], "argument --attempts: '-inf' is not an"),
    (["sweep", "--dry-run", "--base-seed", "-inf"], "argument --base-seed: '-inf' is not an"),
    (["hardware", "--config", "/nonexistent/hw.yaml", "--duration", "-inf"],
     "argument --duration: '-inf' is not a number"),
    (["emulate", "robotiq", "--inject-fault", "-1@3"],
     "argument --inject-fault: '-1@3': expected CODE@SECONDS"),
    (["sweep", "--dry-run", "--attempts", "--dry-run"],
     "argument --attempts: expected one argument"),
    (["sweep", "--attempts", "-v"], "argument --attempts: expected one argument"),
])
def test_a_value_starting_with_a_minus_is_named_by_its_option(argv, words, tmp_path,
                                                              monkeypatch, capfd):
    _refused_in(tmp_path, monkeypatch, capfd, argv, 2, words)


# Rule: every number option reads its text with the package's one reader (rig.number_text's
# number_option, rig.integer_text's integer_option): decimal digits with a '-' sign, nothing
# else that Python's float() or int() reads (`1_0`, another script's digits, spaces, '+'),
# which is refused as a command line that does not parse, naming the option and the text.
@pytest.mark.parametrize("argv", [["hardware", "--config", "/nonexistent/hw.yaml", "--duration"],
                                  ["sweep", "--dry-run", "--attempts"],
                                  ["sweep", "--dry-run", "--base-seed"],
                                  ["sweep", "--dry-run", "--workers"]])
@pytest.mark.parametrize("text", ["1_0", "\u0661\u0662", "\uff11\uff12", " 3", "+3"])
def test_every_number_option_refuses_what_only_python_reads_as_a_number(argv, text, tmp_path,
                                                                         monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text_printed = run_cli([*argv, text], capfd)
    assert code == 2, text_printed
    assert_one_line_error(code, text_printed, f"argument {argv[-1]}: {text!r}")


@pytest.mark.parametrize("seconds", ["1_0", "\u0661\u0662", " 3", "+3"])
def test_a_fault_time_is_read_as_every_number_option_reads_one(seconds):
    import argparse

    from tegrasp_drake.commands.emulate import fault_option
    with pytest.raises(argparse.ArgumentTypeError, match=f"SECONDS {re.escape(repr(seconds))}"):
        fault_option(f"14@{seconds}")


# Rule: a number option's text that no float holds (1e400, a 400-digit integer, a nonzero
# 1e-400 a float rounds to 0) is refused by the reader naming the text as typed, never
# echoed as the inf or 0 it would convert to, nor taken as one.
@pytest.mark.parametrize("argv, words", [
    (["hardware", "--duration", "1e400"], "argument --duration: '1e400' is beyond the range"),
    (["hardware", "--duration", "1e-400"], "argument --duration: '1e-400' is beyond the range"),
    (["hardware", "--duration", "9" * 400], "is an integer of 400 digits, beyond the range"),
    (["sweep", "--dry-run", "--attempts", "9" * 400], "is an integer of 400 digits"),
])
def test_a_number_option_beyond_a_floats_range_is_named_as_typed(argv, words, tmp_path,
                                                                  monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    if argv[0] == "hardware":
        argv = [*argv, "--config", "/nonexistent/hw.yaml"]
    code, text = run_cli(argv, capfd)
    assert code == 2, text
    assert_one_line_error(code, text, words)
    assert "inf" not in text.replace("info", ""), text


def test_a_fault_time_beyond_a_floats_range_is_named_as_typed():
    import argparse

    from tegrasp_drake.commands.emulate import fault_option
    with pytest.raises(argparse.ArgumentTypeError, match="SECONDS '1e400' is beyond the range"):
        fault_option("14@1e400")


def test_no_number_option_bypasses_the_one_number_reader():
    # argparse's type=float or type=int would take what Python reads (1_0, ١٢, ' 3').
    root = pathlib.Path(tegrasp_drake.__file__).parent.parent
    bypassing = []
    for folder in ("tegrasp_drake", "analysis", "benchmarks"):
        for path in sorted((root / folder).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text())):
                if isinstance(node, ast.keyword) and node.arg == "type" and isinstance(
                        node.value, ast.Name) and node.value.id in ("float", "int"):
                    bypassing.append(f"{path.relative_to(root)}:{node.value.lineno}")
    assert not bypassing, bypassing


# Rule: an option's value that parses but lies outside its range is bad input, exit 1, in one
# line naming the option and its range, whichever command takes it; only a value that does not
# parse (not a number, not of the option's form) is a command line that does not parse, exit 2
# (docs/user-guide.md, "Exit codes").
@pytest.mark.parametrize("argv, words", [
    (["hardware", "--duration", "0"], "--duration 0: give a duration in (0, 600] seconds"),
    (["hardware", "--duration", "601"], "--duration 601: give a duration in (0, 600]"),
    (["hardware", "--duration", "-5"], "--duration -5: give a duration in (0, 600]"),
    (["hardware", "--duration", "0.001"], "--duration 0.001: give at least 0.01 s"),
    (["hardware", "--duration", "1e-9"], "--duration 1e-9: give at least 0.01 s, one period"),
    (["hardware", "--duration", "600.0001"], "--duration 600.0001: give a duration in (0, 600]"),
    (["sweep", "--attempts", "0", "--dry-run"], "--attempts must be a positive integer, got 0"),
    (["sweep", "--base-seed", "-1", "--dry-run"], "--base-seed must lie in [0, 4294967295]"),
    (["sweep", "--workers", "0", "--dry-run"], "--workers must be at least 1, got 0"),
    (["sweep", "--confirm-trials", "0", "--dry-run"], "--confirm-trials 0: give the study's"),
    (["record-events", "--ensemble-runs", "-1"], "--ensemble-runs -1: give 0 (none) to 50"),
    (["emulate", "robotiq", "--inject-fault", "14@601"], "SECONDS must lie in [0, 600] s"),
    (["emulate", "robotiq", "--inject-fault", "14@6.01e2"], "[0, 600] s (after the gripper's "
     "activation, within a hardware run's ten minutes), got 6.01e2"),
    (["emulate", "robotiq", "--inject-fault", "0x10@3"], "gFLT holds 4 bits"),
])
def test_an_option_value_out_of_its_range_is_bad_input_on_every_command(argv, words, tmp_path,
                                                                       monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli([*argv, "--scheduling", "normal"] if argv[0] == "emulate" else argv,
                         capfd)
    assert code == 1, text
    assert_one_line_error(code, text, words)
    assert "--help" not in text, text


# Rule: a command-line argument (an option's value, a positional, one of a repeated option's,
# a subcommand's name) holding a control character, a tab or line break too, is a command line
# that does not parse, exit 2, in one line naming the argument, the character's code and its
# byte, whichever command or analysis script takes it: a line break would split the one-line
# error, an escape drive the terminal the value is echoed on.
@pytest.mark.parametrize("argv, name", [
    (["emulate", "jaco", "--scheduling", "normal", "--lcm-url",
      "udpm://239.255.76.67:7667\x07"], "argument --lcm-url holds a control character (0x07)"
                                         " at byte 26"),
    (["emulate", "jaco", "--scheduling", "normal", "--lcm-url",
      "udpm://239.255.76.67:7667\x1b[31m"], "--lcm-url holds a control character (0x1b, "
                                            "escape) at byte 26"),
    (["replay", "run\x1b[2J.lcmlog"], "argument LOG holds a control character (0x1b"),
    (["sweep", "--dry-run", "--out", "sw\x00"], "--out holds a control character (0x00, NUL)"),
    (["trial", "--set", "object.name=\x7f"], "--set holds a control character (0x7f, DEL)"),
    (["trial", "--out", "ab\ncd"], "argument --out holds a control character (0x0a, line "
                                    "break) at byte 3"),
    (["trial", "--out=a\tb"], "argument --out holds a control character (0x09, tab) at byte 2"),
    (["trial", "--out", "\u00e9\r"], "(0x0d, carriage return) at byte 3"),
    (["sweep", "--dry-run", "--workers", "2\n"], "argument --workers holds a control"),
    (["plot", "signals", "l\tog.npz"], "argument LOG|RESULTS holds a control character"),
    (["tr\x1bial"], "tegrasp: error: argument command holds a control character (0x1b"),
    (["record-events", "--out", "e\nv"], "argument --events/--out holds a control character"),
])
def test_a_control_character_in_an_argument_is_a_command_line_that_does_not_parse(
        argv, name, tmp_path, monkeypatch, capfd):
    text = _refused_in(tmp_path, monkeypatch, capfd, argv, 2, name,
                       "printable characters only: remove it")
    assert not any(c in text[:-1] for c in "\x1b\x07\x00\x7f\t\r\n"), repr(text)
    assert list(tmp_path.iterdir()) == [], "a refused command line wrote nothing"


def test_a_control_character_in_an_analysis_script_argument_is_refused_naming_it(capsys):
    from tegrasp_drake.commands.script_output import script_parser
    parser = script_parser("some_script", "Does something.")
    parser.add_argument("--label")
    parser.add_argument("results")
    for argv, name in ((["--label", "a\x1bb", "r"], "--label"), (["a\nb"], "results")):
        with pytest.raises(SystemExit) as exit_:
            parser.parse_args(argv)
        assert exit_.value.code == 2
        text = capsys.readouterr().err
        assert text.startswith(f"some_script: error: argument {name} holds a control "
                               "character (0x"), text
        assert text.count("\n") == 1 and "\x1b" not in text, repr(text)


# Rule: a text default that holds a control character, one the environment set
# (LCM_DEFAULT_URL), is bad input, exit 1, naming the option it is the default of.
def test_a_control_character_in_an_environment_default_is_bad_input(monkeypatch, capfd):
    from tegrasp_drake.commands import emulate
    monkeypatch.setattr(emulate, "default_lcm_url", lambda: "udpm://239.255.76.67:7667\x1b[2J")
    code, text = run_cli(["emulate", "jaco", "--scheduling", "normal"], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "--lcm-url holds an escape (character 0x1b)")
    assert "\x1b[" not in text


# Rule: a --set that is no KEY=VALUE with KEY a dotted field name (an empty key or name, no
# '=') is a command line that does not parse, refused as `--set ''` is, with exit code 2; so
# is such a --config-set (a hardware config's field), its example one of that config's.
@pytest.mark.parametrize("command, option, example", [
    ("trial", "--set", "object.mass"), ("record-events", "--set", "object.mass"),
    ("sweep", "--set", "object.mass"), ("hardware", "--config-set", "tactile.port")])
@pytest.mark.parametrize("assignment", ["=", "=0.2", ".object.mass=0.2", "object..mass=0.2",
                                        "object.=0.2", " =0.2", "object.mass"])
def test_a_malformed_set_is_refused_as_a_command_line_that_does_not_parse(
        command, option, example, assignment, capfd):
    code, text = run_cli([command, option, assignment], capfd)
    assert code == 2, text
    assert text.count("\n") == 1 and "unknown field" not in text, text
    assert text.startswith(
        f"tegrasp: error: argument {option}: '{assignment}': expected KEY=VALUE with "
        f"KEY a dotted field name such as {example} (see "), text


# Rule: a byte that is not UTF-8 in a --set or --config-set (`$'object.mass=\xff'`, held by
# Python as the surrogate \udcff) is refused first, as the byte the user gave, in the key or
# the value alike, as a command line that does not parse (exit 2); PyYAML's "#xdcff" or an
# unknown field 'object.ma\xffss' is never the reason.
@pytest.mark.parametrize("command, option, key", [
    ("trial", "--set", "object.mass"), ("record-events", "--set", "object.mass"),
    ("sweep", "--set", "gripper.pad_friction"), ("hardware", "--config-set", "arm.lcm_url")])
def test_a_byte_that_is_not_utf8_in_a_set_is_named_as_given(command, option, key, capfd):
    code, text = run_cli([command, option, f"{key}=\udcff"], capfd)
    assert code == 2, text
    assert text.count("\n") == 1 and "xdcff" not in text and "udcff" not in text, text
    assert text.startswith(
        f"tegrasp: error: argument {option}: '{key}=\\xff': byte 0xff (character "
        f"{len(key) + 2}, in the value) is not UTF-8; give the value in UTF-8 text (see "
        f"tegrasp {command} --help)"), text
    code, text = run_cli([command, option, "object.ma\udcffss=1"], capfd)
    assert code == 2 and "unknown field" not in text, text
    assert "'object.ma\\xffss=1': byte 0xff (character 10, in the key) is not UTF-8; give " \
           "the key in UTF-8 text (see" in text, text


def test_a_byte_that_is_not_utf8_in_a_set_is_named_from_a_shell(tmp_path):
    done = tegrasp_in_child_process(["trial", "--set", "object.mass=\udcc3(",
                                     "--out", str(tmp_path / "t")])
    assert done.returncode == 2, done.stderr
    assert done.stderr == ("tegrasp: error: argument --set: 'object.mass=\\xc3(': byte "
                           "0xc3 (character 13, in the value) is not UTF-8; give the value in "
                           "UTF-8 text (see tegrasp trial --help)\n"), done.stderr
    assert not (tmp_path / "t").exists()


def test_a_byte_that_is_not_utf8_given_to_the_api_is_named_the_same_way():
    refusal(lambda: T.LoadScenario(overrides=["object.mass=\udcff"]),
            "--set 'object.mass=", "byte 0xff (character 13, in the value) is not UTF-8")


def test_an_empty_set_keeps_its_own_refusal_and_code(capfd):
    code, text = run_cli(["trial", "--set", ""], capfd)
    assert code == 2 and "--set '' is empty" in text, text


def test_a_malformed_assignment_given_to_the_api_is_named_the_same_way():
    refusal(lambda: T.LoadScenario(overrides=["=0.2"]),
            "--set '=0.2': expected KEY=VALUE with KEY a dotted field name such as object.mass")


# Rule: the package's standalone docs commands refuse a command line as `tegrasp` does.
@pytest.mark.parametrize("main, argv, words", [
    ("tegrasp_drake.control.rule_docs", ["--bogus"],
     "python -m tegrasp_drake.control.rule_docs: error: unrecognized arguments: --bogus "
     "(see python -m tegrasp_drake.control.rule_docs --help)"),
    ("tegrasp_drake.control.rule_docs", ["--write", "a", "--check", "b"],
     "python -m tegrasp_drake.control.rule_docs: error: argument --check: not allowed with "
     "argument --write (see "),
    ("tegrasp_drake.sensitivity.parameters", ["--bogus"],
     ": error: one of the arguments --check --write is required (see "),
    ("tegrasp_drake.scenario.rule_reach", ["--check"],
     ": error: argument --check: expected one argument (see "),
])
def test_a_docs_command_line_that_does_not_parse_is_one_line(main, argv, words, capfd):
    import importlib
    with pytest.raises(SystemExit) as exit_:
        importlib.import_module(main).main(argv)
    captured = capfd.readouterr()
    assert exit_.value.code == 2 and captured.out == "", captured
    assert captured.err.count("\n") == 1 and "usage:" not in captured.err, captured.err
    assert words in captured.err, captured.err


# Rule: a long --set list whose refusal names a field none of its assignments set (a rule
# across settings: object.shape's value is refused under object.name) still shows every
# assignment, each cut to a readable length with its start kept, so the user sees which of
# several --set was wrong; never "(and 2 other --set)" with none shown.
def test_a_long_set_refused_under_another_field_is_shown(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.rig.echo import ECHO_CHARS
    monkeypatch.chdir(tmp_path)
    shape = "object.shape=sphere" + "e" * 200
    code, text = run_cli(["trial", "--set", shape, "--set", "grasp.grip_force=50",
                          "--out", "o"], capfd)
    assert_one_line_error(code, text, "--set object.shape=sphereeeee",
                          "--set grasp.grip_force=50", "field 'object.name'")
    assert "other --set" not in text
    source = text.split(": field 'object.name'")[0]
    assert len(source.split("--set object.shape=")[1].split(" --set")[0]) < ECHO_CHARS, source
    assert not (tmp_path / "o").exists()
