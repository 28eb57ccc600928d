"""Runs of the grasp and their judgement: a simulated closed-loop trial (`run_trial`), the
ideal open-loop grasp (`run_ideal_grasp`), the grasp on the devices in real time
(`run_on_hardware`) and its LCM log read back and replayed, the ground-truth judge
(grasp_outcome), and the pad-strike scene of the first-contact RA transient."""
