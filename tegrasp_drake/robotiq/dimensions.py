"""The 2F-85's dimensions the hand models and the arm's grasp frame share [m], in the base
frame (origin at the mounting face, +z along the approach, y along the stroke)."""

from tegrasp_drake.robotiq.units import STROKE_M

# G at the prismatic pads' centres: a 24 mm pad here ends 8 mm short of the datasheet's
# ~0.16 m fingertip
PAD_CENTER_Z = 0.140
HALF_STROKE = STROKE_M / 2  # a pad face from the grasp axis, open
PALM_Z = 0.095  # mounting face to palm; both hand models' palm box ends here
