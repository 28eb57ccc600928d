"""Outputs are checked by one function before the work: an output on a named pipe, in /proc,
inside the installed package, a file where a folder belongs, a folder that cannot be made
or a wrong figure format is refused up front in one line; a figure or report that cannot
be written (a full disk) is one line and the old one is kept; written files honour the
umask and only rig/files.py makes temporary files."""

import errno
import os
import pathlib

import pytest

import tegrasp_drake
from tegrasp_drake import cli
from tegrasp_drake.figures import figure_files
from tegrasp_drake.rig import files
from tests.bad_input.probes import (FAKE_TRIALS, SEED, SEEDED_SWEEP, assert_one_line_error,
                                    folder_contents, one_error_line, one_line_of, run_cli)


def test_a_figure_on_a_full_disk_leaves_the_old_figure_whole(tmp_path):
    """Probe 9: savefig fails part-way; the earlier figure stays, no temporary is left."""
    old = tmp_path / "fig.png"
    old.write_bytes(b"\x89PNG\r\n\x1a\n an earlier figure")

    class FullDiskFigure:
        def savefig(self, path, **kwargs):
            pathlib.Path(path).write_bytes(b"half")
            raise OSError(28, "No space left on device")
    with pytest.raises(OSError):
        figure_files.save_figure(FullDiskFigure(), old)
    assert old.read_bytes() == b"\x89PNG\r\n\x1a\n an earlier figure"
    assert [p.name for p in tmp_path.iterdir()] == ["fig.png"]


# --- files and runs -------------------------------------------------------------------------

@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_written_files_honour_the_umask(umask, mode, tmp_path):
    previous = os.umask(umask)
    try:
        written = files.write_atomically(tmp_path / "a.json", "{}",
                                         start=files.JSON_OBJECT_START)
        with files.temporary_sibling(tmp_path / "b.png", start=b"\x89PNG") as temporary:
            temporary.write_bytes(b"figure")
    finally:
        os.umask(previous)
    assert written.stat().st_mode & 0o777 == mode
    assert (tmp_path / "b.png").stat().st_mode & 0o777 == mode


# --- permissions -------------------------------------------------------------------------------

@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600)])
def test_sweep_records_honour_the_umask(umask, mode, tmp_path):
    from tegrasp_drake.sweep.records import make_record, write_record
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    trial = expand_trials(SweepSpec(objects=("box",), attempts=1))[0].to_dict()
    error = {"type": "RuntimeError", "message": "diverged", "traceback": "Traceback ..."}
    previous = os.umask(umask)
    try:
        path = write_record(tmp_path, make_record(trial, error=error))
    finally:
        os.umask(previous)
    assert path.stat().st_mode & 0o777 == mode


def test_only_rig_files_makes_temporary_files():
    """Every writer goes through rig/files.py, which gives a file the mode the umask gives
    (mkstemp alone makes it 0600). The one other: the private traceback file of the command
    line and the analysis scripts (commands/error_boundary.py)."""
    package = pathlib.Path(tegrasp_drake.__file__).parent
    users = sorted(str(p.relative_to(package)) for p in package.rglob("*.py")
                   if "mkstemp(" in p.read_text(encoding="utf-8"))
    assert users == ["commands/error_boundary.py", "rig/files.py"]


# --- 2. one line, not a raw exception --------------------------------------------------------

def test_a_figure_that_cannot_be_written_is_one_line(tmp_path, capfd):
    out = tmp_path / ("a" * 300 + ".png")  # longer than a file name may be
    code, text = run_cli(["plot", "events", "--out", str(out)], capfd)
    # refused before the figure is drawn, by the check every output file gets
    assert_one_line_error(code, text, "--out", "File name too long")
    assert code == cli.EXIT_ERROR and list(tmp_path.iterdir()) == []


def test_a_figure_name_too_long_in_folders_to_be_made_leaves_no_folders(tmp_path, capfd,
                                                                         monkeypatch):
    """The folders do not exist yet, so the name's length shows only when the figure is
    written: the refusal says to shorten the name, and the folders made for it are removed."""
    monkeypatch.chdir(tmp_path)
    out = pathlib.Path("made", "deeper", "b" * 260 + ".png")
    code, text = run_cli(["plot", "events", "--object", "box", "--out", str(out)], capfd)
    assert_one_line_error(code, text, "File name too long; give a shorter name")
    assert list(tmp_path.iterdir()) == []


