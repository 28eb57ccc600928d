"""Regenerate the results page's tables from the results folders their markers name
(`<!-- results table from ../analysis/results_seed0 -->`) and name the commit of each
folder's records ("Records `analysis/results_seed0/trials`, commit `...` (date)"), after a
sweep was re-run and its records committed.

    python analysis/update_results_page.py [docs/results.md]
"""

import argparse
import pathlib
import sys

from tegrasp_drake.commands.script_output import run_script
from tegrasp_drake.rig.files import MARKDOWN_START, write_atomically
from tegrasp_drake.sweep import readme_with_summaries
from tegrasp_drake.sweep.summary import page_with_record_commits

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "results.md"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("page", nargs="?", default=str(PAGE))
    args = parser.parse_args(argv)
    path = pathlib.Path(args.page)
    text = path.read_text(encoding="utf-8")
    try:
        updated = page_with_record_commits(readme_with_summaries(text, path.parent), ROOT)
    except ValueError as e:
        print(f"{path}: {e}", file=sys.stderr)
        return 1
    if updated != text:  # a new file renamed into place: an interruption leaves the old one
        write_atomically(path, updated, start=MARKDOWN_START)
    print(f"{path}: results {'updated' if updated != text else 'unchanged'}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "update_results_page"))
