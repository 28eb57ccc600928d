"""tegrasp-drake: tactile-event grasping with memorized triggers on Drake.

A Python implementation of Kim and Kim, "Tactile Event Based Grasping Algorithm using
Memorized Triggers and Mechanoreceptive Sensors", on Drake's systems framework.
"""

__version__ = "0.1.0"
