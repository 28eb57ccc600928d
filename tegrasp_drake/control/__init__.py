"""The grasp controllers: the paper's state machine as a rule table, its corrective
actions, the taxel-aware extension and the open-loop script.

  controller_registry.py       one entry per controller: everything "which controller?"
  controller_config.py         the controllers' settings, one config class each
  grasp_controller.py          builders that add a controller's systems to a diagram
  grasp_state_machine.py       GraspStateMachine, the LeafSystem that runs a rule table
  machine_state.py             what the state machine remembers and the plan it follows
  grasp_modes.py               modes, triggers, decisions and timeline entries
  rule_engine.py               rules, guards and rule tables
  rule_actions.py              the actions a rule decides (ReReach, Load, Lift, ...)
  transition_logic.py          the paper's rule table and the tick's Observation
  corrective_actions.py        Re-Reach, Lift-Load and Avoid as pure functions
  rule_docs.py                 the docs' rule tables, generated from the engine
  fixed_load_time.py           the example controller: Lift after a fixed Load time
  heuristic_event_detector.py  the heuristic controller's threshold triggers
  noise_thresholds.py          thresholds raised to the channels' noise
  taxel_contact.py             where a contact sits on the pads, from the taxels
  finger_strike.py             a finger striking the object, from the joint torques
  grasp_wrench_estimator.py    the wrench at the grasp frame from the joint torques
  scripted_grasp.py            the ideal open-loop grasp (Sec. III-A)
  motion_profiles.py           minimum-jerk moves
  cartesian_arm_controller.py  the grasp frame's pose to joint commands (diff IK)
  taxel_aware/                 the taxel-aware controller's rules and estimator"""
