"""The 3 x 4 taxel layout of a fingertip pad, in the pad frame P (`left_pad`/`right_pad`:
origin at the contact face's centre, +z the inward normal, +x across the 20 mm width, +y
along the 24 mm length toward the fingertip). Taxel index = 3 * row + column, row 0
nearest the palm: a regular grid over the pad, like the paper's 12 electrodes (Fig. 7c).
"""

import numpy as np

# The pad's size is part of the layout's interface (contact_pressure.py reads it from here).
from tegrasp_drake.rig.tactile_fingertip import (PAD_LENGTH, PAD_WIDTH, TAXEL_COLUMNS,
                                                      TAXEL_ROWS)

COLUMNS, ROWS = TAXEL_COLUMNS, TAXEL_ROWS  # along x, along y
CELL_X = PAD_WIDTH / COLUMNS
CELL_Y = PAD_LENGTH / ROWS


def taxel_centers() -> np.ndarray:
    """Centres of the 12 taxels, p_PoTk_P, shape (12, 3) [m]."""
    rows, cols = np.divmod(np.arange(ROWS * COLUMNS), COLUMNS)
    x = (cols + 0.5) * CELL_X - PAD_WIDTH / 2
    y = (rows + 0.5) * CELL_Y - PAD_LENGTH / 2
    return np.column_stack([x, y, np.zeros_like(x)])
