"""hardware.myrio."""
