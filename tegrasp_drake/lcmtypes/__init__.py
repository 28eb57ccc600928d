"""The LCM message types of a hardware run's log (channels, rates, units: README.md here).

Generated from the .lcm files here by generate.sh (lcm-gen 1.5.3); do not edit by hand.
  lcmt_tegrasp_fault       a device fault the hardware station saw (TEGRASP_FAULT)
  lcmt_tegrasp_gripper     the 2F-85's command and status registers (TEGRASP_GRIPPER)
  lcmt_tegrasp_run_info    what the run was: scenario, controller, events (TEGRASP_RUN_INFO)
  lcmt_tegrasp_tactile     both pads as the control loop saw them (TEGRASP_TACTILE)
  lcmt_tegrasp_transition  a transition of the grasp state machine (TEGRASP_TRANSITION)
"""

from .lcmt_tegrasp_fault import lcmt_tegrasp_fault as lcmt_tegrasp_fault
from .lcmt_tegrasp_gripper import lcmt_tegrasp_gripper as lcmt_tegrasp_gripper
from .lcmt_tegrasp_run_info import lcmt_tegrasp_run_info as lcmt_tegrasp_run_info
from .lcmt_tegrasp_tactile import lcmt_tegrasp_tactile as lcmt_tegrasp_tactile
from .lcmt_tegrasp_transition import lcmt_tegrasp_transition as lcmt_tegrasp_transition
