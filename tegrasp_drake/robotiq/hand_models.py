"""The names of the simulated 2F-85 hand models (`gripper.model`), plain Python so that a
rule table can name the hands it applies on without loading Drake; what each hand is:
simulation/gripper_hands.py."""

LINKAGE = "linkage"  # the 2F-85's five-bar fingers (the default)
PRISMATIC = "prismatic"  # two translating fingers, the idealised hand
GRIPPER_MODELS = (LINKAGE, PRISMATIC)
