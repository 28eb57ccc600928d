#!/bin/sh
# Regenerates the Python LCM types from the .lcm files here (lcm-gen from the lcm package),
# and gives the generated package's __init__.py a map of its modules in place of lcm-gen's
# own docstring.
set -e
cd "$(dirname "$0")"
out=$(mktemp -d)
lcm-gen --python --ppath "$out" *.lcm
cp "$out"/tegrasp/*.py .
rm -r "$out"
version=$(lcm-gen --version | head -n 1)
imports=$(grep '^from ' __init__.py)
cat > __init__.py <<MAP
"""The LCM message types of a hardware run's log (channels, rates, units: README.md here).

Generated from the .lcm files here by generate.sh ($version); do not edit by hand.
  lcmt_tegrasp_fault       a device fault the hardware station saw (TEGRASP_FAULT)
  lcmt_tegrasp_gripper     the 2F-85's command and status registers (TEGRASP_GRIPPER)
  lcmt_tegrasp_run_info    what the run was: scenario, controller, events (TEGRASP_RUN_INFO)
  lcmt_tegrasp_tactile     both pads as the control loop saw them (TEGRASP_TACTILE)
  lcmt_tegrasp_transition  a transition of the grasp state machine (TEGRASP_TRANSITION)
"""

$imports
MAP
