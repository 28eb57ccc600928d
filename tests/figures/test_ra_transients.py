"""The first-contact RA figure (figures/ra_transients.py): written as every figure is, through
a staging file and a rename (save_figure)."""

import subprocess
import sys

from tests.killed_runs import environment, killed_before_rename
from tegrasp_drake.figures.figure_files import FIGURE_STARTS

# One synthetic strike (no simulation): 100 ms of RA at 1 kHz, each pad touching once.
_PLOT = """import numpy as np
from tegrasp_drake.figures.ra_transients import plot_ra_transients
from tegrasp_drake.runs.pad_strike import PadStrike
t = np.arange(0.0, 0.1, 1e-3)
ra = np.column_stack([np.sin(300 * t), np.cos(300 * t)])
strike = PadStrike(t_ra=t, ra=ra, pad_acceleration=ra, t_sa=t, sa=ra,
                   contact_times=np.array([0.04, 0.05]), time_step_s=1e-3)
plot_ra_transients({{1e-3: strike}}, {path!r})
"""


# Rule: a write of the figure killed past its handlers (SIGKILL) leaves the earlier figure
# whole, and the next write removes what it left beside it.
def test_a_killed_write_keeps_the_earlier_figure_and_the_next_removes_its_leftover(tmp_path):
    target = tmp_path / "ra_transients.png"
    target.write_bytes(b"\x89PNG\r\n\x1a\n the earlier figure")
    killed_before_rename(_PLOT.format(path=str(target)))
    assert target.read_bytes() == b"\x89PNG\r\n\x1a\n the earlier figure"
    subprocess.run([sys.executable, "-c", _PLOT.format(path=str(target))], env=environment(),
                   check=True, timeout=120)  # a bound on a hang, not a measure of speed
    assert sorted(tmp_path.iterdir()) == [target]
    assert target.read_bytes().startswith(FIGURE_STARTS["png"])
