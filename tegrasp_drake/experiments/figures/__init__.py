"""experiments.figures."""
