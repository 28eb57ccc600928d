"""The reports the analysis scripts (analysis/*.py) write: written whole, and a report that
cannot be written ends the script with one line naming it."""

import pathlib

from tegrasp_drake.rig.files import MARKDOWN_START, UserPathError, write_atomically


def write_report(path, text: str, *, script: str, start: bytes = MARKDOWN_START
                 ) -> pathlib.Path:
    """Writes `text` to `path` whole (rig.files.write_atomically: an earlier report stays as it
    was when it cannot) and returns `path`; SystemExit with one line, `<script>: cannot write
    <path>: <why>; <what to do>`, when it cannot. `start` is how a report of `path`'s kind
    starts (MARKDOWN_START; MARKDOWN_TABLE_START for a bare table)."""
    try:
        return write_atomically(path, text, start=start)
    except UserPathError as error:
        raise SystemExit(f"{script}: {error}") from None
