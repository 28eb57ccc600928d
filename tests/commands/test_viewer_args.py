"""The run commands' Meshcat options: the URL as soon as the viewer starts, the wait for
Enter (also with --json), and --html checked before a run."""

import argparse
import io

import pytest

from tegrasp_drake.commands.viewer_args import (check_html_path, start_viewer,
                                                wait_for_viewer, write_replay_html)


def _args(**values):
    return argparse.Namespace(**{"meshcat": False, "html": None, "json": False, **values})


def test_no_viewer_without_meshcat_or_html():
    assert start_viewer(_args()) is None


def test_meshcat_prints_its_url_on_stderr_at_once(capsys):
    meshcat = start_viewer(_args(meshcat=True))
    captured = capsys.readouterr()
    assert captured.out == ""
    assert meshcat.web_url() in captured.err


def test_html_alone_starts_a_viewer_quietly_and_writes_its_page_without_waiting(
        capsys, tmp_path, monkeypatch):
    args = _args(html=str(tmp_path / "replays" / "replay.html"))
    meshcat = start_viewer(args)
    assert capsys.readouterr().err == ""  # no URL: nobody is asked to open a browser
    stdin = io.StringIO("\n")
    monkeypatch.setattr("sys.stdin", stdin)
    wait_for_viewer(args, meshcat)
    assert stdin.tell() == 0  # --html alone does not wait for Enter
    page = write_replay_html(meshcat, args.html)
    assert page == tmp_path / "replays" / "replay.html"
    text = page.read_text()
    assert "<html" in text.lower() and "meshcat" in text.lower()


@pytest.mark.parametrize("json_output", [False, True])
def test_meshcat_waits_for_enter_even_with_json(json_output, monkeypatch, capsys):
    meshcat = start_viewer(_args(meshcat=True))
    stdin = io.StringIO("\n")
    monkeypatch.setattr("sys.stdin", stdin)
    capsys.readouterr()
    wait_for_viewer(_args(meshcat=True, json=json_output), meshcat)
    assert stdin.tell() == 1  # the Enter was read
    captured = capsys.readouterr()
    assert captured.out == ""  # stdout holds only the result (one JSON object with --json)
    assert "press Enter" in captured.err


def test_html_that_is_a_folder_stops_before_the_run(tmp_path):
    with pytest.raises(SystemExit,
                       match="--html .* is a folder where a file belongs; give a file name"):
        check_html_path(_args(html=str(tmp_path)))


def test_html_under_a_file_stops_before_the_run(tmp_path):
    (tmp_path / "a_file").write_text("")
    with pytest.raises(SystemExit, match="--html .*a_file is not a folder"):
        check_html_path(_args(html=str(tmp_path / "a_file" / "replay.html")))


class _Page:
    """A stand-in for the Meshcat whose page --html writes (a real one serves a port)."""

    @staticmethod
    def StaticHtml() -> str:
        return "<!DOCTYPE html>\n<html><body>a replay</body></html>\n"


# Rule: --html writes its page through a temporary file; what a write of that same page
# killed past its handlers (SIGKILL) left beside it, the next one removes, and only that: a
# page of the user's named like a leftover (other content) or another page's stays.
def test_an_html_write_removes_what_a_killed_write_of_that_page_left(tmp_path):
    from tests.commands.test_run_folder import _ended_process_id
    from tests.killed_runs import killed_before_rename
    target = tmp_path / "replay.html"
    killed_before_rename("from tegrasp_drake.commands.viewer_args import write_replay_html\n"
                         f"from tests.commands.test_viewer_args import _Page\n"
                         f"write_replay_html(_Page(), {str(target)!r})")
    left = sorted(tmp_path.iterdir())
    assert len(left) == 1 and not target.exists(), left  # the killed write's temporary file
    dead = _ended_process_id()
    kept = {tmp_path / f".other.html.abcd1234.{dead}.staging": b"<!DOCTYPE html>",
            tmp_path / f".replay.html.abcd1234.{dead}.staging": b"my notes"}
    for path, data in kept.items():
        path.write_bytes(data)
    write_replay_html(_Page(), target)
    assert sorted(tmp_path.iterdir()) == sorted([target, *kept])
    assert target.read_text() == _Page.StaticHtml()


def _replay_page(path, meshcat=None):
    return write_replay_html(meshcat or start_viewer(_args(html=str(path))), path)


def test_html_over_a_file_that_is_no_replay_is_refused_even_with_overwrite(tmp_path):
    notes = tmp_path / "notes.txt"
    notes.write_text("notes")
    for overwrite in (False, True):
        with pytest.raises(SystemExit, match=r"--html .*notes.txt exists and is not a replay "
                           r"page .*give another file name"):
            check_html_path(_args(html=str(notes), overwrite=overwrite))
    assert notes.read_text() == "notes"


def test_html_over_an_earlier_replay_needs_overwrite_or_the_demo(tmp_path):
    page = _replay_page(tmp_path / "replay.html")
    with pytest.raises(SystemExit, match="exists .*pass --overwrite to replace it"):
        check_html_path(_args(html=str(page), overwrite=False, replace_default_out=False))
    assert check_html_path(_args(html=str(page), overwrite=True)) == page
    assert check_html_path(_args(html=str(page), overwrite=False,
                                 replace_default_out=True)) == page


def test_a_trial_refuses_an_html_file_of_the_users_before_it_runs(tmp_path, capfd,
                                                                    monkeypatch):
    from tests.bad_input.probes import run_cli
    monkeypatch.chdir(tmp_path)
    (tmp_path / "notes.txt").write_text("notes")
    code, text = run_cli(["trial", "-q", "--html", "notes.txt", "--out", "o"], capfd)
    assert code == 1 and "--html notes.txt exists and is not a replay page" in text, text
    assert (tmp_path / "notes.txt").read_text() == "notes"
    assert not (tmp_path / "o").exists()
