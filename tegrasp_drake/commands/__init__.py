"""Sub-commands of the tegrasp command line, one module each."""
