"""hardware.jaco."""
