"""The Meshcat options of the run commands (trial, demo): `--meshcat` serves the run live
(its URL printed on stderr; at the end the command waits for Enter), `--html FILE` writes
the run's recording as one standalone HTML file (Meshcat.StaticHtml: no server, no network)."""

import pathlib
import sys

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.rig.files import (existing_file_head, output_file_problem, write_atomically,
                                     os_error_text)

HTML_START = b"<!DOCTYPE html>"  # how Meshcat.StaticHtml's page starts (an HTML5 document)
REPLAY_TITLE = b"<title>Drake MeshCat</title>"  # in that page's head, within its first kB


def add_viewer_arguments(parser) -> None:
    parser.add_argument("--meshcat", action="store_true",
                        help="show the run live in Meshcat: prints the URL as soon as the "
                             "viewer starts; at the end replays the recording there and waits "
                             "for Enter")
    parser.add_argument("--html", metavar="FILE", default=None,
                        help="write the run as a standalone HTML replay (3D scene, contact "
                             "and taxel forces, animation) that opens offline in any browser")


def check_html_path(args) -> pathlib.Path | None:
    """--html as a Path, checked before the run: exits naming the problem."""
    if args.html is None:
        return None
    path = pathlib.Path(args.html)
    problem = output_file_problem(path) or _replacing_problem(path, args)
    if problem:
        raise SystemExit(f"{ERROR_LEAD}--html {path} {problem}, e.g. replay.html")
    return path


def _replacing_problem(path: pathlib.Path, args) -> str | None:
    """Why an existing `path` may not be replaced by the run's page, or None: only a replay
    page (a Meshcat StaticHtml head) is replaced, and only with --overwrite, or by `tegrasp
    demo`, which replaces its last run."""
    if not path.exists():
        return None
    try:  # the head only: a huge file is no page of ours, and is not read
        head = existing_file_head(path, 1024) or b""
    except OSError as e:
        return f"cannot be read to check what it is ({os_error_text(e)}); give another file name"
    if not (head.startswith(HTML_START) and REPLAY_TITLE in head):
        return ("exists and is not a replay page (no Meshcat page head in its first kB); "
                "give another file name, or remove it yourself")
    if not (getattr(args, "overwrite", False) or getattr(args, "replace_default_out", False)):
        return "exists (an earlier replay); pass --overwrite to replace it, or give a new file name"
    return None


def start_viewer(args):
    """A Meshcat for --meshcat or --html (None without either); prints its URL for --meshcat."""
    if not (args.meshcat or args.html):
        return None
    from pydrake.geometry import Meshcat
    meshcat = Meshcat()
    if args.meshcat:
        print(f"Meshcat: open {meshcat.web_url()} to watch the run", file=sys.stderr,
              flush=True)
    return meshcat


def write_replay_html(meshcat, path) -> pathlib.Path:
    """Writes the Meshcat's scene and published recording as one HTML file, atomically; what a
    write of this page killed by SIGKILL left beside it is removed first."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_atomically(path, meshcat.StaticHtml(), start=HTML_START)


def wait_for_viewer(args, meshcat) -> None:
    """With --meshcat, keeps the viewer up until Enter (prompt on stderr), or until standard
    input ends: at once when there is none (closed, as under cron or `<&-`; at its end, as
    /dev/null; a terminal that hung up)."""
    if meshcat is None or not args.meshcat:
        return
    if sys.stdin is None:  # Python's stand-in for a closed file descriptor 0
        print(f"Meshcat at {meshcat.web_url()}: standard input is closed, so the viewer "
              "closes now (--html FILE keeps the recording)", file=sys.stderr, flush=True)
        return
    print(f"Meshcat at {meshcat.web_url()}: the recording replays there (its controls: "
          "Animations); press Enter to quit.", file=sys.stderr, flush=True)
    try:
        sys.stdin.readline()
    except (OSError, ValueError):  # a terminal that hung up (EIO); a stream closed meanwhile
        pass
