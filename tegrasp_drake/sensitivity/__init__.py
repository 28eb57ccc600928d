"""How much the guesses matter: the scenario settings nobody published, each swept over its
plausible range (docs/model.md, "What was guessed"; docs/sweeps.md, "How much the guesses
matter").

- parameters.py: the uncertain parameters, their ranges and sources (the docs' table).
- study.py: the sensitivity spec, its points (one factor at a time, or a Latin hypercube),
  each point a world of the transfer machinery run as resumable sweeps.
- report.py: misplaced hold and placed rates per point, the tornado chart, the failure
  classes at each end."""
