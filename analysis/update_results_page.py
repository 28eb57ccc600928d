"""Regenerate the results page's tables from the results folders their markers name
(`<!-- results table from ../analysis/results_seed0 -->`) and name the commit of each
folder's records ("Records `analysis/results_seed0/trials`, commit `...` (date)"), after a
sweep was re-run and its records committed.

    python analysis/update_results_page.py [docs/results.md]
"""

import pathlib
import sys

from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake.rig.files import MARKDOWN_START, read_bounded, write_atomically
from tegrasp_drake.sweep import readme_with_summaries
from tegrasp_drake.sweep.summary import page_with_record_commits

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "results.md"
# docs/results.md is about 41 kB; a page 100 times longer is still one to regenerate, and the
# bound stops /dev/zero or a mistaken large file before it is read whole.
MAX_PAGE_BYTES = 4_000_000


def main(argv=None) -> int:
    parser = script_parser("update_results_page", __doc__)
    # read and written again: checked as an input, then as an output, before the
    # results folders are read
    parser.add_output("page", nargs="?", default=str(PAGE),
                      reads=("results page", "give the Markdown results page, e.g. "
                                             "docs/results.md"))
    args = parser.parse_args(argv)
    path = pathlib.Path(args.page)
    try:  # a folder, FIFO or device refused before it is opened for reading (no blocking)
        text = read_bounded(path, MAX_PAGE_BYTES).decode("utf-8")
    except UnicodeDecodeError as error:
        raise SystemExit(f"update_results_page: {path}: is not UTF-8 text (byte {error.start}); "
                         "give the Markdown results page") from None
    try:
        updated = page_with_record_commits(readme_with_summaries(text, path.parent), ROOT)
    except ValueError as e:
        raise SystemExit(f"update_results_page: error: {path}: {e}") from None
    if updated != text:  # a new file renamed into place: an interruption leaves the old one
        write_atomically(path, updated, start=MARKDOWN_START)
    print(f"{path}: results {'updated' if updated != text else 'unchanged'}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "update_results_page"))
