"""The 2F-85's dimensions that the hand models and the arm's grasp frame share [m], in the
model generators' base frame (origin at the mounting face, +z along the approach axis, y
along the stroke). Both hands and the arm's IK meet the object at the same point.
"""

from tegrasp_drake.robotiq.units import STROKE_M

# The grasp frame G above the mounting face, at the prismatic hand's pad centres: the
# datasheet's fingertip is ~0.16 m out; a 24 mm pad (rig/tactile_fingertip.py) centred here
# ends 8 mm short of it.
PAD_CENTER_Z = 0.140
HALF_STROKE = STROKE_M / 2  # a pad face from the grasp axis, open
