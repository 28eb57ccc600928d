"""experiments.benchmarks."""