# Rule: a symbolic link at --out, dangling or not, is the user's: it is refused by name
# (with --overwrite too, as trial's --out refuses one), never replaced by the figure.
@pytest.mark.parametrize("overwrite", [[], ["--overwrite"]])
@pytest.mark.parametrize("target", ["nowhere/dangling.png", "figure.png"])
def test_a_figure_is_never_written_over_a_symbolic_link(tmp_path, capfd, target, overwrite):
    from tegrasp_drake.figures.figure_files import new_figure, save_figure
    save_figure(new_figure(1, 1), tmp_path / "figure.png")
    link = tmp_path / "link.png"
    link.symlink_to(tmp_path / target)
    code, text = run_cli(["plot", "events", "--out", str(link), *overwrite], capfd)
    assert_one_line_error(code, text, "--out", "symbolic link")
    assert code == cli.EXIT_ERROR and link.is_symlink()
    assert os.readlink(link) == str(tmp_path / target)


def test_a_figure_on_a_full_disk_is_one_line_and_the_old_one_kept(tmp_path):
    import errno
    from tegrasp_drake.figures.figure_files import new_figure, save_figure
    old = tmp_path / "fig.png"
    old.write_bytes(b"\x89PNG\r\n\x1a\n the earlier figure")
    figure = new_figure(2, 2)

    def disk_full(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    figure.savefig = disk_full
    with pytest.raises(files.UserPathError, match="cannot write the figure .*fig.png: No space"):
        save_figure(figure, old)
    assert (old.read_bytes() == b"\x89PNG\r\n\x1a\n the earlier figure"
            and len(list(tmp_path.iterdir())) == 1)


# --- 4. refused before the work --------------------------------------------------------------

def test_an_output_folder_that_cannot_be_made_is_refused_up_front():
    assert "/proc cannot be written in: making a folder there failed" in files.folder_problem(
        "/proc/tegrasp-test/events")


def test_html_naming_the_run_folder_is_refused_up_front(tmp_path, capfd):
    out = tmp_path / "run"
    code, text = run_cli(["trial", "--out", str(out), "--html", str(out)], capfd)
    assert_one_line_error(code, text, "--html", "is the run's folder")
    assert not out.exists()


def test_reports_into_a_folder_that_does_not_exist_are_refused_and_make_nothing(tmp_path):
    with pytest.raises(files.UserPathError, match="'out_dir'.*does not exist"):
        tegrasp_drake.write_reports(tmp_path / "nonexistent" / "dir")
    assert not (tmp_path / "nonexistent").exists()


def test_a_wrong_figure_format_is_refused_before_any_report_is_written(tmp_path):
    (tmp_path / "trials").mkdir()
    before = folder_contents(tmp_path)
    with pytest.raises(ValueError) as refused:
        tegrasp_drake.write_reports(tmp_path, figure_format="bmp")
    assert "argument 'figure_format'" in one_line_of(refused.value)
    assert folder_contents(tmp_path) == before


@pytest.mark.parametrize("call", [
    lambda file: tegrasp_drake.run_sweep(
        tegrasp_drake.SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                                grid=((0.0, 0.0),), base_seed=SEED),
        tegrasp_drake.run_trial_from_spec, file, workers=1, progress=False),
    lambda file: tegrasp_drake.save_memorized_events(file, []),
])
def test_a_file_given_as_an_output_folder_is_named_as_a_file(tmp_path, call):
    file = tmp_path / "good.npz"
    file.write_bytes(b"PK")
    with pytest.raises(files.UserPathError) as refused:
        call(file)
    assert "is a file, not a folder" in one_line_of(refused.value)
    assert "good.npz" in str(refused.value)


@pytest.mark.parametrize("argv_of", [
    lambda p: ["trial", "--controller", "open_loop", "--out", str(p.parent / "o"),
               "--html", str(p)],
    lambda p: ["plot", "trial", str(p.parent / "missing.npz"), "--out",
               str(p.with_suffix(".png"))],
])
def test_an_output_on_a_fifo_is_refused_naming_its_option(tmp_path, argv_of, capfd):
    path = tmp_path / "pipe.html"
    argv = argv_of(path)
    os.mkfifo(argv[-1])
    code, text = run_cli(argv, capfd)
    assert code not in (0, 70)
    errors = one_error_line(text)
    assert len(errors) == 1 and argv[-2] in errors[0] and "named pipe" in errors[0], text
    assert pathlib.Path(argv[-1]).exists() and not pathlib.Path(argv[-1]).is_file()


