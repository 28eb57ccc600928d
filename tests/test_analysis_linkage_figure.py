"""analysis/linkage_figure.py: the finger linkage figure is written as every figure is
(save_figure), in the format its file name says."""

import subprocess
import sys

import pytest

from tests.killed_runs import REPOSITORY, environment
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS, FIGURE_STARTS

SCRIPT = REPOSITORY / "analysis" / "linkage_figure.py"


def _draw(out):
    return subprocess.run([sys.executable, str(SCRIPT), str(out)], env=environment(),
                          capture_output=True, text=True, timeout=120)  # a bound on a hang


@pytest.mark.parametrize("figure_format", FIGURE_FORMATS)
def test_the_figure_is_written_in_the_format_its_name_says_and_nothing_else(tmp_path,
                                                                           figure_format):
    target = tmp_path / f"finger_linkage.{figure_format}"
    done = _draw(target)
    assert done.returncode == 0, done.stderr
    assert sorted(tmp_path.iterdir()) == [target]
    assert target.read_bytes().startswith(FIGURE_STARTS[figure_format])


def test_a_name_of_no_figure_format_is_refused_in_one_line(tmp_path):
    done = _draw(tmp_path / "finger_linkage.jpg")
    assert done.returncode == 1
    assert "must end in one of .png, .pdf, .svg" in done.stderr.splitlines()[-1]
    assert list(tmp_path.iterdir()) == []
