"""Recording memorized events in simulation and measuring how well they detect their
transitions from recorded logs.

- campaign.py: one recording campaign: runs simulated, cut, combined by their mean.
- paper_events.py: the paper's events, cut from one clean ideal grasp.
- ensemble_events.py: events from an ensemble of randomised ideal grasps (taxel_aware).
- corrective_events.py: events of the corrective situations (a hit, a slip).
- detection_quality.py: detection, false triggers and latency at any Eq. 3 thresholds.
- corrective_detection.py: the same for the corrective triggers, and their threshold rule."""