@pytest.mark.parametrize("option, name", [("--html", "h.html")])
def test_an_output_in_proc_is_refused_before_the_run(tmp_path, option, name, capfd):
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "o"),
                          option, f"/proc/{name}"], capfd)
    assert code not in (0, 70)
    errors = one_error_line(text)
    assert len(errors) == 1 and option in errors[0] and "/proc" in errors[0], text
    assert not (tmp_path / "o").exists()


def test_output_file_problem_refuses_devices_and_proc_and_accepts_a_new_file(tmp_path):
    from tegrasp_drake.rig.files import output_file_problem
    assert "device" in output_file_problem("/dev/null")
    assert "/proc" in output_file_problem("/proc/self/x.html")
    assert "folder" in output_file_problem(tmp_path)
    assert output_file_problem(tmp_path / "new" / "replay.html") is None
    (tmp_path / "plain").write_text("x")
    assert "not a folder" in output_file_problem(tmp_path / "plain" / "replay.html")


# Rule: no output of any command goes inside the installed package, which pip deletes.
def test_output_inside_the_installed_package_is_refused(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.rig import files
    package = (tmp_path / "site-packages" / "tegrasp_drake").resolve()
    (package / "events").mkdir(parents=True)
    monkeypatch.setattr(files, "installed_package_dir", lambda: package)
    assert "pip deletes" in files.folder_problem(package / "events" / "mine")
    assert "pip deletes" in files.output_file_problem(package / "f.png")
    assert files.folder_problem(tmp_path / "mine") is None
    code, text = run_cli(["trial", "--out", str(package / "events" / "mine")], capfd)
    assert_one_line_error(code, text, "is inside the installed package", "outside it")
    assert not (package / "events" / "mine").exists()


def test_a_source_checkout_is_not_an_installed_package():
    from tegrasp_drake.rig.files import installed_package_dir
    assert installed_package_dir() is None  # the tests run from the checkout


def _full_disk(*args, **kwargs):
    """rig.files.staged_file on a file system with no room left."""
    raise OSError(errno.ENOSPC, "No space left on device")


def test_a_finished_transfer_rerun_on_a_full_disk_is_one_line_and_keeps_its_reports(
        tmp_path, capfd, monkeypatch):
    """A rerun with nothing left to run rewrites only its reports: on a full disk that was exit
    70 (world.json rewritten unchanged) and a 0-byte table1.md (written in place)."""
    from tegrasp_drake.events.events_folder import load_memorized_events
    from tegrasp_drake.recording import paper_events
    from tegrasp_drake.rig import files, paths
    monkeypatch.setattr(paper_events, "record_events", lambda name, scenario=None, **_:
                        load_memorized_events(paths.package_events_dir(), name))
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds: {w: {scenario: faithful_world}}\ncells: [[w, w]]\n" + SEEDED_SWEEP)
    out = tmp_path / "out"
    argv = ["transfer", str(spec), "--out", str(out), "--workers", "1", "--no-progress",
            *FAKE_TRIALS]
    code, text = run_cli(argv, capfd)
    assert code == 0, text
    reports = sorted(out.glob("transfer.*"))
    assert any(report.name == "transfer.md" for report in reports)
    before = {report: report.read_bytes() for report in reports}
    world = out / "events" / "w" / "world.json"
    world_before = world.stat().st_mtime_ns

    monkeypatch.setattr(files, "staged_file", _full_disk)
    code, text = run_cli(argv, capfd)
    assert code == 1, text
    assert "No space left on device" in text and "internal error" not in text
    assert len([line for line in text.splitlines() if "error" in line]) == 1, text
    assert "transfer.md" in text  # the first write of the rerun: world.json is kept as it is
    assert {report: report.read_bytes() for report in reports} == before
    assert world.stat().st_mtime_ns == world_before


def test_a_finished_sweep_rerun_on_a_full_disk_is_one_line_and_keeps_its_reports(
        tmp_path, capfd, monkeypatch):
    """The Markdown, CSV and JSON reports were written in place: a full disk left a 0-byte
    table1.md where the earlier one was, and exit 70."""
    from tegrasp_drake.rig import files
    spec = tmp_path / "s.yaml"
    spec.write_text("controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                    "grid: [[0.0, 0.0]]\nbase_seed: 640\n")
    out = tmp_path / "out"
    argv = ["sweep", "--spec", str(spec), "--out", str(out), "--workers", "1",
            "--no-progress", "--trial-function", "tests.fake_trials:fake_trial"]
    code, text = run_cli(argv, capfd)
    assert code == 0, text
    reports = sorted(path for path in out.iterdir() if path.suffix in (".md", ".csv", ".json"))
    assert {"table1.md", "table1.csv", "statistics.json"} <= {path.name for path in reports}
    before = {report: report.read_bytes() for report in reports}

    monkeypatch.setattr(files, "staged_file", _full_disk)
    code, text = run_cli(argv, capfd)
    assert code == 1, text
    assert "No space left on device" in text and "internal error" not in text
    assert {report: report.read_bytes() for report in reports} == before


# Rule: a long path a user gave (hundreds or thousands of characters) is cut in an error line
# to about 80 characters, its start and its end kept, saying how long it was; the line stays
# short, whichever command or analysis script says it.
@pytest.mark.parametrize("argv_of", [
    lambda path: ["sweep", "--dry-run", "--out", path],
    lambda path: ["trial", "--out", path],
    lambda path: ["plot", "signals", path + ".npz"],
    lambda path: ["replay", path + ".lcmlog"],
    lambda path: ["trial", "--scenario", path + ".yaml"],
], ids=["sweep-out", "trial-out", "plot-log", "replay-log", "trial-scenario"])
def test_a_long_path_is_cut_keeping_its_start_and_end(argv_of, tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("x")
    path = "afile/" + "/".join(f"{k:02d}" + "d" * 150 for k in range(20)) + "/the_end"
    argv = argv_of(path)
    code, text = run_cli(argv, capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "afile/00ddd", "d/the_end", "characters)")
    assert len(text) < 300, text


def test_an_analysis_script_cuts_a_long_path_keeping_its_start_and_end(tmp_path, capsys):
    from tegrasp_drake.commands.script_output import run_script, script_parser
    parser = script_parser("some_script", "Does something.")
    parser.add_input("results", what="results folder",
                     advice="give the --out folder of `tegrasp sweep`")
    path = f"{tmp_path}/" + ("x" * 150 + "/") * 4 + "the_end"
    try:
        code = run_script(lambda argv: parser.parse_args(argv) and 0, "some_script", [path])
    except SystemExit as exit_:
        code = exit_.code
    text = (code if isinstance(code, str) else "") + capsys.readouterr().err
    assert text.count("\n") <= 1 and len(text) < 300, text
    assert str(tmp_path)[:20] in text and "x/the_end" in text, text


# Rule: an empty file (0 bytes) where a figure goes is refused saying it is empty and what a
# file there must hold to be replaced (a figure of its suffix's format), by `tegrasp plot` and
# the analysis scripts alike; an output given as '' is refused naming it, not as '.'.
@pytest.mark.parametrize("suffix", ["png", "pdf", "svg"])
def test_an_empty_file_where_a_figure_goes_is_named_empty(suffix, tmp_path, capsys):
    from tests.analysis_script import load_analysis_script
    figure = tmp_path / f"maps.{suffix}"
    figure.write_bytes(b"")
    make_success_maps = load_analysis_script("make_success_maps")
    results = str(pathlib.Path(tegrasp_drake.__file__).parents[1] / "analysis" / "results_seed0")
    for overwrite in ([], ["--overwrite"]):
        code, text = _script_exit(make_success_maps, [results, "--file", str(figure),
                                                      *overwrite], capsys)
        assert code == 1, text
        assert f"maps.{suffix} exists and is empty (0 bytes), not a .{suffix} figure" in text
        assert "first bytes" not in text and text.count("\n") == 1, text
    assert figure.read_bytes() == b""


def test_plot_names_an_empty_figure_file_empty(tmp_path, capfd):
    figure = tmp_path / "fig.png"
    figure.write_bytes(b"")
    code, text = run_cli(["plot", "events", "--out", str(figure), "--overwrite"], capfd)
    assert_one_line_error(code, text, "exists and is empty (0 bytes), not a .png figure")
    assert code == 1


def test_an_analysis_script_output_given_empty_is_named(capsys):
    from tests.analysis_script import load_analysis_script
    make_success_maps = load_analysis_script("make_success_maps")
    code, text = _script_exit(make_success_maps, ["results", "--file", ""], capsys)
    assert code == 2, text
    assert text.startswith("make_success_maps: error: --file '' is empty; give a figure file"
                           " (.png, .pdf or .svg)"), text


def _script_exit(script, argv, capsys) -> tuple[int, str]:
    """(exit code, its error line) of the analysis script module `script` run on `argv`."""
    try:
        code, message = script.run_script(script.main, script.__name__, argv), ""
    except SystemExit as exit_:
        code, message = ((1, exit_.code + "\n") if isinstance(exit_.code, str)
                         else (exit_.code, ""))
    return code, message + capsys.readouterr().err
