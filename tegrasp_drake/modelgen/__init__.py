"""Generators for the SDF models in models/ (run `python -m tegrasp_drake.modelgen`)."""
