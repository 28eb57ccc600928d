"""The 2F-85's dimensions that the hand models and the arm's grasp frame share [m].

Base frame as in the model generators (modelgen/robotiq_sdf.py): origin at the mounting
face, +z out of the gripper along the approach axis, y along the stroke.

- PAD_CENTER_Z: the grasp frame G's height above the mounting face, at the centre of the
  pads of the prismatic hand. The datasheet puts the fingertip about 0.16 m from the
  coupling; the 24 mm pad (rig/tactile_fingertip.py) centred 140 mm out ends 8 mm short of
  it. The linkage hand puts its grasp frame here too, so both hands and the arm's IK
  (rig/arm_kinematics.py) meet the object at the same point.
- HALF_STROKE: a pad face's distance from the grasp axis with the gripper open, half the
  datasheet's 85 mm stroke (units.STROKE_M).
"""

from tegrasp_drake.robotiq.units import STROKE_M

PAD_CENTER_Z = 0.140
HALF_STROKE = STROKE_M / 2
