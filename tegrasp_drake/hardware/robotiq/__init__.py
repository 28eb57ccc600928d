"""hardware.robotiq."""
