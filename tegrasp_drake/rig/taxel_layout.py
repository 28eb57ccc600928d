"""The 3 x 4 taxel layout of a fingertip pad, in the pad frame P.

Pad frame P (frames `left_pad` / `right_pad` of the gripper model): origin at the centre of
the pad's contact surface, +z the inward normal (toward the object), +x across the pad's
20 mm width, +y along its 24 mm length toward the fingertip (on both pads). Taxel index =
3 * row + column, row 0..3 along +y (row 0 nearest the palm), column 0..2 along +x. Each
taxel is one cell of a regular 3 x 4 grid covering the pad, like the 12 electrodes of the
paper's Fig. 7c; the sizes are the gripper model's own (rig/tactile_fingertip.py).
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
