"""analysis/update_results_page.py: the results page is rewritten through a staging file and
a rename, and what a rewrite killed past its handlers left the next one removes."""

import subprocess
import sys

from tests.killed_runs import REPOSITORY, environment, killed_before_rename
from tests.sweep.test_summary import records
from tegrasp_drake.sweep.records import write_record

_PAGE = ("# Results\n\n<!-- results table from results -->\nan old table\n"
         "<!-- end of results table -->\n")


def test_a_killed_rewrite_keeps_the_page_and_the_next_removes_its_leftover(tmp_path):
    for record in records(objects=("box",)):
        write_record(tmp_path / "results", record)
    page = tmp_path / "results.md"
    page.write_text(_PAGE)
    statements = ("import runpy, sys\n"
                  f"sys.argv = ['update_results_page.py', {str(page)!r}]\n"
                  f"runpy.run_path({str(REPOSITORY / 'analysis' / 'update_results_page.py')!r}, "
                  "run_name='__main__')")
    killed_before_rename(statements)
    assert page.read_text() == _PAGE
    subprocess.run([sys.executable, "-c", statements], env=environment(), check=True,
                   stdout=subprocess.DEVNULL, timeout=120)  # a bound on a hang
    assert sorted(path.name for path in tmp_path.iterdir()) == ["results", "results.md"]
    assert "an old table" not in page.read_text()
