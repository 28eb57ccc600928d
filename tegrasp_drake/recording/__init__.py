"""Recording memorized events in simulation (the paper's one clean ideal grasp, the
randomised ensemble, the corrective situations) and measuring, from recorded logs, how
well they detect their transitions at given Eq. 3 thresholds."""
