"""Regenerate the README's results table from the results folder its marker names
(`<!-- results table from analysis/results_seed0 -->`), after a sweep was re-run there.

    python analysis/update_readme_results.py [README.md]
"""

import argparse
import pathlib
import sys

from tegrasp_drake.experiments.sweep import readme_with_summaries

README = pathlib.Path(__file__).resolve().parent.parent / "README.md"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("readme", nargs="?", default=str(README))
    args = parser.parse_args(argv)
    path = pathlib.Path(args.readme)
    text = path.read_text(encoding="utf-8")
    try:
        updated = readme_with_summaries(text, path.parent)
    except ValueError as e:
        print(f"{path}: {e}", file=sys.stderr)
        return 1
    path.write_text(updated, encoding="utf-8")
    print(f"{path}: results table {'updated' if updated != text else 'unchanged'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
