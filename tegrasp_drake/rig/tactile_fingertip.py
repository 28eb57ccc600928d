"""The paper's tactile fingertip (Sec. IV-A, Fig. 7c): the one source of its dimensions, for the
pad's collision box and its 12 electrodes alike (docs/model.md, "The fingertip and its taxels")."""

# [m] along the approach (pad y): the paper's +-1 cm misplacement plus 2 mm, 2 x (10 + 2) mm
PAD_LENGTH = 0.024
# [m] across (pad x): 3 electrodes at the AD7147 arrays' 6-7 mm pitch, within the 22 mm finger
PAD_WIDTH = 0.020
PAD_THICKNESS = 0.004  # m, the paper's elastomer under conductive fabric
# 12 electrodes (Fig. 7c), one per AD7147 stage: 4 rows (row 0 at the palm) x 3 columns
TAXEL_ROWS = 4
TAXEL_COLUMNS = 3
