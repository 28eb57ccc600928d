"""Runs of the grasp and their judgement.

- trial.py: run_trial, a simulated closed-loop trial, judged.
- ideal_grasp.py: run_ideal_grasp, the scripted open-loop grasp (Sec. III-A).
- hardware_run.py: run_on_hardware, the grasp on the devices in real time, logged.
- hardware_log_reader.py: a hardware run's LCM log read back.
- tactile_log_columns.py: that log's tactile messages decoded straight into arrays.
- hardware_log_replay.py: the event matcher re-run on that log.
- pad_strike.py: the pad-strike scene of the first-contact RA transient."""
