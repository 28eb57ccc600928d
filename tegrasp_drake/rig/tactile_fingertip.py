"""The paper's tactile fingertip (Sec. IV-A, Fig. 7c): the one source of its dimensions, from
which the gripper model makes the pad's collision box and rig/taxel_layout.py its 12
electrodes, so sensing area and contact geometry agree. The paper gives no dimensions; the
reasoning: docs/model.md, "The fingertip and its taxels".
"""

# [m] along the approach axis (pad frame y, rows): holds the contact line through the paper's
# +-1 cm misplacement normal to the palm (Sec. IV-B) with 2 mm margin: 2 x (10 + 2) mm.
PAD_LENGTH = 0.024
# [m] across (pad frame x, columns): 3 electrodes at the 6-7 mm pitch of AD7147 arrays; fits
# the 2F-85 finger, about 22 mm wide.
PAD_WIDTH = 0.020
PAD_THICKNESS = 0.004  # m, the paper's elastomer under conductive fabric
# 12 electrodes (Fig. 7c), one per AD7147 conversion stage: 4 rows along PAD_LENGTH (row 0
# nearest the palm) by 3 columns, each 6.0 x 6.7 mm.
TAXEL_ROWS = 4
TAXEL_COLUMNS = 3
