"""Figure files (figures/figure_files.py): a figure is written through a temporary file beside
it and a rename, and the next write of a figure removes what a write of that same figure
killed past its handlers (SIGKILL) left beside it, and nothing else."""

import os

import pytest

from tests.commands.test_run_folder import _ended_process_id
from tests.killed_runs import killed_before_rename
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS, new_figure, save_figure

PNG_START = b"\x89PNG\r\n\x1a\n"  # a PNG file's signature (PNG specification, 5.2)


@pytest.mark.parametrize("figure_format", FIGURE_FORMATS)
def test_a_figure_write_removes_what_a_killed_write_of_that_figure_left(tmp_path,
                                                                       figure_format):
    target = tmp_path / f"timeline.{figure_format}"
    killed_before_rename("from tegrasp_drake.figures.figure_files import new_figure, "
                         f"save_figure\nsave_figure(new_figure(2, 1), {str(target)!r})")
    left = sorted(tmp_path.iterdir())
    assert len(left) == 1 and not target.exists(), left  # the killed write's temporary file
    save_figure(new_figure(2, 1), target)
    assert sorted(tmp_path.iterdir()) == [target]


def test_a_figure_write_keeps_other_figures_and_other_files_leftovers(tmp_path):
    target = tmp_path / "timeline.png"
    killed_before_rename("from tegrasp_drake.figures.figure_files import new_figure, "
                         f"save_figure\nsave_figure(new_figure(2, 1), {str(target)!r})")
    dead = _ended_process_id()
    kept = {tmp_path / f".other.png.abcd1234.{dead}.staging": PNG_START,  # another figure's
            tmp_path / f".timeline.png.abcd1234.{dead}.staging": b"my notes",  # not a PNG
            tmp_path / f".timeline.png.efgh5678.{os.getppid()}.staging": PNG_START}  # live
    for path, data in kept.items():
        path.write_bytes(data)
    link = tmp_path / f".timeline.png.ijkl9012.{dead}.staging"
    link.symlink_to(tmp_path / f".other.png.abcd1234.{dead}.staging")
    save_figure(new_figure(2, 1), target)
    assert sorted(tmp_path.iterdir()) == sorted([target, link, *kept])
    assert all(path.read_bytes() == data for path, data in kept.items())


# --- an existing file is replaced only when it is a figure of its format ------------------

@pytest.mark.parametrize("figure_format", FIGURE_FORMATS)
def test_a_figure_is_never_written_over_a_file_of_another_kind(tmp_path, figure_format):
    from tegrasp_drake.rig.files import UserPathError
    notes = tmp_path / f"notes.{figure_format}"
    notes.write_text("important\n")
    with pytest.raises(UserPathError, match=f"is not a .{figure_format} figure"):
        save_figure(new_figure(2, 2), notes)
    assert notes.read_text() == "important\n"
    save_figure(new_figure(2, 2), tmp_path / f"f.{figure_format}")
    save_figure(new_figure(2, 2), tmp_path / f"f.{figure_format}")  # a figure of its format


def test_plot_keeps_a_users_file_and_replaces_a_figure_only_with_overwrite(tmp_path, capfd):
    from tests.bad_input.probes import run_cli
    notes = tmp_path / "notes.png"
    notes.write_text("important\n")
    code, text = run_cli(["plot", "events", "--out", str(notes), "--overwrite"], capfd)
    assert code != 0 and len(text.strip().splitlines()) == 1, text
    assert "is not a .png figure" in text and notes.read_text() == "important\n"
    figure = tmp_path / "events.png"
    assert run_cli(["plot", "events", "--out", str(figure)], capfd)[0] == 0
    code, text = run_cli(["plot", "events", "--out", str(figure)], capfd)
    assert code != 0 and "pass --overwrite" in text, text
    assert run_cli(["plot", "events", "--out", str(figure), "--overwrite"], capfd)[0] == 0


def test_an_analysis_script_keeps_a_users_file_where_its_figure_goes(tmp_path):
    from tests.test_analysis_error_boundary import run_script
    notes = tmp_path / "notes.svg"
    notes.write_text("important\n")
    done = run_script("make_success_maps", [str(tmp_path), "--file", str(notes)], tmp_path)
    assert done.returncode != 0 and "is not a .svg figure" in done.stderr, done.stderr
    assert notes.read_text() == "important\n"
