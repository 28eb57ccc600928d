"""The paper's tactile fingertip (Sec. IV-A, Fig. 7c): the one source of its dimensions.

The gripper model (robotiq_sdf.py) makes the pad's collision box from these numbers and the
taxel layout (rig/taxel_layout.py) divides the same area into the 12 electrodes, so the
sensing area and the contact geometry cannot disagree.

The paper gives no dimensions. What it gives:
- 12 capacitive electrodes (Fig. 7c) read by one AD7147, whose 12 conversion stages match
  them one to one. Laid out as 4 rows along the approach axis by 3 columns across it.
- The misplacement normal to the palm, +-1 cm, was "set by considering the ... dimensions of
  the tactile sensor" (Sec. IV-B). At the nominal grasp the object's contact line lies on the
  sensor's centre (the row boundary 1|2), so the sensing length along the approach axis must
  hold that line 1 cm either way with a margin: 2 x (10 + 2) mm = 24 mm. (The previous
  38 mm pad would have allowed +-1.9 cm, and the paper would then have chosen more.)
- Across the pad (vertical in the side grasp) 3 columns of electrodes at about the 6-7 mm
  pitch typical of AD7147 electrode arrays: 20 mm, which also fits the 2F-85 finger, about
  22 mm wide.
So an electrode is 6.0 mm (along the approach axis) x 6.7 mm (across).

The pad is the paper's elastomer under conductive fabric: 4 mm thick, as before.
"""

PAD_LENGTH = 0.024  # m, along the approach axis (the pad frame's y, rows)
PAD_WIDTH = 0.020  # m, across the pad (the pad frame's x, columns)
PAD_THICKNESS = 0.004  # m, elastomer and fabric
TAXEL_ROWS = 4  # along PAD_LENGTH, row 0 nearest the palm
TAXEL_COLUMNS = 3  # along PAD_WIDTH
